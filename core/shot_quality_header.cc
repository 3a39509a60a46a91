#include "core/shot_quality_header.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/csv.h"
#include "core/error.h"

namespace hapcine {
namespace {

constexpr const char* kKeyPrefix = "shot_quality.";

// The whole of `text` as an int (no sign but '-', no blanks, no fraction,
// within int); nullopt otherwise: converting the rest would be undefined or
// a guess.
std::optional<int> CheckedInt(const std::string& text) {
  int v = 0;
  const char* end = text.data() + text.size();
  const auto [at, error] = std::from_chars(text.data(), end, v);
  if (error != std::errc() || at != end) return std::nullopt;
  return v;
}

// A frame index or a count: CheckedInt and not negative.
std::optional<int> CheckedCount(const std::string& text) {
  const std::optional<int> v = CheckedInt(text);
  return v && *v >= 0 ? v : std::nullopt;
}

// The whole of `text` as a finite double.
std::optional<double> CheckedDouble(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::optional<bool> CheckedFlag(const std::string& text) {
  if (text == "0" || text == "1") return text == "1";
  return std::nullopt;
}

// `*field` = `parsed` when the text was well formed; left as it was otherwise.
template <typename T, typename U>
void SetIfValid(const std::optional<U>& parsed, T* field) {
  if (parsed) *field = *parsed;
}

void ReadField(const std::string& name, const std::string& text, ShotQuality* q) {
  if (name == "first") SetIfValid(CheckedCount(text), &q->first_frame);
  else if (name == "last") SetIfValid(CheckedCount(text), &q->last_frame);
  else if (name == "frames") SetIfValid(CheckedCount(text), &q->frames);
  else if (name == "lost") SetIfValid(CheckedCount(text), &q->lost);
  else if (name == "median_confidence") SetIfValid(CheckedDouble(text), &q->median_confidence);
  else if (name == "inlier_ratio") SetIfValid(CheckedDouble(text), &q->inlier_ratio);
  else if (name == "rms_px") SetIfValid(CheckedDouble(text), &q->rms_px);
  else if (name == "focal_observable") SetIfValid(CheckedFlag(text), &q->focal_observable);
  else if (name == "zoom_ambiguous") SetIfValid(CheckedCount(text), &q->zoom_ambiguous);
  else if (name == "ambiguous_zoom_kept") SetIfValid(CheckedCount(text), &q->ambiguous_zoom_kept);
  else if (name == "border_support")
    SetIfValid(CheckedDouble(text), &q->border_support);
  else if (name == "still_border")
    SetIfValid(CheckedFlag(text), &q->still_border);
  else if (name == "doubtful") SetIfValid(CheckedFlag(text), &q->doubtful);
}

}  // namespace

void WriteShotQuality(const std::vector<ShotQuality>& shots, CameraPath* path) {
  for (const ShotQuality& q : shots) {
    std::ostringstream v;
    v << "first:" << q.first_frame << " last:" << q.last_frame << " frames:" << q.frames << " lost:" << q.lost
      << " median_confidence:" << FormatFixed(q.median_confidence, 3);
    if (q.inlier_ratio) v << " inlier_ratio:" << FormatFixed(*q.inlier_ratio, 3);
    if (q.rms_px) v << " rms_px:" << FormatFixed(*q.rms_px, 3);
    if (q.focal_observable) v << " focal_observable:" << (*q.focal_observable ? 1 : 0);
    if (q.zoom_ambiguous) v << " zoom_ambiguous:" << *q.zoom_ambiguous;
    if (q.zoom_ambiguous.value_or(0) > 0 && q.ambiguous_zoom_kept)
      v << " ambiguous_zoom_kept:" << *q.ambiguous_zoom_kept;
    if (q.border_support) v << " border_support:" << FormatFixed(*q.border_support, 3);
    if (q.still_border) v << " still_border:1";
    v << " doubtful:" << (q.doubtful ? 1 : 0);
    path->metadata[kKeyPrefix + std::to_string(q.shot)] = v.str();
  }
}

std::vector<ShotQuality> ReadShotQuality(const CameraPath& path) {
  std::vector<ShotQuality> out;
  const std::string prefix = kKeyPrefix;
  for (const auto& [key, value] : path.metadata) {
    if (key.rfind(prefix, 0) != 0) continue;
    const std::optional<int> shot = CheckedInt(key.substr(prefix.size()));
    if (!shot) continue;
    ShotQuality q;
    q.shot = *shot;
    std::istringstream in(value);
    for (std::string field; in >> field;) {
      const size_t colon = field.find(':');
      if (colon != std::string::npos) ReadField(field.substr(0, colon), field.substr(colon + 1), &q);
    }
    out.push_back(q);
  }
  std::sort(out.begin(), out.end(), [](const ShotQuality& a, const ShotQuality& b) { return a.shot < b.shot; });
  return out;
}

std::vector<ShotQuality> ReadShotQualityOfFile(const std::string& camera_csv) {
  std::ifstream in(camera_csv);
  CsvReader csv(in, camera_csv);
  try {
    csv.ReadPreamble();
  } catch (const Error&) {
    // No column row (or no file): the header lines read so far, if any, are
    // all there is; the rows are not this reader's business.
  }
  CameraPath header;
  header.metadata = csv.metadata();
  return ReadShotQuality(header);
}

ShotQualityCounts CountShotQuality(const std::vector<ShotQuality>& shots) {
  ShotQualityCounts c;
  long long lost = 0;  // each count is an int; their sum may not be
  for (const ShotQuality& q : shots) {
    c.doubtful += q.doubtful ? 1 : 0;
    c.zoom_ambiguous += q.zoom_ambiguous.value_or(0) > 0 ? 1 : 0;
    lost += q.lost;
  }
  c.shots = static_cast<int>(shots.size());
  c.lost_frames = static_cast<int>(std::min<long long>(lost, std::numeric_limits<int>::max()));
  return c;
}

}  // namespace hapcine
