#pragma once
// How far to trust each shot of an estimated camera path: a per-shot
// summary written in the path's header (`# shot_quality.<shot>=...`,
// docs/formats.md), in the --report file and as one warning line per
// doubtful shot by `hapcine estimate`. The struct and the header lines' text:
// core/shot_quality_header.h.
//
// Doubtful (the rule, docs/estimate.md "Shot quality"): more than 5 % of
// the shot's frames lost (one frame in twenty has no pose), or a median
// confidence below 0.12, i.e. more than half its frames are weak. A frame
// whose tracks are all inliers with a small RMS gets 0.3 at the floor of
// track quality, 0.24 with the focal unobserved (what the synthetic suite's
// clean shots get: medians 0.21-0.91); below half of that, the inlier share
// times the RMS likelihood exp(-0.5 (rms / 2 px)^2) is under 1/2: half the
// tracks disagree with the pose, or the RMS exceeds 2.35 px (1.2 sigma of
// the confidence's noise model). Or the camera's motion unconfirmed (and
// not read as a subject's before a still border, ShotQuality::still_border):
// a median border support (core/shot_quality_header.h,
// estimate/geometry/border_support.h) below one half, the motion's inliers
// reaching fewer than half the frame's edge cells in most of the shot's
// intervals. The background surrounds a subject; a motion it does not
// confirm may be the subject's own (a face filling the frame over a dark,
// defocused background), which the border rule (motion_hypotheses.h)
// cannot tell without background tracks.

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/camera_path.h"
#include "core/shot_quality_header.h"
#include "estimate/geometry/border_support.h"
#include "estimate/window/window_solver.h"

namespace hapcine {

constexpr double kDoubtfulLostShare = 0.05;
constexpr double kDoubtfulMedianConfidence = 0.12;
constexpr double kDoubtfulBorderSupport = kUnconfirmedBorderSupport;

// The border support rule of the doubtful test (above): false once the shot
// was read as a still camera (its still border confirms that reading).
bool UnconfirmedMotion(const ShotQuality& q);

// One entry per shot of `path`, in order. `width`: the decoded width.
std::vector<ShotQuality> SummariseShots(const CameraPath& path, const std::vector<WindowReport>& windows,
                                        int width);

nlohmann::json ShotQualityJson(const ShotQuality& q);
// "shot 2 (frames 120-260): doubtful: 14 frames lost, median confidence 0.21"
// (", border support 0.42 (the motion rests on a region inside the picture)"
// where that rule holds)
std::string DoubtfulShotLine(const ShotQuality& q);
// "shot 3 (frames 200-269): read as a still camera: the frame's border
// stays where its motion would move it (border support 0.46): a subject's
// motion, not the camera's"
std::string StillBorderLine(const ShotQuality& q);
// "shot 0 (frames 0-159): zoom ambiguous in 41 of 160 frames (zoom or dolly,
// zoom or none): the reading without zoom kept, confidence lowered" (or "the
// zoom kept", or "the zoom kept in 10, the reading without zoom in 31"; no
// reading named from a header written before ambiguous_zoom_kept).
std::string AmbiguousZoomLine(const ShotQuality& q);

}  // namespace hapcine
