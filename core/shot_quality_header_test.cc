#include "core/shot_quality_header.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

namespace hapcine {
namespace {

std::vector<ShotQuality> ReadValue(const std::string& value, const std::string& key = "shot_quality.0") {
  CameraPath path;
  path.metadata[key] = value;
  return ReadShotQuality(path);
}

TEST(ShotQualityHeader, WrittenAndReadBack) {
  ShotQuality q;
  q.shot = 3;
  q.first_frame = 10;
  q.last_frame = 29;
  q.frames = 20;
  q.lost = 2;
  q.median_confidence = 0.25;
  q.inlier_ratio = 0.875;
  q.rms_px = 0.5;
  q.focal_observable = false;
  q.zoom_ambiguous = 7;
  q.ambiguous_zoom_kept = 3;
  q.border_support = 0.25;
  q.doubtful = true;
  CameraPath path;
  WriteShotQuality({q}, &path);
  EXPECT_EQ(
      path.metadata.at("shot_quality.3"),
      "first:10 last:29 frames:20 lost:2 median_confidence:0.250 inlier_ratio:0.875 rms_px:0.500 "
      "focal_observable:0 zoom_ambiguous:7 ambiguous_zoom_kept:3 border_support:0.250 doubtful:1");
  const std::vector<ShotQuality> back = ReadShotQuality(path);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].shot, 3);
  EXPECT_EQ(back[0].first_frame, 10);
  EXPECT_EQ(back[0].last_frame, 29);
  EXPECT_EQ(back[0].frames, 20);
  EXPECT_EQ(back[0].lost, 2);
  EXPECT_EQ(back[0].median_confidence, 0.25);
  EXPECT_EQ(back[0].inlier_ratio, 0.875);
  EXPECT_EQ(back[0].rms_px, 0.5);
  EXPECT_EQ(back[0].focal_observable, false);
  EXPECT_EQ(back[0].zoom_ambiguous, 7);
  EXPECT_EQ(back[0].ambiguous_zoom_kept, 3);
  EXPECT_EQ(back[0].border_support, 0.25);
  EXPECT_TRUE(back[0].doubtful);
  EXPECT_FALSE(back[0].still_border);
  // Which reading was kept is written only where a decision was ambiguous.
  q.zoom_ambiguous = 0;
  WriteShotQuality({q}, &path);
  EXPECT_EQ(path.metadata.at("shot_quality.3").find("ambiguous_zoom_kept"), std::string::npos);
  // A shot read as a still camera before a subject says so; others do not.
  EXPECT_EQ(path.metadata.at("shot_quality.3").find("still_border"), std::string::npos);
  q.still_border = true;
  WriteShotQuality({q}, &path);
  EXPECT_NE(
      path.metadata.at("shot_quality.3").find(" border_support:0.250 still_border:1 doubtful:1"),
      std::string::npos);
  EXPECT_TRUE(ReadShotQuality(path)[0].still_border);
  EXPECT_FALSE(ReadValue("still_border:2")[0].still_border);  // not a flag: ignored
}

// Shots in number order, not in the key's text order ("10" < "2").
TEST(ShotQualityHeader, OrderedByShot) {
  CameraPath path;
  for (const char* shot : {"10", "2", "-1"}) path.metadata[std::string("shot_quality.") + shot] = "frames:1";
  path.metadata["width"] = "1920";
  const std::vector<ShotQuality> q = ReadShotQuality(path);
  ASSERT_EQ(q.size(), 3u);
  EXPECT_EQ(q[0].shot, -1);
  EXPECT_EQ(q[1].shot, 2);
  EXPECT_EQ(q[2].shot, 10);
}

// A hand-edited header with counts no int holds (or NaN): those fields are
// ignored, the others read (no undefined conversion).
TEST(ShotQualityHeader, CountsOutsideIntAreIgnored) {
  const std::vector<ShotQuality> q = ReadValue(
      "first:1e300 last:7 frames:nan lost:99999999999999999999 zoom_ambiguous:inf "
      "border_support:nan doubtful:1");
  ASSERT_EQ(q.size(), 1u);
  EXPECT_EQ(q[0].first_frame, ShotQuality{}.first_frame);
  EXPECT_EQ(q[0].last_frame, 7);
  EXPECT_EQ(q[0].frames, ShotQuality{}.frames);
  EXPECT_EQ(q[0].lost, ShotQuality{}.lost);
  EXPECT_FALSE(q[0].zoom_ambiguous);
  EXPECT_FALSE(q[0].border_support);
  EXPECT_TRUE(q[0].doubtful);
  // The edges of int: the largest reads, one more does not.
  EXPECT_EQ(ReadValue("lost:2147483647")[0].lost, 2147483647);
  EXPECT_EQ(ReadValue("lost:2147483648")[0].lost, 0);
}

