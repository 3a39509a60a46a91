// Revisit loop closure measured on a finished camera path (docs/estimate.md,
// "Revisits: a rotation pose graph"): which views of each shot see the same
// side again (bench/revisit_loops.h, from the path's rotations),
// SIFT matches between those frames of the video verified by an essential
// matrix at the path's focal (their relative rotation), then the rotation
// pose graph over every frame of the shot, written as a new camera path.
//
//   hapcine_revisit_closure VIDEO EST.camera.csv OUT.camera.csv
//       [--every 5] [--overlap 20] [--left 40] [--per-view 2]
//       [--step-sigma-deg 0.05] [--min-inliers 30] [--px-sigma 1]
//       [--gt GT.camera.csv [--oracle]] [--chain K]
//
// --oracle with --gt: each verified link carries the ground truth's relative
// rotation instead of the measured one (the pose graph's ceiling at those
// links); --chain K: also link every view to its next K views (SIFT
// odometry). Per link it prints the verified matches and the link's
// disagreement with the path (and with the truth, given --gt).
//
// --every: one view for links every N frames; --overlap/--left: degrees
// (RevisitCandidates); --step-sigma-deg: one frame's drift
// (LoopClosureOptions::step_sigma_rad, in degrees); --min-inliers: fewer
// verified matches, no link; --px-sigma: a keypoint's localisation noise
// (px), which with the inliers gives the link's sigma.
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/features2d.hpp>

#include "core/camera_path.h"
#include "bench/revisit_loops.h"
#include "extract/frame_source.h"

