#pragma once
// The procedural "building interior" of the synthetic clips: a hall 14 m wide,
// 5 m high and 18 m deep (x in [-7, 7], y in [0, 5], z in [-12, 6]) with brick
// side walls, a plastered and wainscoted back wall with a door, posters and
// paintings, a tiled marble floor, a panelled ceiling, six fluted pillars,
// crates, a lamp, a table and a bench at different depths (for parallax), and
// two standing characters near (0, 0, -4.1) facing +Z. The characters are
// static: the ground truth of a clip is the camera only, and static content
// keeps the tracking fair.

#include <Eigen/Core>
#include <cstdint>
#include <memory>

#include "datasets/scene.h"

namespace hapcine::synth {

enum class SceneStyle {
  kTextured,    // rich, multi-scale texture everywhere
  kLowTexture,  // flat surfaces with faint low-frequency shading, no posters
  // kLowTexture at a fifth of the albedo: a dark room whose surfaces give
  // (almost) no trackable corners, as behind a face lit for a close-up.
  kDarkLowTexture,
};

// Builds (paints) the hall. Deterministic in `seed`; takes a second or two
// (texture painting, on `threads` threads, 0 = all cores).
std::shared_ptr<const Scene> BuildHallScene(uint32_t seed, SceneStyle style, int threads = 0);

// Midpoint between the two characters at chest height: what the camera
// presets frame.
Eigen::Vector3d HallSubjectCenter();

}  // namespace hapcine::synth
