// Peer: OpenCV's stitching module as a camera-rotation-and-focal estimator.
// Keyframes every --step frames get SIFT (or ORB) features; each keyframe is
// matched with its next --range - 1 neighbours (BestOf2NearestRangeMatcher);
// the keyframe chain is cut where no match crosses (a cut, a fade), and each
// piece is solved like cv::Stitcher does: HomographyBasedEstimator for the
// initial rotations and focal, then BundleAdjusterRay (rotation + focal per
// camera). Frames between keyframes are interpolated (slerp, geometric focal).
// The homography model has no translation: on moving-camera clips parallax is
// folded into rotation, which is what this peer is expected to get wrong.
//
//   hapcine_peer_stitch VIDEO -o OUT.camera.csv [--step 8] [--max-side 640]
//                       [--features sift|orb] [--range 2] [--features-per-image 250]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <opencv2/features2d.hpp>
#include <opencv2/stitching/detail/matchers.hpp>
#include <opencv2/stitching/detail/motion_estimators.hpp>
#include <opencv2/stitching/detail/util.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bench/peer_convert.h"
#include "bench/peer_video.h"
#include "core/camera_path.h"
#include "core/error.h"
#include "core/rotation.h"

namespace {

using hapcine::CameraFrame;

Eigen::Matrix3d ToEigen(const cv::Mat& m) {
  cv::Mat d;
  m.convertTo(d, CV_64F);
  Eigen::Matrix3d e;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) e(r, c) = d.at<double>(r, c);
  return e;
}

