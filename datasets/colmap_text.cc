#include "datasets/colmap_text.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"
#include "core/rotation.h"
#include "core/statistics.h"

namespace hapcine {
namespace {

struct ColmapCamera {
  int width = 0, height = 0;
  double focal_px = 0;
};

struct ColmapImage {
  Eigen::Quaterniond cam_from_world;
  Eigen::Vector3d translation;  // X_c = R X_w + t
  int camera_id = 0;
  int frame = 0;
  std::vector<long> point_ids;
};

// Data lines of a COLMAP text file (comments and blank lines skipped), with line numbers.
std::vector<std::pair<int, std::string>> ReadLines(const std::string& path, bool keep_blank) {
  InputFile file(path);
  std::ifstream& in = file.stream();
  std::vector<std::pair<int, std::string>> lines;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.empty() && line[0] == '#') continue;
    if (line.empty() && !keep_blank) continue;
    lines.push_back({number, line});
  }
  return lines;
}

int FrameFromName(const std::string& name) {
  const size_t end = name.find_last_of("0123456789");
  if (end == std::string::npos) return -1;
  size_t begin = end;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(name[begin - 1]))) --begin;
  try {
    return std::stoi(name.substr(begin, end - begin + 1));
  } catch (...) {
    return -1;
  }
}

std::map<int, ColmapCamera> ReadCameras(const std::string& cameras_path) {
  std::map<int, ColmapCamera> cameras;
  for (const auto& [number, line] : ReadLines(cameras_path, false)) {
    std::istringstream s(line);
    int id;
    std::string model;
    ColmapCamera cam;
    if (!(s >> id >> model >> cam.width >> cam.height >> cam.focal_px) || cam.width <= 0 ||
        !(cam.focal_px > 0) || !std::isfinite(cam.focal_px))
      throw Error(cameras_path + ":" + std::to_string(number), "malformed camera line");
    cameras[id] = cam;
  }
  return cameras;
}

// The pose line of one image (the first of its two lines).
ColmapImage ParseImageLine(const std::string& line, const std::string& where,
                           const std::map<int, ColmapCamera>& cameras) {
  std::istringstream s(line);
  long image_id;
  double qw, qx, qy, qz, tx, ty, tz;
  ColmapImage im;
  std::string name;
  if (!(s >> image_id >> qw >> qx >> qy >> qz >> tx >> ty >> tz >> im.camera_id >> name))
    throw Error(where, "malformed image line");
  const Eigen::Quaterniond q(qw, qx, qy, qz);
  if (!std::isfinite(q.norm()) || std::abs(q.norm() - 1) > 1e-3)
    throw Error(where, "non-unit quaternion");
  if (!cameras.count(im.camera_id))
    throw Error(where, "unknown camera id " + std::to_string(im.camera_id));
  im.cam_from_world = q.normalized();
  im.translation = Eigen::Vector3d(tx, ty, tz);
  if (!im.translation.allFinite()) throw Error(where, "non-finite translation");
  im.frame = FrameFromName(name);
  if (im.frame < 0) throw Error(where, "no frame number in image name '" + name + "'");
  return im;
}

// images.txt: two lines per image; the second (2-D points) may be empty.
// Sorted by frame number.
std::vector<ColmapImage> ReadImages(const std::string& images_path,
                                    const std::map<int, ColmapCamera>& cameras) {
  std::vector<ColmapImage> images;
  const auto lines = ReadLines(images_path, true);
  for (size_t i = 0; i < lines.size(); ++i) {
    const auto& [number, line] = lines[i];
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    ColmapImage im = ParseImageLine(line, images_path + ":" + std::to_string(number), cameras);
    if (i + 1 < lines.size()) {  // the points line
      std::istringstream p(lines[i + 1].second);
      double x, y;
      long pid;
      while (p >> x >> y >> pid)
        if (pid >= 0) im.point_ids.push_back(pid);
      ++i;
    }
    images.push_back(std::move(im));
  }
  if (images.empty()) throw Error(images_path, "no registered images");
  std::sort(images.begin(), images.end(),
            [](const auto& a, const auto& b) { return a.frame < b.frame; });
  return images;
}

