#pragma once
// Level-of-detail curves for the studio's timeline: a two-hour film has
// 720 000 actuator samples per axis at 100 Hz, the timeline a few thousand
// pixels. Each series keeps a pyramid of min/max/mean blocks (4, 16, 64, ...
// samples), built once; a query of any time range in N buckets then costs
// O(N log n) and every bucket's min/max is exact: it bounds every raw sample
// whose time lies in the bucket.

#include <string>
#include <vector>

namespace hapcine::studio {

// One series: min, max and mean per bucket.
struct BucketValues {
  std::vector<float> min, max, mean;
};

// A series over the sample times of its group (CurveGroup).
class CurvePyramid {
 public:
  explicit CurvePyramid(std::vector<float> values);
  size_t size() const { return values_.size(); }
  // min/max/mean of the samples [first, last) (last > first).
  void Aggregate(size_t first, size_t last, float* min, float* max, double* mean) const;
  float value(size_t i) const { return values_[i]; }

 private:
  struct Block {
    float min, max, mean;
  };
  std::vector<float> values_;
  std::vector<std::vector<Block>> levels_;  // levels_[k]: blocks of 4^(k+1) samples
};

// Series sharing one increasing time axis (the camera frames, or the haptic
// track's samples).
struct CurveGroup {
  std::vector<double> time_s;
  std::vector<std::string> names;
  std::vector<CurvePyramid> series;  // one per name, each of time_s.size() values
};

// The answer to one query: bucket centres and, per series name, its buckets.
struct CurveBuckets {
  double from_s = 0, to_s = 0;
  std::vector<double> centre_s;
  std::vector<std::string> names;
  std::vector<BucketValues> values;  // parallel to names
};

// Buckets of equal width over [from_s, to_s]: at most max_buckets, and no
// more than the densest group has samples in the range (at least 1). A bucket
// holding no sample of a group takes that group's series interpolated at the
// bucket centre (min = max = mean), so every series is defined everywhere.
CurveBuckets QueryCurves(const std::vector<const CurveGroup*>& groups, double from_s, double to_s,
                         int max_buckets);

// {"from","to","t":[...],"series":{name:{"min":[],"max":[],"mean":[]}}},
// numbers in their shortest round-trip text (floats).
std::string CurveBucketsToJson(const CurveBuckets& buckets);

}  // namespace hapcine::studio
