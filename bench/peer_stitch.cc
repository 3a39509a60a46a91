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

struct StitchArgs {
  std::string video, out, kind;
  int step = 8, max_side = 640, range = 2, features_per_image = 250;
};

// The command line into *a: -1, or the exit code (--help, bad arguments).
int ParseArgs(int argc, char** argv, StitchArgs* a) {
  using namespace hapcine;
  if (argc < 2 || std::string(argv[1]) == "--help") {
    std::printf("usage: %s VIDEO -o OUT.camera.csv [--step 8] [--max-side 640] "
                "[--features sift|orb] [--range 2] [--features-per-image 250]\n", argv[0]);
    return argc < 2 ? 2 : 0;
  }
  a->video = argv[1];
  a->out = bench::ArgValue(argc, argv, "-o", "");
  a->step = std::stoi(bench::ArgValue(argc, argv, "--step", "8"));
  a->max_side = std::stoi(bench::ArgValue(argc, argv, "--max-side", "640"));
  a->kind = bench::ArgValue(argc, argv, "--features", "sift");
  a->range = std::stoi(bench::ArgValue(argc, argv, "--range", "2"));
  // BundleAdjusterRay builds a dense numeric Jacobian (3 rows per inlier
  // match, 4 columns per camera): a few hundred features per keyframe keep
  // it to tens of MB; 1500 took ~1 GB and minutes on 43 keyframes.
  a->features_per_image = std::stoi(bench::ArgValue(argc, argv, "--features-per-image", "250"));
  if (a->out.empty() || a->step < 1 || a->range < 2 || a->features_per_image < 20 ||
      (a->kind != "sift" && a->kind != "orb")) {
    std::fprintf(stderr, "hapcine_peer_stitch: bad arguments (see --help)\n");
    return 2;
  }
  return -1;
}

constexpr float kConfThresh = 1.0f;  // cv::Stitcher's panoConfidenceThresh

// Every --step-th frame, and the last one, at --max-side.
struct Keyframes {
  std::vector<cv::Mat> images;
  std::vector<int> frame;     // video frame of each keyframe
  std::vector<double> times;  // of every video frame
  hapcine::bench::VideoInfo info;
};

Keyframes ReadKeyframes(const StitchArgs& a) {
  Keyframes k;
  cv::Mat last;
  k.info = hapcine::bench::ForEachFrame(a.video, a.max_side, [&](int i, double t, const cv::Mat& img) {
    k.times.push_back(t);
    if (i % a.step == 0) {
      k.images.push_back(img.clone());
      k.frame.push_back(i);
      last.release();
    } else {
      last = img.clone();
    }
  });
  if (!last.empty()) {
    k.images.push_back(last);
    k.frame.push_back(k.info.frames - 1);
  }
  return k;
}

std::vector<cv::detail::ImageFeatures> FindFeatures(const std::vector<cv::Mat>& images, const StitchArgs& a) {
  cv::Ptr<cv::Feature2D> finder = a.kind == "sift"
                                      ? cv::Ptr<cv::Feature2D>(cv::SIFT::create(a.features_per_image))
                                      : cv::Ptr<cv::Feature2D>(cv::ORB::create(a.features_per_image));
  const int n = static_cast<int>(images.size());
  std::vector<cv::detail::ImageFeatures> features(n);
  for (int k = 0; k < n; ++k) {
    cv::detail::computeImageFeatures(finder, images[k], features[k]);
    features[k].img_idx = k;
  }
  return features;
}

// The matcher zeroes the confidence of pairs that overlap almost fully
// (num_inliers / (8 + 0.3 matches) > 3): a panorama gains nothing from
// them. Consecutive video frames are mostly such pairs, so their
// confidence is given back, capped at 3. Returns how many.
int RestoreNearIdenticalPairs(std::vector<cv::detail::MatchesInfo>* pairwise) {
  int restored = 0;
  for (auto& m : *pairwise) {
    if (m.src_img_idx < 0 || m.src_img_idx == m.dst_img_idx || m.confidence > 0 || m.H.empty()) continue;
    const double c = m.num_inliers / (8 + 0.3 * m.matches.size());
    if (c > 3) {
      m.confidence = 3;
      ++restored;
    }
  }
  return restored;
}

