#include "estimate/window/dolly_or_zoom.h"

#include <algorithm>
#include <cmath>

namespace hapcine {

double DepthRelief(const std::vector<Eigen::Vector3d>& xyw) {
  std::vector<double> w;
  for (const auto& v : xyw)
    if (std::isfinite(v.z())) w.push_back(v.z());
  if (w.empty()) return 0;
  std::sort(w.begin(), w.end());
  const double median = w[w.size() / 2];
  if (!(median > 0)) return 0;
  return (w[w.size() * 9 / 10] - w[w.size() / 10]) / median;
}

std::vector<MotionModel> DollyLabels(const std::vector<WindowKeyframe>& keyframes) {
  const int n = static_cast<int>(keyframes.size());
  std::vector<MotionModel> labels(n);
  bool zooms = false;
  for (int i = 0; i < n; ++i) {
    const WindowKeyframe& k = keyframes[i];
    labels[i] = k.model;
    if (i == 0) continue;
    if (HasTranslation(k.model)) return {};
    if (k.fixed || k.chain_start || k.model == MotionModel::kStatic) continue;
    zooms |= HasZoom(k.model);
    labels[i] = MotionModel::kGeneral;
  }
  if (!zooms) return {};
  return labels;
}

std::vector<BaCamera> DollyStart(const std::vector<BaCamera>& shared, const std::vector<BaCamera>& zoom, int held,
                                 double depth) {
  std::vector<BaCamera> out = shared;
  const int n = static_cast<int>(std::min(shared.size(), zoom.size()));
  if (held < 0 || held >= n) return out;
  const BaCamera& pivot = zoom[held];
  for (int k = held + 1; k < n; ++k) {
    if (zoom[k].rotation_source >= 0) out[k].rotation_source = zoom[k].rotation_source;
    const double travel = depth * (1 - std::exp(pivot.log_focal - zoom[k].log_focal));
    out[k].world_from_cam = zoom[k].world_from_cam;
    out[k].center = pivot.center + travel * (zoom[k].world_from_cam * Eigen::Vector3d::UnitZ());
    out[k].log_focal = pivot.log_focal;
  }
  return out;
}

int DollyExtraParameters(const std::vector<MotionModel>& zoom_labels, const std::vector<MotionModel>& dolly_labels,
                         const std::vector<BaObservation>& observations) {
  const int n = static_cast<int>(std::min(zoom_labels.size(), dolly_labels.size()));
  int k = 0;
  // translating_before[i]: intervals that gain a translation, ending at cameras < i.
  std::vector<int> translating_before(n + 1, 0);
  for (int i = 0; i < n; ++i) {
    const MotionModel a = zoom_labels[i], b = dolly_labels[i];
    const bool gains_translation = i > 0 && HasTranslation(b) && !HasTranslation(a);
    if (i > 0) k += 3 * gains_translation - (HasZoom(a) && !HasZoom(b));
    translating_before[i + 1] = translating_before[i] + gains_translation;
  }
  // Points seen on both sides of a translating interval get a depth.
  int points = 0;
  for (const BaObservation& o : observations) points = std::max(points, o.point + 1);
  std::vector<int> first(points, n), last(points, -1);
  for (const BaObservation& o : observations) {
    if (o.camera < 0 || o.camera >= n) continue;
    first[o.point] = std::min(first[o.point], o.camera);
    last[o.point] = std::max(last[o.point], o.camera);
  }
  bool any_translation = false;
  for (int p = 0; p < points; ++p)
    if (last[p] > first[p] && translating_before[last[p] + 1] > translating_before[first[p] + 1]) ++k;
  for (int i = 1; i < n; ++i) any_translation |= HasTranslation(dolly_labels[i]) && !HasTranslation(zoom_labels[i]);
  return any_translation ? k - 1 : k;  // the scale of a translation is not observed
}

}  // namespace hapcine
