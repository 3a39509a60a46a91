#pragma once
// Platform tracks (*.platform.csv, platform/platform_track.h) as a Figure,
// like the paper's Figure 4 for the HapSeat: the platform's translations
// (sway x, heave y, surge z in mm), rotations (pitch, yaw, roll in degrees)
// and, for a Stewart platform, each leg's extension from its length at the
// first sample (mm), over time; several tracks overlaid (the first solid,
// the others dashed). `hapcine plot platform A.platform.csv [B ...]`.

#include <string>
#include <vector>

#include "datasets/plot_figure.h"
#include "platform/platform_track.h"

namespace hapcine {

// Throws UsageError when no track or a track without samples is given.
Figure PlatformTracksFigure(const std::vector<const PlatformTrack*>& tracks,
                            const std::string& title = "",
                            const std::vector<std::string>& names = {});

}  // namespace hapcine