// A count or frame index below 0 is no count: ignored, not read as a huge
// or negative number.
TEST(ShotQualityHeader, NegativeCountsAreIgnored) {
  const ShotQuality q = ReadValue("first:-3 last:-1 frames:-20 lost:-1 zoom_ambiguous:-5")[0];
  EXPECT_EQ(q.first_frame, 0);
  EXPECT_EQ(q.last_frame, 0);
  EXPECT_EQ(q.frames, 0);
  EXPECT_EQ(q.lost, 0);
  EXPECT_FALSE(q.zoom_ambiguous);
  EXPECT_EQ(ReadValue("lost:0 zoom_ambiguous:0")[0].zoom_ambiguous, 0);  // 0 is a count
}

// Every field of `q` as the writer puts it (the shot, then the value).
std::string Fields(const ShotQuality& q) {
  CameraPath path;
  WriteShotQuality({q}, &path);
  return path.metadata.begin()->first + "=" + path.metadata.begin()->second;
}

// Anything but the writer's plain digits is ignored, where atoi/strtod would
// have read a prefix.
TEST(ShotQualityHeader, MalformedValuesAreIgnored) {
  const ShotQuality q = ReadValue(
      "first:12abc last:1.5 frames:+20 lost: median_confidence:0.3x inlier_ratio:nan rms_px:inf "
      "focal_observable:2 zoom_ambiguous:0x10 doubtful:yes")[0];
  EXPECT_EQ(Fields(q), Fields(ShotQuality{}));
  // Fields without a colon and names no reader knows are passed over.
  const ShotQuality other = ReadValue("lost 4 colour:blue lost:4 doubtful:1")[0];
  EXPECT_EQ(other.lost, 4);
  EXPECT_TRUE(other.doubtful);
  // A key whose shot is not a number is not a shot line.
  EXPECT_TRUE(ReadValue("lost:4", "shot_quality.x").empty());
  EXPECT_TRUE(ReadValue("lost:4", "shot_quality.").empty());
  EXPECT_TRUE(ReadValue("lost:4", "shot_quality.99999999999").empty());
}

// Missing values keep their defaults: an older header without
// `zoom_ambiguous` (before the count existed) reads as unknown, one with
// only some fields reads what is there.
TEST(ShotQualityHeader, MissingValuesKeepTheirDefaults) {
  const std::string old = "first:0 last:9 frames:10 lost:1 median_confidence:0.300 doubtful:0";
  EXPECT_EQ(Fields(ReadValue(old)[0]), "shot_quality.0=" + old);  // inlier ratio, rms, focal, zoom unknown
  EXPECT_EQ(Fields(ReadValue("")[0]), Fields(ShotQuality{}));
  EXPECT_EQ(Fields(ReadValue("lost:2")[0]), "shot_quality.0=first:0 last:0 frames:0 lost:2 median_confidence:0.000 doubtful:0");
}

// The file reader reads the header lines up to the column row, unescaped as
// every header line is, and nothing after it.
TEST(ShotQualityHeader, FromTheFileHeaderOnly) {
  const std::string file =
      (std::filesystem::temp_directory_path() / "hapcine_core_shot_quality.camera.csv").string();
  {
    std::ofstream out(file);
    out << "# fps=24\n# shot_quality.1=first:10 last:19 frames:10 lost:3 median_confidence:0.100 doubtful:1\n"
           "# shot_quality.0=first:0 last:9 frames:10 lost:0 median_confidence:0.300 doubtful:0\n"
           "frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg\n# shot_quality.5=not a header: after the column row\n";
  }
  const std::vector<ShotQuality> q = ReadShotQualityOfFile(file);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(q[0].shot, 0);
  EXPECT_EQ(q[1].lost, 3);
  EXPECT_TRUE(q[1].doubtful);
  std::remove(file.c_str());
  EXPECT_TRUE(ReadShotQualityOfFile(file).empty());  // no file: no summary
}

// A shot counts once however many of its frames were ambiguous; a zero
// or unknown count is no ambiguity; the lost frames' sum stops at the int
// maximum rather than wrap.
TEST(ShotQualityHeader, Counts) {
  EXPECT_EQ(CountShotQuality({}).shots, 0);
  std::vector<ShotQuality> shots(4);
  shots[0].doubtful = true;
  shots[0].zoom_ambiguous = 12;
  shots[1].zoom_ambiguous = 0;
  shots[2].doubtful = true;
  shots[2].zoom_ambiguous = 1;
  shots[0].lost = shots[1].lost = std::numeric_limits<int>::max();
  const ShotQualityCounts c = CountShotQuality(shots);
  EXPECT_EQ(c.shots, 4);
  EXPECT_EQ(c.doubtful, 2);
  EXPECT_EQ(c.zoom_ambiguous, 2);
  EXPECT_EQ(c.lost_frames, std::numeric_limits<int>::max());
  shots[0].lost = 3;
  shots[1].lost = 4;
  EXPECT_EQ(CountShotQuality(shots).lost_frames, 7);
}

}  // namespace
}  // namespace hapcine
