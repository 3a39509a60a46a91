#pragma once
// Reproducible randomisation for the study plan. std::shuffle and
// std::uniform_int_distribution are implementation-defined, so a plan made
// with one standard library could not be re-derived with another; here both
// the engine (std::mt19937_64, fully specified) and the bounded draw and
// Fisher–Yates shuffle are our own.

#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace hapcine::study {

// SplitMix64 finaliser: a well-mixed 64-bit function of its input.
uint64_t SplitMix64(uint64_t x);
// The per-participant seed: a function of the plan seed and the participant's
// 1-based number only, so adding participants never changes earlier ones.
uint64_t ParticipantSeed(uint64_t plan_seed, int participant_number);

class StudyRng {
 public:
  explicit StudyRng(uint64_t seed) : engine_(seed) {}
  // Uniform in [0, n), n >= 1, by rejection (no modulo bias).
  uint64_t Below(uint64_t n);
  template <typename T>
  void Shuffle(std::vector<T>& v) {
    for (size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[Below(i)]);
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace hapcine::study