namespace hapcine {
namespace {

struct Args {
  std::string video, est, out;
  int every = 5;
  double overlap = 20, left = 40;
  int per_view = 2;
  double step_sigma_deg = 0.05;
  int min_inliers = 30;
  double px_sigma = 1;
  bool oracle = false;  // links measured by the ground truth (the pose graph's ceiling)
  int chain = 0;   // also link each view to the next `chain` views (SIFT odometry)
  std::string gt;  // optional ground truth: each link's error against it
};

Args Parse(int argc, char** argv) {
  Args a;
  std::vector<std::string> pos;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto next = [&]() -> double {
      if (i + 1 >= argc) throw std::runtime_error("missing value after " + s);
      return std::atof(argv[++i]);
    };
    if (s == "--every") a.every = static_cast<int>(next());
    else if (s == "--overlap") a.overlap = next();
    else if (s == "--left") a.left = next();
    else if (s == "--per-view") a.per_view = static_cast<int>(next());
    else if (s == "--step-sigma-deg") a.step_sigma_deg = next();
    else if (s == "--min-inliers") a.min_inliers = static_cast<int>(next());
    else if (s == "--px-sigma") a.px_sigma = next();
    else if (s == "--oracle") a.oracle = true;
    else if (s == "--chain") a.chain = static_cast<int>(next());
    else if (s == "--gt" && i + 1 < argc) a.gt = argv[++i];
    else pos.push_back(s);
  }
  if (pos.size() != 3 || a.every < 1) throw std::runtime_error("usage: VIDEO EST.camera.csv OUT.camera.csv [options]");
  a.video = pos[0];
  a.est = pos[1];
  a.out = pos[2];
  return a;
}

struct Described {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  double scale = 1;  // working / decoded px
  int width = 0, height = 0;
};

// SIFT on the frames the links need (working resolution of the decoder).
std::map<int, Described> DescribeFrames(const std::string& video, const std::set<int>& wanted) {
  std::map<int, Described> out;
  auto source = OpenFrameSource(video, FrameSourceOptions{});
  cv::Ptr<cv::SIFT> sift = cv::SIFT::create(2000, 3, 0.01);
  Frame frame;
  while (source->Next(&frame)) {
    if (!wanted.count(frame.index)) continue;
    Described d;
    sift->detectAndCompute(frame.gray, cv::noArray(), d.keypoints, d.descriptors);
    d.scale = frame.scale;
    d.width = frame.gray.cols;
    d.height = frame.gray.rows;
    out[frame.index] = std::move(d);
  }
  return out;
}

// The file's camera axes (OpenGL) from OpenCV's and back: flip y and z.
const Eigen::Matrix3d kFlip = Eigen::Vector3d(1, -1, -1).asDiagonal();

// cam_a from cam_b (file axes) from SIFT matches, or no link.
bool MeasureLink(const Described& a, const Described& b, double focal_working_px, const Args& args,
                 Eigen::Quaterniond* a_from_b, int* inliers) {
  if (a.descriptors.empty() || b.descriptors.empty()) return false;
  cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> knn;
  matcher.knnMatch(a.descriptors, b.descriptors, knn, 2);
  std::vector<cv::Point2d> pa, pb;
  const cv::Point2d c(0.5 * (a.width - 1), 0.5 * (a.height - 1));
  for (const auto& m : knn) {
    if (m.size() < 2 || m[0].distance > 0.8 * m[1].distance) continue;
    pa.push_back((cv::Point2d(a.keypoints[m[0].queryIdx].pt) - c) / focal_working_px);
    pb.push_back((cv::Point2d(b.keypoints[m[0].trainIdx].pt) - c) / focal_working_px);
  }
  if (static_cast<int>(pa.size()) < args.min_inliers) return false;
  cv::Mat mask;
  const cv::Mat E = cv::findEssentialMat(pa, pb, 1.0, cv::Point2d(0, 0), cv::RANSAC, 0.999,
                                         args.px_sigma / focal_working_px, mask);
  if (E.rows != 3 || E.cols != 3) return false;
  cv::Mat R, t;
  *inliers = cv::recoverPose(E, pa, pb, R, t, 1.0, cv::Point2d(0, 0), mask);
  if (*inliers < args.min_inliers) return false;
  Eigen::Matrix3d b_from_a_cv;
  cv::cv2eigen(R, b_from_a_cv);
  *a_from_b = Eigen::Quaterniond(kFlip * b_from_a_cv.transpose() * kFlip).normalized();
  return true;
}

// The truth's cam_a from cam_b (file axes), where a ground truth was given.
std::map<int, Eigen::Quaterniond> g_truth;
double TruthErrorDeg(int frame_a, int frame_b, const Eigen::Quaterniond& a_from_b) {
  if (!g_truth.count(frame_a) || !g_truth.count(frame_b)) return -1;
  const Eigen::Quaterniond truth = g_truth[frame_a].conjugate() * g_truth[frame_b];
  return Eigen::AngleAxisd(a_from_b.conjugate() * truth).angle() * 180 / M_PI;
}

void CloseShot(const std::vector<int>& rows, const std::map<int, Described>& described,
               const std::vector<RevisitPair>& pairs, const std::vector<int>& view_rows, const Args& args,
               CameraPath* path) {
  std::vector<Eigen::Quaterniond> q;
  std::vector<Eigen::Vector3d> c;
  std::map<int, int> node_of_row;
  for (int r : rows) {
    node_of_row[r] = static_cast<int>(q.size());
    q.push_back(path->frames[r].world_from_cam.quaternion());
    c.push_back(path->frames[r].center);
  }
  std::vector<RevisitLink> links;
  for (const RevisitPair& p : pairs) {
    const int ra = view_rows[p.i], rb = view_rows[p.j];
    const CameraFrame& fa = path->frames[ra];
    const auto da = described.find(fa.frame), db = described.find(path->frames[rb].frame);
    if (da == described.end() || db == described.end()) continue;
    const double focal = (fa.focal_px.has_value() ? double(*fa.focal_px) : 0.5 * path->width() /
                          std::tan(0.5 * double(fa.fov_deg) * M_PI / 180)) * da->second.scale;
    Eigen::Quaterniond a_from_b;
    int inliers = 0;
    if (!MeasureLink(da->second, db->second, focal, args, &a_from_b, &inliers)) continue;
    if (args.oracle && g_truth.count(fa.frame) && g_truth.count(path->frames[rb].frame))
      a_from_b = g_truth[fa.frame].conjugate() * g_truth[path->frames[rb].frame];
    const double sigma = args.px_sigma / focal / std::sqrt(static_cast<double>(inliers));
    links.push_back({node_of_row[ra], node_of_row[rb], a_from_b, sigma});
    const Eigen::Quaterniond solved = q[node_of_row[ra]].conjugate() * q[node_of_row[rb]];
    std::fprintf(stderr, "link %d-%d: %d inliers, %.2f deg from the path, %.2f from the truth (path %.2f)\n",
                 fa.frame, path->frames[rb].frame, inliers,
                 Eigen::AngleAxisd(a_from_b.conjugate() * solved).angle() * 180 / M_PI,
                 TruthErrorDeg(fa.frame, path->frames[rb].frame, a_from_b),
                 TruthErrorDeg(fa.frame, path->frames[rb].frame, solved));
  }
  LoopClosureOptions o;
  o.step_sigma_rad = args.step_sigma_deg * M_PI / 180;
  const LoopClosure closed = CloseRevisitLoops(q, links, o);
  std::fprintf(stderr, "shot: %zu frames, %zu candidate pairs, %zu links measured, %d used, %d rejected\n",
               rows.size(), pairs.size(), links.size(), closed.links_used, closed.links_rejected);
  if (!closed.changed) return;
  const std::vector<Eigen::Vector3d> centres = CarryCentres(q, closed.world_from_cam, c);
  for (size_t k = 0; k < rows.size(); ++k) {
    path->frames[rows[k]].world_from_cam = closed.world_from_cam[k];
    path->frames[rows[k]].center = centres[k];
  }
}

int Run(const Args& args) {
  CameraPath path = ReadCameraPathFile(args.est);
  if (!args.gt.empty())
    for (const CameraFrame& f : ReadCameraPathFile(args.gt).frames) g_truth[f.frame] = f.world_from_cam.quaternion();
  std::map<int, std::vector<int>> rows_of_shot;  // placed frames only
  for (size_t r = 0; r < path.frames.size(); ++r) {
    const CameraFrame& f = path.frames[r];
    if (!IsLost(f)) rows_of_shot[f.shot.has_value() ? int(*f.shot) : 0].push_back(static_cast<int>(r));
  }
  std::map<int, std::vector<RevisitPair>> pairs_of_shot;
  std::map<int, std::vector<int>> views_of_shot;
  std::set<int> wanted;
  for (const auto& [shot, rows] : rows_of_shot) {
    std::vector<Eigen::Quaterniond> view_q;
    for (size_t k = 0; k < rows.size(); k += args.every) {
      views_of_shot[shot].push_back(rows[k]);
      view_q.push_back(path.frames[rows[k]].world_from_cam.quaternion());
    }
    pairs_of_shot[shot] = RevisitCandidates(view_q, args.overlap, args.left, args.per_view);
    if (args.chain > 0 && !pairs_of_shot[shot].empty()) {
      for (int i = 0; i < static_cast<int>(view_q.size()); ++i)
        for (int d = 1; d <= args.chain && i + d < static_cast<int>(view_q.size()); ++d)
          pairs_of_shot[shot].push_back({i, i + d, 0});
    }
    for (const RevisitPair& p : pairs_of_shot[shot]) {
      wanted.insert(path.frames[views_of_shot[shot][p.i]].frame);
      wanted.insert(path.frames[views_of_shot[shot][p.j]].frame);
    }
  }
  const std::map<int, Described> described = wanted.empty() ? std::map<int, Described>{}
                                                             : DescribeFrames(args.video, wanted);
  for (const auto& [shot, rows] : rows_of_shot)
    CloseShot(rows, described, pairs_of_shot[shot], views_of_shot[shot], args, &path);
  WriteCameraPathFile(path, args.out);
  return 0;
}

}  // namespace
}  // namespace hapcine

int main(int argc, char** argv) {
  try {
    return hapcine::Run(hapcine::Parse(argc, argv));
  } catch (const std::exception& e) {
    std::cerr << "hapcine_revisit_closure: " << e.what() << "\n";
    return 1;
  }
}