// Keyframes [a, b] as a problem of their own (indices renumbered from 0).
void SubProblem(const std::vector<cv::detail::ImageFeatures>& features,
                const std::vector<cv::detail::MatchesInfo>& pairwise, int a, int b,
                std::vector<cv::detail::ImageFeatures>* sub_f,
                std::vector<cv::detail::MatchesInfo>* sub_p) {
  const int n = static_cast<int>(features.size()), m = b - a + 1;
  sub_f->assign(features.begin() + a, features.begin() + b + 1);
  for (int i = 0; i < m; ++i) (*sub_f)[i].img_idx = i;
  sub_p->assign(static_cast<size_t>(m) * m, cv::detail::MatchesInfo());
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      cv::detail::MatchesInfo mi = pairwise[static_cast<size_t>(a + i) * n + (a + j)];
      if (mi.src_img_idx >= 0) mi.src_img_idx = i;
      if (mi.dst_img_idx >= 0) mi.dst_img_idx = j;
      (*sub_p)[static_cast<size_t>(i) * m + j] = mi;
    }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace hapcine;
  if (argc < 2 || std::string(argv[1]) == "--help") {
    std::printf("usage: %s VIDEO -o OUT.camera.csv [--step 8] [--max-side 640] "
                "[--features sift|orb] [--range 2] [--features-per-image 250]\n", argv[0]);
    return argc < 2 ? 2 : 0;
  }
  const std::string video = argv[1];
  const std::string out = bench::ArgValue(argc, argv, "-o", "");
  const int step = std::stoi(bench::ArgValue(argc, argv, "--step", "8"));
  const int max_side = std::stoi(bench::ArgValue(argc, argv, "--max-side", "640"));
  const std::string kind = bench::ArgValue(argc, argv, "--features", "sift");
  const int range = std::stoi(bench::ArgValue(argc, argv, "--range", "2"));
  // BundleAdjusterRay builds a dense numeric Jacobian (3 rows per inlier
  // match, 4 columns per camera): a few hundred features per keyframe keep
  // it to tens of MB; 1500 took ~1 GB and minutes on 43 keyframes.
  const int features_per_image = std::stoi(bench::ArgValue(argc, argv, "--features-per-image", "250"));
  if (out.empty() || step < 1 || range < 2 || features_per_image < 20 || (kind != "sift" && kind != "orb")) {
    std::fprintf(stderr, "hapcine_peer_stitch: bad arguments (see --help)\n");
    return 2;
  }
  const float conf_thresh = 1.0f;  // cv::Stitcher's panoConfidenceThresh
  try {
    std::vector<cv::Mat> key_img;
    std::vector<int> key_frame;
    std::vector<double> times;
    cv::Mat last;
    bench::VideoInfo info = bench::ForEachFrame(video, max_side, [&](int i, double t, const cv::Mat& img) {
      times.push_back(t);
      if (i % step == 0) {
        key_img.push_back(img.clone());
        key_frame.push_back(i);
        last.release();
      } else {
        last = img.clone();
      }
    });
    if (!last.empty()) {
      key_img.push_back(last);
      key_frame.push_back(info.frames - 1);
    }
    using Clock = std::chrono::steady_clock;
    auto seconds_since = [](Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); };
    Clock::time_point t0 = Clock::now();
    const int n = static_cast<int>(key_img.size());
    const double work_width = key_img[0].cols;

    cv::Ptr<cv::Feature2D> finder =
        kind == "sift" ? cv::Ptr<cv::Feature2D>(cv::SIFT::create(features_per_image)) : cv::Ptr<cv::Feature2D>(cv::ORB::create(features_per_image));
    std::vector<cv::detail::ImageFeatures> features(n);
    for (int k = 0; k < n; ++k) {
      cv::detail::computeImageFeatures(finder, key_img[k], features[k]);
      features[k].img_idx = k;
    }
    const double features_s = seconds_since(t0);
    t0 = Clock::now();
    // Match confidences as in the stitching_detailed sample (0.65 SIFT/SURF, 0.3 ORB).
    cv::detail::BestOf2NearestRangeMatcher matcher(range, false, kind == "sift" ? 0.65f : 0.3f);
    // A keyframe with (almost) no features, e.g. black in a fade, would trip
    // an assertion in the FLANN matcher: it is left out of matching (which
    // cuts the chain there).
    cv::Mat_<uchar> mask(n, n, uchar(1));
    for (int k = 0; k < n; ++k)
      if (features[k].keypoints.size() < 10) mask.row(k).setTo(0), mask.col(k).setTo(0);
    std::vector<cv::detail::MatchesInfo> pairwise;
    matcher(features, pairwise, mask.getUMat(cv::ACCESS_READ));
    matcher.collectGarbage();
    // The matcher zeroes the confidence of pairs that overlap almost fully
    // (num_inliers / (8 + 0.3 matches) > 3): a panorama gains nothing from
    // them. Consecutive video frames are mostly such pairs, so their
    // confidence is given back, capped at 3.
    int restored = 0;
    for (auto& m : pairwise) {
      if (m.src_img_idx < 0 || m.src_img_idx == m.dst_img_idx || m.confidence > 0 || m.H.empty()) continue;
      const double c = m.num_inliers / (8 + 0.3 * m.matches.size());
      if (c > 3) {
        m.confidence = 3;
        ++restored;
      }
    }

    const double matching_s = seconds_since(t0);
    t0 = Clock::now();
    // Cut the chain between k and k+1 when no confident match crosses it.
    std::vector<int> seg_start{0};
    for (int k = 0; k + 1 < n; ++k) {
      bool linked = false;
      for (int i = std::max(0, k - range + 2); i <= k && !linked; ++i)
        for (int j = k + 1; j < std::min(n, i + range) && !linked; ++j)
          linked = pairwise[static_cast<size_t>(i) * n + j].confidence > conf_thresh;
      if (!linked) seg_start.push_back(k + 1);
    }
    seg_start.push_back(n);

    // Estimated keyframe cameras (empty frame = not estimated).
    std::vector<std::optional<CameraFrame>> key_cam(n);
    std::vector<int> key_segment(n, -1);
    int segments_solved = 0, segments_failed = 0;
    std::string fail_reason;
    const double to_decoded = info.width / work_width;
    for (size_t s = 0; s + 1 < seg_start.size(); ++s) {
      const int a = seg_start[s], b = seg_start[s + 1] - 1;
      if (b <= a) continue;  // a lone keyframe: nothing to relate it to
      std::vector<cv::detail::ImageFeatures> sf;
      std::vector<cv::detail::MatchesInfo> sp;
      SubProblem(features, pairwise, a, b, &sf, &sp);
      std::vector<int> kept = cv::detail::leaveBiggestComponent(sf, sp, conf_thresh);
      if (kept.size() < 2) { ++segments_failed; fail_reason = "no connected pair"; continue; }
      std::vector<cv::detail::CameraParams> cams;
      cv::detail::HomographyBasedEstimator estimator;
      if (!estimator(sf, sp, cams)) { ++segments_failed; fail_reason = "HomographyBasedEstimator failed"; continue; }
      for (auto& c : cams) {
        cv::Mat r;
        c.R.convertTo(r, CV_32F);
        c.R = r;
      }
      cv::detail::BundleAdjusterRay adjuster;
      adjuster.setConfThresh(conf_thresh);
      // OpenCV's default stop is 1000 iterations at DBL_EPSILON; on a zoom
      // that ran for minutes. 50 iterations or a 1e-6 relative change.
      adjuster.setTermCriteria(cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-6));
      if (!adjuster(sf, sp, cams)) { ++segments_failed; fail_reason = "BundleAdjusterRay failed"; continue; }
      bool finite = true;
      for (const auto& c : cams) finite = finite && std::isfinite(c.focal) && c.focal > 0 && cv::checkRange(c.R);
      if (!finite) { ++segments_failed; fail_reason = "non-finite cameras"; continue; }
      const Eigen::Matrix3d first = ToEigen(cams[0].R);
      for (size_t i = 0; i < kept.size(); ++i) {
        const int k = a + kept[i];
        CameraFrame f;
        f.frame = key_frame[k];
        f.time_s = times[key_frame[k]];
        f.world_from_cam = bench::RelativeRotationGl(first, ToEigen(cams[i].R));
        f.focal_px = cams[i].focal * to_decoded;
        f.fov_deg = FovDegFromFocalPx(*f.focal_px, info.width);
        f.shot = segments_solved;
        f.model = "rotation+zoom";
        key_cam[k] = f;
        key_segment[k] = segments_solved;
      }
      ++segments_solved;
    }

    const double solve_s = seconds_since(t0);
    CameraPath path;
    path.metadata["width"] = std::to_string(info.width);
    path.metadata["height"] = std::to_string(info.height);
    path.metadata["fps"] = std::to_string(info.fps);
    path.metadata["estimator"] = "opencv-stitching " + kind + " step=" + std::to_string(step);
    for (int k = 0; k < n; ++k) {
      if (!key_cam[k]) continue;
      path.frames.push_back(*key_cam[k]);
      // Interpolate up to the next keyframe when it belongs to the same solved piece.
      if (k + 1 < n && key_cam[k + 1] && key_segment[k + 1] == key_segment[k]) {
        const CameraFrame& fa = *key_cam[k];
        const CameraFrame& fb = *key_cam[k + 1];
        for (int fr = fa.frame + 1; fr < fb.frame; ++fr) {
          CameraFrame f = bench::InterpolateFrames(fa, fb, double(fr - fa.frame) / (fb.frame - fa.frame));
          f.frame = fr;
          f.time_s = times[fr];
          path.frames.push_back(f);
        }
      }
    }
    std::fprintf(stderr, "stitch: %d keyframes, %d near-identical pairs kept, %zu pieces (%d solved, %d failed), "
                 "%zu of %d frames written; features %.1f s, matching %.1f s, solving %.1f s\n", n, restored,
                 seg_start.size() - 1, segments_solved, segments_failed, path.frames.size(), info.frames, features_s,
                 matching_s, solve_s);
    if (path.frames.empty()) throw Error(video, "the stitching estimator solved no keyframes (" + fail_reason + ")");
    WriteCameraPathFile(path, out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hapcine_peer_stitch: %s\n", e.what());
    return 1;
  }
  return 0;
}
