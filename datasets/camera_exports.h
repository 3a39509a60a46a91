#pragma once
// Camera path exports for post-production tools (docs/formats.md, "Camera
// exports"): a Blender Python script, Nuke .chan files and KITTI poses, and
// the split of a film into its shots, so that a multi-shot film never becomes
// one trajectory jumping back to the origin at every cut.
//
// The camera path is camera-to-world with OpenGL camera axes (+X right, +Y up,
// looking along -Z) in a Y-up world; each export says how it maps that onto
// its tool's axes.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <istream>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "core/camera_path.h"

namespace hapcine {

// The frames of one shot, in file order.
struct ShotFrames {
  int shot = 0;
  std::vector<CameraFrame> frames;
};

// Frames grouped by their `shot` column (a frame without one is shot 0),
// shots in order of first appearance. With `only_shot`, just that shot.
// Throws Error(source, ...) for a path without frames or an absent shot.
std::vector<ShotFrames> SelectShots(const CameraPath& path, std::optional<int> only_shot,
                                    const std::string& source);

// "out.txt", 3 -> "out.shot003.txt"; a name without an extension (or a dot
// only in its folder) gets ".shot003" appended.
std::string PerShotFileName(const std::string& file, int shot);

// Frame rate for the exports: the `fps` header, else 1 / the median frame
// interval, else 24 (a single frame).
double ExportFps(const CameraPath& path);

// ---- Blender (Z-up world: +X right, +Y forward, +Z up; camera axes as ours)
struct BlenderPose {
  Eigen::Vector3d location = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // matrix_world rotation
};
// Our world turned +90 degrees about X (our +Y up -> Blender +Z up, our +Z
// backward -> Blender -Y); the camera's own axes are the same in both.
BlenderPose BlenderPoseFromFrame(const CameraFrame& frame);
// Focal length in mm for a horizontal field of view on a sensor this wide.
double LensMmFromFovDeg(double fov_deg, double sensor_width_mm);

struct BlenderExportOptions {
  double sensor_width_mm = 36;
  int start_frame = 1;  // Blender frame of the camera path's frame 0
  std::string source;   // named in the script
};
// A Python script that, run by Blender, makes one animated camera per shot
// (keys on location, rotation_euler XYZ and lens) with timeline markers that
// switch the scene camera at each cut, and sets fps, resolution and range.
void WriteBlenderScript(const CameraPath& path, const std::vector<ShotFrames>& shots,
                        const BlenderExportOptions& options, std::ostream& out);

// ---- Nuke .chan (Y-up world and camera axes as ours; rotation order ZXY)
struct NukeChanRow {
  int frame = 0;
  Eigen::Vector3d translate = Eigen::Vector3d::Zero();
  Eigen::Vector3d rotate_deg = Eigen::Vector3d::Zero();  // rotate.x, .y, .z
  double vertical_fov_deg = 0;
};
// One row per frame: translate = camera centre; rotate = (tilt, pan, roll),
// Nuke's ZXY order (R = R_y(ry) R_x(rx) R_z(rz)), unwrapped across frames so
// that no angle jumps by 360; vertical FOV from the horizontal one and the
// frame's `height_over_width`.
std::vector<NukeChanRow> NukeChanRows(const ShotFrames& shot, double height_over_width,
                                      int start_frame);
void WriteNukeChan(const std::vector<NukeChanRow>& rows, std::ostream& out);
// Reads 8 numbers per line (blank lines skipped); Error("<source>:<line>", ...).
std::vector<NukeChanRow> ReadNukeChan(std::istream& in, const std::string& source);
// The camera's world_from_cam of a row (our axes).
Eigen::Quaterniond NukeRotation(const Eigen::Vector3d& rotate_deg);

// ---- KITTI odometry poses (camera x right, y down, z forward)
using KittiPose = Eigen::Matrix<double, 3, 4>;
// Camera-to-world [R | t] of every frame in the camera frame of the shot's
// first frame (the first pose is the identity), KITTI camera axes.
std::vector<KittiPose> KittiPoses(const ShotFrames& shot);
void WriteKittiPoses(const std::vector<KittiPose>& poses, std::ostream& out);
// 12 numbers per line, row-major; Error("<source>:<line>", ...).
std::vector<KittiPose> ReadKittiPoses(std::istream& in, const std::string& source);

}  // namespace hapcine
