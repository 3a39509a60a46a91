// Peer: OpenCV videostab's 2-D global motion, read as camera motion.
// Between consecutive frames cv::videostab::KeypointBasedMotionEstimator
// (GFTT corners, pyramidal LK, MotionEstimatorRansacL2 with a similarity
// model) gives a 2-D similarity; chained from frame 0, its rotation is the
// roll, its scale the zoom and the motion of the image centre the pan and
// tilt (bench/peer_convert.h), at an assumed frame-0 field of view (--fov,
// the same 50 deg prior hapcine uses when the focal cannot be observed).
// Camera translation is invisible to it: it comes out as pan and tilt.
// A frame pair whose estimate fails keeps the previous motion (counted).
//
//   hapcine_peer_videostab VIDEO -o OUT.camera.csv [--max-side 640] [--fov 50]
#include <cmath>
#include <cstdio>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videostab/global_motion.hpp>
#include <string>

#include "bench/peer_convert.h"
#include "bench/peer_video.h"
#include "core/camera_path.h"
#include "core/error.h"
#include "core/rotation.h"

int main(int argc, char** argv) {
  using namespace hapcine;
  namespace vs = cv::videostab;
  if (argc < 2 || std::string(argv[1]) == "--help") {
    std::printf("usage: %s VIDEO -o OUT.camera.csv [--max-side 640] [--fov 50]\n", argv[0]);
    return argc < 2 ? 2 : 0;
  }
  const std::string video = argv[1];
  const std::string out = bench::ArgValue(argc, argv, "-o", "");
  const int max_side = std::stoi(bench::ArgValue(argc, argv, "--max-side", "640"));
  const double fov0 = std::stod(bench::ArgValue(argc, argv, "--fov", "50"));
  if (out.empty() || !(fov0 > 1 && fov0 < 170)) {
    std::fprintf(stderr, "hapcine_peer_videostab: bad arguments (see --help)\n");
    return 2;
  }
  try {
    vs::KeypointBasedMotionEstimator motion(
        cv::makePtr<vs::MotionEstimatorRansacL2>(vs::MM_SIMILARITY));
    motion.setDetector(cv::GFTTDetector::create(1000, 0.01, 8));
    CameraPath path;
    cv::Mat prev, gray;
    Eigen::Matrix3d frame0_to_i = Eigen::Matrix3d::Identity();
    double work_w = 0, work_h = 0, focal0 = 0;
    int failures = 0;
    Eigen::Matrix3d last_step = Eigen::Matrix3d::Identity();
    bench::VideoInfo info = bench::ForEachFrame(video, max_side, [&](int i, double t, const cv::Mat& img) {
      cv::cvtColor(img, gray, cv::COLOR_BGR2GRAY);
      if (i == 0) {
        work_w = gray.cols;
        work_h = gray.rows;
        focal0 = FocalPxFromFovDeg(fov0, work_w);
      } else {
        bool ok = false;
        cv::Mat m = motion.estimate(prev, gray, &ok);
        Eigen::Matrix3d step = last_step;
        if (ok && !m.empty()) {
          cv::Mat d;
          m.convertTo(d, CV_64F);
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) step(r, c) = d.at<double>(r, c);
          if (!step.allFinite()) { step = last_step; ok = false; }
        }
        if (!ok) ++failures;
        last_step = step;
        frame0_to_i = step * frame0_to_i;  // prev -> current after frame 0 -> prev
      }
      gray.copyTo(prev);
      const bench::SimilarityCamera cam = bench::CameraFromSimilarity(frame0_to_i, work_w, work_h, focal0);
      CameraFrame f;
      f.frame = i;
      f.time_s = t;
      f.world_from_cam = QuaternionFromPanTiltRoll({cam.pan_deg, cam.tilt_deg, cam.roll_deg});
      f.fov_deg = FovDegFromFocalPx(cam.focal_px, work_w);
      f.focal_px = cam.focal_px;  // rescaled to the decoded width below
      f.model = "rotation+zoom";
      path.frames.push_back(f);
    });
    for (auto& f : path.frames) *f.focal_px *= info.width / work_w;
    path.metadata["width"] = std::to_string(info.width);
    path.metadata["height"] = std::to_string(info.height);
    path.metadata["fps"] = std::to_string(info.fps);
    path.metadata["estimator"] = "opencv-videostab similarity";
    std::fprintf(stderr, "videostab: %d frames, %d failed pairs\n", info.frames, failures);
    WriteCameraPathFile(path, out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hapcine_peer_videostab: %s\n", e.what());
    return 1;
  }
  return 0;
}