// Each keyframe against its next --range - 1 (n x n, row-major).
std::vector<cv::detail::MatchesInfo> MatchKeyframes(const std::vector<cv::detail::ImageFeatures>& features,
                                                    const StitchArgs& a) {
  const int n = static_cast<int>(features.size());
  // Match confidences as in the stitching_detailed sample (0.65 SIFT/SURF, 0.3 ORB).
  cv::detail::BestOf2NearestRangeMatcher matcher(a.range, false, a.kind == "sift" ? 0.65f : 0.3f);
  // A keyframe with (almost) no features, e.g. black in a fade, would trip
  // an assertion in the FLANN matcher: it is left out of matching (which
  // cuts the chain there).
  cv::Mat_<uchar> mask(n, n, uchar(1));
  for (int k = 0; k < n; ++k)
    if (features[k].keypoints.size() < 10) mask.row(k).setTo(0), mask.col(k).setTo(0);
  std::vector<cv::detail::MatchesInfo> pairwise;
  matcher(features, pairwise, mask.getUMat(cv::ACCESS_READ));
  matcher.collectGarbage();
  return pairwise;
}

// The first keyframe of each piece, then n: the chain is cut between k and
// k+1 when no confident match crosses it.
std::vector<int> PieceStarts(const std::vector<cv::detail::MatchesInfo>& pairwise, int n, int range) {
  std::vector<int> seg_start{0};
  for (int k = 0; k + 1 < n; ++k) {
    bool linked = false;
    for (int i = std::max(0, k - range + 2); i <= k && !linked; ++i)
      for (int j = k + 1; j < std::min(n, i + range) && !linked; ++j)
        linked = pairwise[static_cast<size_t>(i) * n + j].confidence > kConfThresh;
    if (!linked) seg_start.push_back(k + 1);
  }
  seg_start.push_back(n);
  return seg_start;
}

// Estimated keyframe cameras (empty = not estimated) and their pieces.
struct KeyCameras {
  std::vector<std::optional<CameraFrame>> cam;
  std::vector<int> segment;
  int solved = 0, failed = 0;
  std::string fail_reason;
};

// Keyframes [a, b] solved as cv::Stitcher does; into *cams, or the reason
// it failed.
std::string SolvePiece(const std::vector<cv::detail::ImageFeatures>& features,
                       const std::vector<cv::detail::MatchesInfo>& pairwise, int a, int b,
                       std::vector<int>* kept, std::vector<cv::detail::CameraParams>* cams) {
  std::vector<cv::detail::ImageFeatures> sf;
  std::vector<cv::detail::MatchesInfo> sp;
  SubProblem(features, pairwise, a, b, &sf, &sp);
  *kept = cv::detail::leaveBiggestComponent(sf, sp, kConfThresh);
  if (kept->size() < 2) return "no connected pair";
  cv::detail::HomographyBasedEstimator estimator;
  if (!estimator(sf, sp, *cams)) return "HomographyBasedEstimator failed";
  for (auto& c : *cams) {
    cv::Mat r;
    c.R.convertTo(r, CV_32F);
    c.R = r;
  }
  cv::detail::BundleAdjusterRay adjuster;
  adjuster.setConfThresh(kConfThresh);
  // OpenCV's default stop is 1000 iterations at DBL_EPSILON; on a zoom
  // that ran for minutes. 50 iterations or a 1e-6 relative change.
  adjuster.setTermCriteria(cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-6));
  if (!adjuster(sf, sp, *cams)) return "BundleAdjusterRay failed";
  bool finite = true;
  for (const auto& c : *cams) finite = finite && std::isfinite(c.focal) && c.focal > 0 && cv::checkRange(c.R);
  if (!finite) return "non-finite cameras";
  return "";
}

// The piece's cameras as keyframe frames, relative to its first camera.
void StorePiece(const Keyframes& keys, int a, const std::vector<int>& kept,
                const std::vector<cv::detail::CameraParams>& cams, double to_decoded, KeyCameras* out) {
  const Eigen::Matrix3d first = ToEigen(cams[0].R);
  for (size_t i = 0; i < kept.size(); ++i) {
    const int k = a + kept[i];
    CameraFrame f;
    f.frame = keys.frame[k];
    f.time_s = keys.times[keys.frame[k]];
    f.world_from_cam = hapcine::bench::RelativeRotationGl(first, ToEigen(cams[i].R));
    f.focal_px = cams[i].focal * to_decoded;
    f.fov_deg = hapcine::FovDegFromFocalPx(*f.focal_px, keys.info.width);
    f.shot = out->solved;
    f.model = "rotation+zoom";
    out->cam[k] = f;
    out->segment[k] = out->solved;
  }
}

