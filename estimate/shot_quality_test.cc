#include "estimate/shot_quality.h"

#include <gtest/gtest.h>

#include <sstream>

namespace hapcine {
namespace {

CameraPath TwoShots() {
  CameraPath path;
  for (int i = 0; i < 40; ++i) {
    CameraFrame f;
    f.frame = i;
    f.time_s = i / 25.0;
    f.fov_deg = 50;
    f.shot = i < 20 ? 0 : 1;
    const bool lost = i >= 30 && i < 33;  // 3 of shot 1's 20 frames
    f.model = lost ? kLostModel : "rotation";
    f.confidence = lost ? 0.0 : (i < 20 ? 0.3 : 0.1);
    path.frames.push_back(f);
  }
  return path;
}

// The shot quality `path`'s header carries, written to a file and read back.
std::vector<ShotQuality> ThroughTheFile(const CameraPath& path) {
  std::stringstream file;
  WriteCameraPath(path, file);
  return ReadShotQuality(ReadCameraPath(file, "test"));
}

// Stills shots linked across a split are one shot whose frames are not
// contiguous (frames 0-19 and 30-39 here, shot 1 between): one summary of
// all its frames, not one per run.
TEST(ShotQuality, AShotSplitByAnotherIsOneSummary) {
  CameraPath path = TwoShots();
  for (CameraFrame& f : path.frames) {
    f.shot = f.frame >= 20 && f.frame < 30 ? 1 : 0;
    f.model = "general";
    f.confidence = f.frame < 20 ? 0.3 : (f.frame < 30 ? 0.1 : 0.5);
  }
  const std::vector<ShotQuality> q = SummariseShots(path, {}, 1920);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(q[0].shot, 0);
  EXPECT_EQ(q[0].frames, 30);
  EXPECT_EQ(q[0].first_frame, 0);
  EXPECT_EQ(q[0].last_frame, 39);
  EXPECT_NEAR(q[0].median_confidence, 0.3, 1e-12);  // 20 at 0.3, 10 at 0.5
  EXPECT_EQ(q[1].shot, 1);
  EXPECT_EQ(q[1].frames, 10);
}

TEST(ShotQuality, SummaryRuleAndHeaderRoundTrip) {
  CameraPath path = TwoShots();
  WindowReport w;
  w.shot = 0;
  w.inliers = 90;
  w.correspondences = 100;
  w.observations = 100;
  w.rms_px = 0.5;  // at 1920 px: 0.25 px at 960
  w.focal_observable = true;
  const std::vector<ShotQuality> q = SummariseShots(path, {w}, 1920);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(q[0].frames, 20);
  EXPECT_EQ(q[0].lost, 0);
  EXPECT_NEAR(q[0].median_confidence, 0.3, 1e-12);
  EXPECT_NEAR(*q[0].inlier_ratio, 0.9, 1e-12);
  EXPECT_NEAR(*q[0].rms_px, 0.25, 1e-12);
  EXPECT_TRUE(*q[0].focal_observable);
  EXPECT_FALSE(q[0].doubtful);
  EXPECT_EQ(q[1].first_frame, 20);
  EXPECT_EQ(q[1].last_frame, 39);
  EXPECT_EQ(q[1].lost, 3);
  EXPECT_FALSE(q[1].inlier_ratio);  // no window: unknown, not 0
  EXPECT_TRUE(q[1].doubtful);       // 15 % lost, median 0.1
  EXPECT_EQ(DoubtfulShotLine(q[1]), "shot 1 (frames 20-39): doubtful: 3 of 20 frames lost, median confidence 0.10");

  WriteShotQuality(q, &path);
  EXPECT_EQ(path.metadata.at("shot_quality.1"),
            "first:20 last:39 frames:20 lost:3 median_confidence:0.100 doubtful:1");
  // Through the file and back.
  const std::vector<ShotQuality> back = ThroughTheFile(path);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(ShotQualityJson(back[0]), ShotQualityJson(q[0]));
  EXPECT_EQ(ShotQualityJson(back[1]), ShotQualityJson(q[1]));
}

// The median border support over the shot's keyframe intervals, whichever
// window they are in: below one half, the shot is doubtful even with a good
// confidence (the motion rests on a region inside the picture); no
// interval (no window, or none with a keyframe interval): unknown.
TEST(ShotQuality, BorderSupportRule) {
  CameraPath path = TwoShots();
  for (CameraFrame& f : path.frames) f.confidence = 0.3, f.model = "rotation";
  WindowReport a, b, other;
  a.border_support = {5.0 / 12, 1.0};  // a still interval counts 1
  b.border_support = {4.0 / 12, 6.0 / 12};
  other.shot = 1;
  other.border_support = {6.0 / 12};
  std::vector<ShotQuality> q = SummariseShots(path, {a, b, other}, 960);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_NEAR(*q[0].border_support, 5.5 / 12, 1e-12);
  EXPECT_TRUE(UnconfirmedMotion(q[0]));
  EXPECT_TRUE(q[0].doubtful);
  EXPECT_EQ(DoubtfulShotLine(q[0]),
            "shot 0 (frames 0-19): doubtful: median confidence 0.30, border support 0.46 (the "
            "motion rests on a "
            "region inside the picture)");
  EXPECT_NEAR(*q[1].border_support, 0.5, 1e-12);  // half the edge: not below
  EXPECT_FALSE(q[1].doubtful);
  WriteShotQuality(q, &path);
  EXPECT_EQ(path.metadata.at("shot_quality.0"),
            "first:0 last:19 frames:20 lost:0 median_confidence:0.300 "
            "focal_observable:0 zoom_ambiguous:0 border_support:0.458 doubtful:1");
  EXPECT_NEAR(*ThroughTheFile(path)[0].border_support, 0.458, 1e-12);
  // Degenerate: windows without keyframe intervals, or none at all.
  EXPECT_FALSE(SummariseShots(path, {WindowReport{}}, 960)[0].border_support);
  EXPECT_FALSE(SummariseShots(path, {}, 960)[0].border_support);
  EXPECT_FALSE(SummariseShots(path, {}, 960)[0].doubtful);
}

// A shot the estimator read as a still camera before a moving subject
// (WindowReport::shot_held_still on its last window): its low border
// support no longer makes it doubtful (the still border confirms the still
// camera), the header says still_border:1 and the line says why.
TEST(ShotQuality, StillBorderShotIsNotDoubtfulByItsBorder) {
  CameraPath path = TwoShots();
  for (CameraFrame& f : path.frames) f.confidence = 0.3, f.model = "static";
  WindowReport a, b;
  a.border_support = {4.0 / 12, 5.0 / 12};
  a.last_frame = 19;
  a.zoom_decisions.push_back({"focal", 110, 100, true, 0.2});  // ambiguous, the zoom kept
  b.border_support = {3.0 / 12};
  b.shot_held_still = true;
  std::vector<ShotQuality> q = SummariseShots(path, {a, b}, 960);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_TRUE(q[0].still_border);
  EXPECT_FALSE(UnconfirmedMotion(q[0]));
  EXPECT_FALSE(q[0].doubtful);
  EXPECT_EQ(q[0].zoom_ambiguous, 0);  // the shot writes no zoom
  EXPECT_EQ(
      StillBorderLine(q[0]),
      "shot 0 (frames 0-19): read as a still camera: the frame's border stays where its motion "
      "would move it (border support 0.33): a subject's motion, not the camera's");
  EXPECT_FALSE(q[1].still_border);
  WriteShotQuality(q, &path);
  EXPECT_TRUE(ThroughTheFile(path)[0].still_border);
  EXPECT_EQ(ShotQualityJson(q[0])["still_border"], true);
}

// Each window writes the frames after the previous one's; those of a window
// whose zoom decision sat within half a threshold of the other reading are
// counted, the others not, and of them those whose window kept the zoom.
TEST(ShotQuality, ZoomAmbiguousFramesOfUndecidedWindows) {
  CameraPath path = TwoShots();
  WindowReport decided, not_clear, undecided_zoom, undecided_none, other_shot;
  decided.last_frame = 5;
  decided.zoom_decisions.push_back({"focal", 300, 100, true, 0.2});  // twice the penalty
  not_clear.last_frame = 9;
  not_clear.zoom_decisions.push_back({"focal", 175, 100, true, 0.2});  // decisiveness 0.75: not ambiguous
  undecided_zoom.first_frame = 8;                                      // its held lead-in
  undecided_zoom.last_frame = 14;
  undecided_zoom.zoom_decisions.push_back({"freedoms", 140, 100, false, 0.2});  // decisiveness 0.4: zoom dropped
  undecided_zoom.zoom_decisions.push_back({"focal", 110, 100, true, 0.2});  // 0.1, the least decisive: kept
  undecided_none.last_frame = 19;
  undecided_none.zoom_decisions.push_back({"branch", 10, 100, false, 0.2});  // the fixed lens kept
  other_shot.shot = 1;
  other_shot.first_frame = 20;
  other_shot.last_frame = 39;
  std::vector<ShotQuality> q =
      SummariseShots(path, {decided, not_clear, undecided_zoom, undecided_none, other_shot}, 960);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(*q[0].zoom_ambiguous, 10);      // frames 10-19
  EXPECT_EQ(*q[0].ambiguous_zoom_kept, 5);  // frames 10-14
  EXPECT_EQ(*q[1].zoom_ambiguous, 0);       // no zoom decision to make
  EXPECT_EQ(AmbiguousZoomLine(q[0]),
            "shot 0 (frames 0-19): zoom ambiguous in 10 of 20 frames (zoom or dolly, zoom or none): the zoom kept "
            "in 5, the reading without zoom in 5, confidence lowered");
  EXPECT_FALSE(SummariseShots(path, {}, 960)[0].zoom_ambiguous);  // no windows (COLMAP): unknown

  WriteShotQuality(q, &path);
  EXPECT_EQ(path.metadata.at("shot_quality.0"),
            "first:0 last:19 frames:20 lost:0 median_confidence:0.300 focal_observable:0 zoom_ambiguous:10 "
            "ambiguous_zoom_kept:5 doubtful:0");
  EXPECT_EQ(path.metadata.at("shot_quality.1").find("ambiguous_zoom_kept"), std::string::npos);  // none ambiguous
  const std::vector<ShotQuality> back = ThroughTheFile(path);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(ShotQualityJson(back[0]), ShotQualityJson(q[0]));
  EXPECT_EQ(ShotQualityJson(back[0])["zoom_ambiguous"], 10);
  EXPECT_EQ(ShotQualityJson(back[0])["ambiguous_zoom_kept"], 5);
}

// The warning names the reading kept where every ambiguous frame kept the
// same one, and none where the header predates the count.
TEST(ShotQuality, AmbiguousZoomLineNamesTheReadingKept) {
  CameraPath older;  // before ambiguous_zoom_kept
  older.metadata["shot_quality.0"] = "first:0 last:159 frames:160 lost:0 zoom_ambiguous:41 doubtful:0";
  ShotQuality q = ReadShotQuality(older).at(0);
  const std::string head = "shot 0 (frames 0-159): zoom ambiguous in 41 of 160 frames (zoom or dolly, zoom or none): ";
  EXPECT_EQ(AmbiguousZoomLine(q), head + "confidence lowered");
  q.ambiguous_zoom_kept = 0;
  EXPECT_EQ(AmbiguousZoomLine(q), head + "the reading without zoom kept, confidence lowered");
  q.ambiguous_zoom_kept = 41;
  EXPECT_EQ(AmbiguousZoomLine(q), head + "the zoom kept, confidence lowered");
  q.ambiguous_zoom_kept = 500;  // a hand-edited header: no more than the ambiguous frames
  EXPECT_EQ(AmbiguousZoomLine(q), head + "the zoom kept, confidence lowered");
}

// One lost frame in 20 is the limit; a single weak frame is not a weak shot.
TEST(ShotQuality, DoubtfulRuleAtItsEdges) {
  CameraPath path = TwoShots();
  for (auto& f : path.frames) {
    f.shot = 0;
    f.model = "rotation";
    f.confidence = 0.3;
  }
  path.frames[5].model = kLostModel;
  path.frames[6].model = kLostModel;  // 2 of 40: 5 %
  path.frames[7].confidence = 0.01;
  EXPECT_FALSE(SummariseShots(path, {}, 960)[0].doubtful);
  path.frames[8].model = kLostModel;  // 3 of 40
  EXPECT_TRUE(SummariseShots(path, {}, 960)[0].doubtful);
  CameraPath empty;
  EXPECT_TRUE(SummariseShots(empty, {}, 960).empty());
}

}  // namespace
}  // namespace hapcine
