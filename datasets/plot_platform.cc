#include "datasets/plot_platform.h"

#include "core/error.h"
#include "core/rotation.h"

namespace hapcine {
namespace {

void AddSeries(PlotPanel* panel, const std::string& name, const std::vector<double>& t,
               std::vector<double> v, int color, bool dashed) {
  PlotSeries s;
  s.name = name;
  s.x = t;
  s.y = std::move(v);
  s.color = PaletteColor(color);
  s.dashed = dashed;
  panel->series.push_back(std::move(s));
}

// The pose panels of one track: DOFs the platform does not have (all zero)
// are left out, so a 3-DOF seat shows heave, pitch and roll only.
void AddPoseSeries(const PlatformTrack& track, const std::string& suffix, bool dashed,
                   const std::vector<double>& t, PlotPanel* translation, PlotPanel* rotation) {
  const char* names[kNumDofs] = {"sway x", "heave y", "surge z", "pitch", "yaw", "roll"};
  for (int d = 0; d < kNumDofs; ++d) {
    std::vector<double> v;
    bool moves = false;
    for (const auto& s : track.samples) {
      v.push_back(IsRotation(d) ? RadToDeg(s.pose[d]) : 1000.0 * s.pose[d]);
      moves |= s.pose[d] != 0;
    }
    if (!moves) continue;
    AddSeries(IsRotation(d) ? rotation : translation, names[d] + suffix, t, std::move(v), d, dashed);
  }
}

void AddLegSeries(const PlatformTrack& track, const std::string& suffix, bool dashed,
                  const std::vector<double>& t, PlotPanel* legs) {
  const auto& first = track.samples.front().legs;
  if (!first) return;
  for (int i = 0; i < 6; ++i) {
    std::vector<double> v;
    for (const auto& s : track.samples) v.push_back(s.legs ? 1000.0 * ((*s.legs)[i] - (*first)[i]) : 0.0);
    AddSeries(legs, "leg " + std::to_string(i + 1) + suffix, t, std::move(v), i, dashed);
  }
}

}  // namespace

Figure PlatformTracksFigure(const std::vector<const PlatformTrack*>& tracks,
                            const std::string& title, const std::vector<std::string>& names) {
  if (tracks.empty()) throw UsageError("no platform track to plot");
  for (const PlatformTrack* track : tracks) {
    if (!track || track->samples.empty()) throw UsageError("platform track has no samples");
  }
  Figure fig;
  fig.title = title;
  PlotPanel translation, rotation, legs;
  translation.title = "translation (sway x right, heave y up, surge z backward)";
  translation.y_label = "mm";
  rotation.title = "rotation (pitch: front up, yaw: turning left, roll: right side up)";
  rotation.y_label = "deg";
  legs.title = "Stewart legs: extension from the first sample";
  legs.y_label = "mm";
  for (size_t n = 0; n < tracks.size(); ++n) {
    const PlatformTrack& track = *tracks[n];
    const std::string name = n < names.size() ? names[n] : track.platform;
    const std::string suffix = tracks.size() > 1 ? " (" + name + ")" : "";
    std::vector<double> t;
    for (const auto& s : track.samples) t.push_back(s.time_s);
    AddPoseSeries(track, suffix, n > 0, t, &translation, &rotation);
    AddLegSeries(track, suffix, n > 0, t, &legs);
  }
  for (PlotPanel* p : {&translation, &rotation, &legs}) {
    if (!p->series.empty()) fig.panels.push_back(std::move(*p));
  }
  if (fig.panels.empty()) {  // a platform that never moves: one flat panel
    translation = PlotPanel();
    translation.title = "translation";
    translation.y_label = "mm";
    std::vector<double> t;
    for (const auto& s : tracks[0]->samples) t.push_back(s.time_s);
    AddSeries(&translation, "home", t, std::vector<double>(t.size(), 0.0), 0, false);
    fig.panels.push_back(std::move(translation));
  }
  return fig;
}

}  // namespace hapcine
