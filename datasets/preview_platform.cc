#include "datasets/preview_platform.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/rotation.h"
#include "platform/stewart.h"

namespace hapcine {
namespace {

struct Segment {
  Eigen::Vector3d a, b;
};

// The 12 edges of an axis-aligned box.
void AddBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, std::vector<Segment>* out) {
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int k = 0; k < 4; ++k) {
      Eigen::Vector3d a = lo, b = lo;
      a[u] = b[u] = (k & 1) ? hi[u] : lo[u];
      a[v] = b[v] = (k & 2) ? hi[v] : lo[v];
      b[axis] = hi[axis];
      out->push_back({a, b});
    }
  }
}

// Seat on the moving plate, in the moving frame (metres, seat frame).
const std::vector<Segment>& SeatWireframe() {
  static const std::vector<Segment> seat = [] {
    std::vector<Segment> s;
    AddBox({-0.35, -0.04, -0.35}, {0.35, 0.0, 0.35}, &s);    // top plate
    AddBox({-0.25, 0.05, -0.30}, {0.25, 0.15, 0.20}, &s);    // seat pan
    AddBox({-0.23, 0.15, 0.20}, {0.23, 0.85, 0.28}, &s);     // backrest
    AddBox({-0.30, 0.15, -0.25}, {-0.25, 0.35, 0.15}, &s);   // left armrest
    AddBox({0.25, 0.15, -0.25}, {0.30, 0.35, 0.15}, &s);     // right armrest
    return s;
  }();
  return seat;
}

struct View {
  const char* name;
  int h_axis, v_axis;     // seat-frame axes drawn right and up
  double h_sign, v_sign;  // flips so the picture reads naturally
};

// Behind the seat: X right, Y up. Right side: -Z (the screen) left, Y up.
// Above: X right, -Z (the screen) up.
const View kViews[3] = {
    {"behind", 0, 1, 1, 1}, {"side, screen <", 2, 1, 1, 1}, {"top, screen ^", 0, 2, 1, -1}};

void DrawView(cv::Mat& img, const cv::Rect& r, const View& v, const PlatformPose& pose,
              const PlatformPose* actual) {
  const double scale = std::min(r.width, r.height) / 1.6;  // metres -> pixels
  const cv::Point2d centre(r.x + r.width / 2.0, r.y + r.height * (v.v_axis == 1 ? 0.62 : 0.5));
  auto px = [&](const Eigen::Vector3d& p) {
    return cv::Point(static_cast<int>(std::lround(centre.x + scale * v.h_sign * p[v.h_axis])),
                     static_cast<int>(std::lround(centre.y - scale * v.v_sign * p[v.v_axis])));
  };
  const Eigen::Matrix3d rot = PoseRotation(pose);
  const Eigen::Vector3d shift = pose.head<3>();
  if (v.v_axis == 1) {  // fixed base and the jack under the plate
    const Eigen::Vector3d base_l(-0.4, -0.45, -0.4), base_r(0.4, -0.45, 0.4);
    cv::line(img, px(base_l), px(Eigen::Vector3d(base_r.x(), -0.45, base_r.z())), {150, 150, 150}, 2);
    cv::line(img, px(Eigen::Vector3d(0, -0.45, 0)), px(shift + rot * Eigen::Vector3d(0, -0.04, 0)),
             {150, 150, 150}, 2, cv::LINE_AA);
  }
  for (const Segment& s : SeatWireframe()) {
    cv::line(img, px(s.a), px(s.b), {90, 90, 90}, 1, cv::LINE_AA);  // home
  }
  if (actual) {  // the simulated platform, under the target
    const Eigen::Matrix3d rot_a = PoseRotation(*actual);
    const Eigen::Vector3d shift_a = actual->head<3>();
    for (const Segment& s : SeatWireframe()) {
      cv::line(img, px(shift_a + rot_a * s.a), px(shift_a + rot_a * s.b), {255, 200, 60}, 1,
               cv::LINE_AA);
    }
  }
  for (const Segment& s : SeatWireframe()) {
    cv::line(img, px(shift + rot * s.a), px(shift + rot * s.b), {40, 220, 255}, 1, cv::LINE_AA);
  }
  const double font = std::max(0.3, std::min(r.height / 300.0, r.width / 330.0));
  cv::putText(img, v.name, cv::Point(r.x + 4, r.y + static_cast<int>(14 * font / 0.4)),
              cv::FONT_HERSHEY_SIMPLEX, font, {230, 230, 230}, 1, cv::LINE_AA);
}

}  // namespace

PlatformPose PlatformPoseAt(const PlatformTrack& track, double t) {
  const auto& s = track.samples;
  if (s.empty()) return PlatformPose::Zero();
  if (t <= s.front().time_s) return s.front().pose;
  if (t >= s.back().time_s) return s.back().pose;
  const auto it = std::upper_bound(s.begin(), s.end(), t,
                                   [](double v, const PlatformSample& x) { return v < x.time_s; });
  const PlatformSample& b = *it;
  const PlatformSample& a = *(it - 1);
  const double w = (t - a.time_s) / (b.time_s - a.time_s);
  return a.pose + w * (b.pose - a.pose);
}

void DrawPlatformInset(cv::Mat& img, const cv::Rect& r, const PlatformTrack& track, double t,
                       const PlatformTrack* response) {
  cv::Mat roi = img(r);
  cv::Mat shade(roi.size(), roi.type(), cv::Scalar(30, 30, 30));
  cv::addWeighted(shade, 0.75, roi, 0.25, 0, roi);
  const PlatformPose pose = PlatformPoseAt(track, t);
  const int text_h = std::max(16, r.height / 5);
  const int w = r.width / 3;
  const PlatformPose actual = response ? PlatformPoseAt(*response, t) : PlatformPose::Zero();
  for (int i = 0; i < 3; ++i) {
    DrawView(img, cv::Rect(r.x + i * w, r.y, w, r.height - text_h), kViews[i], pose,
             response ? &actual : nullptr);
  }
  char lines[2][96];
  std::snprintf(lines[0], sizeof lines[0], "sway %+5.1f  heave %+5.1f  surge %+5.1f mm",
                1000 * pose[0], 1000 * pose[1], 1000 * pose[2]);
  std::snprintf(lines[1], sizeof lines[1], "pitch %+5.1f  yaw %+5.1f  roll %+5.1f deg",
                RadToDeg(pose[3]), RadToDeg(pose[4]), RadToDeg(pose[5]));
  const double font = std::max(0.25, std::min(text_h / 50.0, r.width / 900.0));
  for (int k = 0; k < 2; ++k) {
    const int y = r.y + r.height - text_h + (k + 1) * text_h / 2 - text_h / 8;
    cv::putText(img, lines[k], cv::Point(r.x + 4, y), cv::FONT_HERSHEY_SIMPLEX, font,
                {230, 230, 230}, 1, cv::LINE_AA);
  }
}

}  // namespace hapcine