// Optional: read when present (and then it must be a regular file).
std::map<long, Eigen::Vector3d> ReadPoints(const std::string& points_path) {
  std::map<long, Eigen::Vector3d> points;
  std::error_code ec;
  if (!std::filesystem::exists(points_path, ec)) return points;
  for (const auto& [number, line] : ReadLines(points_path, false)) {
    std::istringstream s(line);
    long id;
    double x, y, z;
    if (!(s >> id >> x >> y >> z))
      throw Error(points_path + ":" + std::to_string(number), "malformed point line");
    points[id] = Eigen::Vector3d(x, y, z);
  }
  return points;
}

// The path's unit: the median depth of the reference image's points (1 without points).
double MedianDepth(const ColmapImage& ref, const std::map<long, Eigen::Vector3d>& points) {
  const Eigen::Matrix3d R_ref = ref.cam_from_world.toRotationMatrix();
  std::vector<double> depths;
  for (long pid : ref.point_ids) {
    auto it = points.find(pid);
    if (it == points.end()) continue;
    const double z = (R_ref * it->second + ref.translation).z();
    if (z > 0 && std::isfinite(z)) depths.push_back(z);
  }
  return depths.empty() ? 1.0 : Quantile(std::move(depths), 0.5);
}

// Every image's pose relative to the first registered one, in the camera
// path's axes, keyed by frame number.
std::map<int, CameraFrame> RegisteredFrames(const std::vector<ColmapImage>& images,
                                            const std::map<int, ColmapCamera>& cameras,
                                            double unit, const ColmapReadOptions& options) {
  const ColmapImage& ref = images.front();
  const Eigen::Matrix3d R_ref = ref.cam_from_world.toRotationMatrix();
  const Eigen::Vector3d C_ref = -R_ref.transpose() * ref.translation;
  const Eigen::Matrix3d F = Eigen::Vector3d(1, -1, -1).asDiagonal();
  std::map<int, CameraFrame> registered;
  for (const auto& im : images) {
    const Eigen::Matrix3d R = im.cam_from_world.toRotationMatrix();
    const Eigen::Vector3d C = -R.transpose() * im.translation;
    CameraFrame f;
    f.frame = im.frame;
    f.world_from_cam = CanonicalQuaternion(Eigen::Quaterniond(F * (R_ref * R.transpose()) * F));
    f.center = F * (R_ref * (C - C_ref)) / unit;
    const ColmapCamera& cam = cameras.at(im.camera_id);
    const int width = options.decoded_width > 0 ? options.decoded_width : cam.width;
    const double focal = cam.focal_px * width / cam.width;
    f.focal_px = focal;
    f.fov_deg = FovDegFromFocalPx(focal, width);
    f.shot = 0;
    f.model = "general";
    f.confidence = 1;
    registered[im.frame] = f;
  }
  return registered;
}

// One frame per entry of frame_times; a frame COLMAP did not register is
// `lost` (docs/formats.md): nothing places it, and the placeholder is the
// last registered pose, or the first one before any.
CameraPath PathOnFrameTimes(const std::map<int, CameraFrame>& registered,
                            const std::vector<double>& frame_times) {
  CameraPath path;
  const CameraFrame* prev = nullptr;
  for (size_t i = 0; i < frame_times.size(); ++i) {
    auto it = registered.find(static_cast<int>(i));
    CameraFrame f;
    if (it != registered.end()) {
      f = it->second;
      prev = &it->second;
    } else {
      f = prev ? *prev : registered.begin()->second;
      f.model = kLostModel;
      f.confidence = 0;
    }
    f.frame = static_cast<int>(i);
    f.time_s = frame_times[i];
    path.frames.push_back(f);
  }
  return path;
}

}  // namespace

CameraPath ReadColmapTextModel(const std::string& dir, const ColmapReadOptions& options) {
  const std::map<int, ColmapCamera> cameras = ReadCameras(dir + "/cameras.txt");
  const std::vector<ColmapImage> images = ReadImages(dir + "/images.txt", cameras);
  const std::map<long, Eigen::Vector3d> points = ReadPoints(dir + "/points3D.txt");
  const double unit = MedianDepth(images.front(), points);
  std::map<int, CameraFrame> registered = RegisteredFrames(images, cameras, unit, options);
  if (!options.frame_times.empty()) return PathOnFrameTimes(registered, options.frame_times);
  CameraPath path;
  const double fps = options.fps > 0 ? options.fps : 25;
  for (auto& [frame, f] : registered) {
    f.time_s = frame / fps;
    path.frames.push_back(f);
  }
  return path;
}

}  // namespace hapcine