KeyCameras SolvePieces(const Keyframes& keys, const std::vector<cv::detail::ImageFeatures>& features,
                       const std::vector<cv::detail::MatchesInfo>& pairwise, const std::vector<int>& seg_start) {
  const int n = static_cast<int>(keys.images.size());
  KeyCameras out;
  out.cam.resize(n);
  out.segment.assign(n, -1);
  const double to_decoded = keys.info.width / static_cast<double>(keys.images[0].cols);
  for (size_t s = 0; s + 1 < seg_start.size(); ++s) {
    const int a = seg_start[s], b = seg_start[s + 1] - 1;
    if (b <= a) continue;  // a lone keyframe: nothing to relate it to
    std::vector<int> kept;
    std::vector<cv::detail::CameraParams> cams;
    const std::string failure = SolvePiece(features, pairwise, a, b, &kept, &cams);
    if (!failure.empty()) {
      ++out.failed;
      out.fail_reason = failure;
      continue;
    }
    StorePiece(keys, a, kept, cams, to_decoded, &out);
    ++out.solved;
  }
  return out;
}

// The keyframe cameras, with the frames between two keyframes of the same
// solved piece interpolated.
hapcine::CameraPath PathOf(const Keyframes& keys, const KeyCameras& kc, const StitchArgs& a) {
  const int n = static_cast<int>(kc.cam.size());
  hapcine::CameraPath path;
  path.metadata["width"] = std::to_string(keys.info.width);
  path.metadata["height"] = std::to_string(keys.info.height);
  path.metadata["fps"] = std::to_string(keys.info.fps);
  path.metadata["estimator"] = "opencv-stitching " + a.kind + " step=" + std::to_string(a.step);
  for (int k = 0; k < n; ++k) {
    if (!kc.cam[k]) continue;
    path.frames.push_back(*kc.cam[k]);
    if (k + 1 < n && kc.cam[k + 1] && kc.segment[k + 1] == kc.segment[k]) {
      const CameraFrame& fa = *kc.cam[k];
      const CameraFrame& fb = *kc.cam[k + 1];
      for (int fr = fa.frame + 1; fr < fb.frame; ++fr) {
        CameraFrame f = hapcine::bench::InterpolateFrames(fa, fb, double(fr - fa.frame) / (fb.frame - fa.frame));
        f.frame = fr;
        f.time_s = keys.times[fr];
        path.frames.push_back(f);
      }
    }
  }
  return path;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace hapcine;
  StitchArgs a;
  if (const int rc = ParseArgs(argc, argv, &a); rc >= 0) return rc;
  try {
    const Keyframes keys = ReadKeyframes(a);
    using Clock = std::chrono::steady_clock;
    auto seconds_since = [](Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); };
    Clock::time_point t0 = Clock::now();
    const int n = static_cast<int>(keys.images.size());
    const std::vector<cv::detail::ImageFeatures> features = FindFeatures(keys.images, a);
    const double features_s = seconds_since(t0);
    t0 = Clock::now();
    std::vector<cv::detail::MatchesInfo> pairwise = MatchKeyframes(features, a);
    const int restored = RestoreNearIdenticalPairs(&pairwise);
    const double matching_s = seconds_since(t0);
    t0 = Clock::now();
    const std::vector<int> seg_start = PieceStarts(pairwise, n, a.range);
    const KeyCameras kc = SolvePieces(keys, features, pairwise, seg_start);
    const double solve_s = seconds_since(t0);
    const CameraPath path = PathOf(keys, kc, a);
    std::fprintf(stderr, "stitch: %d keyframes, %d near-identical pairs kept, %zu pieces (%d solved, %d failed), "
                 "%zu of %d frames written; features %.1f s, matching %.1f s, solving %.1f s\n", n, restored,
                 seg_start.size() - 1, kc.solved, kc.failed, path.frames.size(), keys.info.frames, features_s,
                 matching_s, solve_s);
    if (path.frames.empty()) throw Error(a.video, "the stitching estimator solved no keyframes (" + kc.fail_reason + ")");
    WriteCameraPathFile(path, a.out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hapcine_peer_stitch: %s\n", e.what());
    return 1;
  }
  return 0;
}
