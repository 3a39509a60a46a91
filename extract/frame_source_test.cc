#include "extract/frame_source.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "core/error.h"

namespace hapcine {
namespace {

namespace fs = std::filesystem;

// Small videos are made with the ffmpeg CLI on the fly, once per test run.
class FrameSourceTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("hapcine_extract_test_" + std::to_string(::getpid())));
    fs::create_directories(*dir_);
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(*dir_, ec);
    delete dir_;
  }
  static std::string Path(const std::string& name) { return (*dir_ / name).string(); }
  // Runs ffmpeg quietly; returns the output path.
  static std::string Make(const std::string& name, const std::string& args) {
    const std::string out = Path(name);
    if (!fs::exists(out)) {
      const std::string cmd =
          "ffmpeg -nostdin -hide_banner -loglevel error -y " + args + " '" + out + "'";
      EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    }
    return out;
  }
  static std::vector<Frame> ReadAll(const std::string& path, const FrameSourceOptions& o = {}) {
    auto source = OpenFrameSource(path, o);
    std::vector<Frame> frames;
    Frame f;
    while (source->Next(&f)) frames.push_back(f);
    return frames;
  }
  static std::string Testsrc() {
    return Make("testsrc.mp4",
                "-f lavfi -i testsrc=size=320x240:rate=24 -t 1 -c:v libx264 -pix_fmt yuv420p");
  }
  static void ExpectError(const std::string& path, const std::string& reason_part) {
    try {
      ReadAll(path);
      ADD_FAILURE() << "no error for " << path;
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), path);
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
      EXPECT_NE(e.reason().find(reason_part), std::string::npos) << e.what();
    }
  }
  static fs::path* dir_;
};
fs::path* FrameSourceTest::dir_ = nullptr;

TEST_F(FrameSourceTest, DecodesAllFramesWithMonotoneTimes) {
  const std::string path = Testsrc();
  auto source = OpenFrameSource(path, {});
  EXPECT_EQ(source->info().width, 320);
  EXPECT_EQ(source->info().height, 240);
  EXPECT_NEAR(source->info().fps, 24, 1e-6);
  EXPECT_EQ(source->info().codec, "h264");
  EXPECT_EQ(source->info().rotation_deg, 0);
  std::vector<Frame> frames;
  Frame f;
  while (source->Next(&f)) frames.push_back(f);
  EXPECT_FALSE(source->Next(&f));  // stays at the end
  ASSERT_EQ(frames.size(), 24u);
  for (size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].index, static_cast<int>(i));
    EXPECT_NEAR(frames[i].time_s, i / 24.0, 1e-3);
    EXPECT_EQ(frames[i].gray.type(), CV_8UC1);
    EXPECT_EQ(frames[i].bgr.type(), CV_8UC3);
    EXPECT_EQ(frames[i].gray.size(), cv::Size(320, 240));  // smaller than 960: kept
    EXPECT_DOUBLE_EQ(frames[i].scale, 1.0);
  }
}

// The containers and codecs users bring: every frame, in order, at the right
// size, with the container's times (12 frames at 24 fps, 160x120).
TEST_F(FrameSourceTest, DecodesCommonContainersAndCodecs) {
  struct Case {
    const char* file;
    const char* codec_args;
    const char* codec;  // VideoInfo::codec
  };
  const Case cases[] = {
      {"h264.mov", "-c:v libx264 -pix_fmt yuv420p", "h264"},
      {"hevc.mkv", "-c:v libx265 -x265-params log-level=error", "hevc"},
      {"vp9.webm", "-c:v libvpx-vp9 -deadline realtime -cpu-used 8", "vp9"},
      {"mpeg4.avi", "-c:v mpeg4", "mpeg4"},
      {"prores.mov", "-c:v prores_ks -profile:v 0", "prores"},
  };
  for (const Case& c : cases) {
    const std::string path = Make(
        std::string("codec_") + c.file,
        std::string("-f lavfi -i testsrc=size=160x120:rate=24 -frames:v 12 ") + c.codec_args);
    auto source = OpenFrameSource(path, {});
    EXPECT_EQ(source->info().codec, c.codec) << c.file;
    std::vector<Frame> frames;
    Frame f;
    while (source->Next(&f)) frames.push_back(f);
    ASSERT_EQ(frames.size(), 12u) << c.file;
    for (size_t i = 0; i < frames.size(); ++i) {
      EXPECT_NEAR(frames[i].time_s, i / 24.0, 2e-3) << c.file << " frame " << i;
      EXPECT_EQ(frames[i].gray.size(), cv::Size(160, 120)) << c.file;
    }
    // A picture, not a blank or garbage-grey frame.
    cv::Scalar mean, stddev;
    cv::meanStdDev(frames[0].gray, mean, stddev);
    EXPECT_GT(stddev[0], 30) << c.file;
  }
}

TEST_F(FrameSourceTest, ScalesToWorkingSizeInGrayAndColour) {
  FrameSourceOptions o;
  o.max_working_side = 160;
  o.decode_threads = 2;
  const auto frames = ReadAll(Testsrc(), o);
  ASSERT_EQ(frames.size(), 24u);
  EXPECT_EQ(frames[0].gray.size(), cv::Size(160, 120));
  EXPECT_EQ(frames[0].bgr.size(), cv::Size(160, 120));
  EXPECT_DOUBLE_EQ(frames[0].scale, 0.5);
  EXPECT_EQ(frames[0].decoded_width, 320);
  EXPECT_EQ(frames[0].decoded_height, 240);
  // Gray agrees with the colour image's luma (same scaling, same frame).
  cv::Mat luma;
  cv::cvtColor(frames[5].bgr, luma, cv::COLOR_BGR2GRAY);
  EXPECT_LT(cv::norm(luma, frames[5].gray, cv::NORM_L1) / luma.total(), 12.0);
  o.want_color = false;
  const auto gray_only = ReadAll(Testsrc(), o);
  EXPECT_TRUE(gray_only[0].bgr.empty());
}

TEST_F(FrameSourceTest, ColourThumbnailBesideFullSizeGray) {
  FrameSourceOptions o;
  o.color_max_side = 80;
  const auto frames = ReadAll(Testsrc(), o);
  ASSERT_EQ(frames.size(), 24u);
  EXPECT_EQ(frames[3].gray.size(), cv::Size(320, 240));
  EXPECT_EQ(frames[3].bgr.size(), cv::Size(80, 60));
  // The thumbnail is the same picture: its luma matches the gray image's
  // area average (testsrc has large flat colour blocks).
  cv::Mat luma, small;
  cv::cvtColor(frames[3].bgr, luma, cv::COLOR_BGR2GRAY);
  cv::resize(frames[3].gray, small, luma.size(), 0, 0, cv::INTER_AREA);
  EXPECT_LT(cv::norm(luma, small, cv::NORM_L1) / luma.total(), 12.0);
  // Never bigger than the working image.
  o.color_max_side = 2000;
  o.max_working_side = 160;
  EXPECT_EQ(ReadAll(Testsrc(), o)[0].bgr.size(), cv::Size(160, 120));
}

TEST_F(FrameSourceTest, SkippingTheLoopFilterKeepsThePicture) {
  FrameSourceOptions o;
  o.skip_loop_filter = true;
  const auto fast = ReadAll(Testsrc(), o);
  const auto full = ReadAll(Testsrc());
  ASSERT_EQ(fast.size(), full.size());
  for (size_t i = 0; i < fast.size(); i += 7)
    EXPECT_LT(cv::norm(fast[i].gray, full[i].gray, cv::NORM_L1) / fast[i].gray.total(), 3.0) << i;
}

TEST_F(FrameSourceTest, SkippingNonReferenceFramesKeepsEveryIndexAndTime) {
  FrameSourceOptions o;
  o.skip_nonref_frames = true;
  auto source = OpenFrameSource(Testsrc(), o);  // x264's defaults: B-frames, some not referenced
  std::vector<Frame> decoded;
  std::vector<double> time_of(64, -1);  // by index, decoded or skipped
  Frame f;
  while (source->Next(&f)) {
    const int n = static_cast<int>(f.skipped_before_s.size());
    for (int k = 0; k < n; ++k) time_of.at(f.index - n + k) = f.skipped_before_s[k];
    time_of.at(f.index) = f.time_s;
    decoded.push_back(f);
  }
  int next = decoded.back().index + 1;
  for (double t : source->SkippedAtEnd()) time_of.at(next++) = t;
  const auto full = ReadAll(Testsrc());
  ASSERT_EQ(next, static_cast<int>(full.size()));
  EXPECT_LT(decoded.size(), full.size() * 3 / 4);  // about half skipped
  for (size_t i = 0; i < full.size(); ++i) EXPECT_NEAR(time_of[i], full[i].time_s, 1e-9) << i;
  // A reference frame decodes to the same picture whether or not the
  // frames nothing refers to were decoded.
  for (const Frame& d : decoded) {
    EXPECT_EQ(cv::norm(d.gray, full.at(d.index).gray, cv::NORM_INF), 0) << d.index;
    EXPECT_EQ(d.time_s, full.at(d.index).time_s);
  }
  // Without B-frames every frame is a reference: nothing is skipped.
  const std::string no_b = Make("testsrc_nob.mp4",
                                "-f lavfi -i testsrc=size=320x240:rate=24 -t 1 -c:v libx264 -bf 0 "
                                "-pix_fmt yuv420p");
  const auto all = ReadAll(no_b, o);
  ASSERT_EQ(all.size(), 24u);
  for (size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(all[i].index, static_cast<int>(i));
    EXPECT_TRUE(all[i].skipped_before_s.empty());
  }
}

TEST_F(FrameSourceTest, SkippingNonReferenceFramesWithoutTimestampsDecodesThemAll) {
  // MPEG-4 with B-frames in AVI: packets carry no presentation time, so a
  // skipped frame could not be counted; every frame is decoded instead.
  const std::string avi = Make("testsrc_b.avi",
                               "-f lavfi -i testsrc=size=160x120:rate=24 -t 1 -c:v mpeg4 -bf 2");
  FrameSourceOptions o;
  o.skip_nonref_frames = true;
  const auto frames = ReadAll(avi, o);
  const auto full = ReadAll(avi);
  ASSERT_EQ(frames.size(), full.size());
  for (size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].index, static_cast<int>(i));
    EXPECT_NEAR(frames[i].time_s, full[i].time_s, 1e-9) << i;
  }
}

TEST_F(FrameSourceTest, BlackIsBlackInGray) {
  // Limited-range video: black (Y=16) must come out near 0 for blank tests.
  const auto frames = ReadAll(Make("black.mp4",
                                   "-f lavfi -i color=c=black:s=64x48:r=10 -t 0.3 "
                                   "-c:v libx264 -pix_fmt yuv420p"));
  ASSERT_FALSE(frames.empty());
  EXPECT_LT(cv::mean(frames[0].gray)[0], 4.0);
}

TEST_F(FrameSourceTest, VariableFrameRateTimesComeFromTheContainer) {
  // 12 frames at 1/24 s, then 12 at 1/12 s.
  const std::string path =
      Make("vfr.mkv",
           "-f lavfi -i testsrc=size=160x120:rate=24 -frames:v 24 "
           "-vf \"setpts='if(lt(N,12),N,12+2*(N-12))'\" -fps_mode vfr -c:v libx264");
  const auto frames = ReadAll(path);
  ASSERT_EQ(frames.size(), 24u);
  for (int i = 0; i < 24; ++i) {
    const double want = i < 12 ? i / 24.0 : 0.5 + (i - 12) / 12.0;
    EXPECT_NEAR(frames[i].time_s, want, 2e-3) << "frame " << i;
  }
}

TEST_F(FrameSourceTest, HonoursDisplayRotation) {
  // White box in the top-left corner of a black 320x240 frame. The "rotate=90"
  // tag means 90 degrees counter-clockwise for display (ffprobe: rotation=90;
  // the ffmpeg CLI puts the box bottom-left), i.e. 270 clockwise.
  const std::string plain =
      Make("box.mp4",
           "-f lavfi -i color=c=black:s=320x240:r=10 -t 0.5 "
           "-vf drawbox=x=0:y=0:w=80:h=60:color=white:t=fill -c:v libx264 -pix_fmt yuv420p");
  const std::string rotated =
      Make("box_rot90.mp4", "-i '" + plain + "' -c copy -metadata:s:v rotate=90");
  auto source = OpenFrameSource(rotated, {});
  EXPECT_EQ(source->info().rotation_deg, 270);
  EXPECT_EQ(source->info().width, 240);
  EXPECT_EQ(source->info().height, 320);
  Frame f;
  ASSERT_TRUE(source->Next(&f));
  ASSERT_EQ(f.gray.size(), cv::Size(240, 320));
  EXPECT_EQ(f.decoded_width, 240);
  EXPECT_EQ(f.decoded_height, 320);
  EXPECT_GT(cv::mean(f.gray(cv::Rect(10, 320 - 70, 40, 60)))[0], 200);  // bottom-left: box
  EXPECT_LT(cv::mean(f.gray(cv::Rect(10, 10, 40, 60)))[0], 30);         // top-left: black
  EXPECT_LT(cv::mean(f.gray(cv::Rect(240 - 50, 10, 40, 60)))[0], 30);   // top-right: black
  EXPECT_EQ(f.bgr.size(), cv::Size(240, 320));
}

TEST_F(FrameSourceTest, ResamplesAnamorphicPixelsToSquareOnes) {
  // 160x120 stored with 2:1 pixels (wide pixels, as a squeezed anamorphic
  // recording): shown 320x120. A white box over stored columns 40..79 is
  // display columns 80..159.
  const std::string path =
      Make("anamorphic.mp4",
           "-f lavfi -i color=c=black:s=160x120:r=10 -t 0.5 "
           "-vf drawbox=x=40:y=30:w=40:h=60:color=white:t=fill,setsar=2/1 -c:v libx264 "
           "-pix_fmt yuv420p");
  auto source = OpenFrameSource(path, {});
  EXPECT_EQ(source->info().sample_aspect_num, 2);
  EXPECT_EQ(source->info().sample_aspect_den, 1);
  EXPECT_EQ(source->info().width, 320);
  EXPECT_EQ(source->info().height, 120);
  Frame f;
  ASSERT_TRUE(source->Next(&f));
  ASSERT_EQ(f.gray.size(), cv::Size(320, 120));
  EXPECT_EQ(f.decoded_width, 320);
  EXPECT_EQ(f.decoded_height, 120);
  EXPECT_GT(cv::mean(f.gray(cv::Rect(90, 40, 60, 40)))[0], 200);  // the box, twice as wide
  EXPECT_LT(cv::mean(f.gray(cv::Rect(170, 40, 60, 40)))[0], 30);  // right of it: black
  EXPECT_LT(cv::mean(f.gray(cv::Rect(10, 40, 60, 40)))[0], 30);   // left of it: black
  // Shrunk to a working size, the display aspect is kept.
  FrameSourceOptions small;
  small.max_working_side = 160;
  const std::vector<Frame> frames = ReadAll(path, small);
  ASSERT_FALSE(frames.empty());
  EXPECT_EQ(frames[0].gray.size(), cv::Size(160, 60));
  EXPECT_EQ(frames[0].decoded_width, 320);
  // Square pixels are left alone.
  EXPECT_EQ(OpenFrameSource(Testsrc(), {})->info().sample_aspect_num, 1);
}

TEST_F(FrameSourceTest, BadInputsNameTheFile) {
  ExpectError(Path("does_not_exist.mp4"), "no such file");
  const std::string empty = Path("empty.mp4");
  std::ofstream(empty).close();
  ExpectError(empty, "empty file");
  const std::string text = Path("notes.mp4");
  std::ofstream(text) << "this is not a video, just some words\n";
  ExpectError(text, "not a media file");
  // No read permission (root reads anything, so only checked as another user).
  const std::string locked = Path("locked.mp4");
  fs::copy_file(Testsrc(), locked, fs::copy_options::overwrite_existing);
  fs::permissions(locked, fs::perms::none);
  if (::geteuid() != 0) ExpectError(locked, "cannot read the file (Permission denied)");
  const std::string txt = Path("notes.txt");
  std::ofstream(txt) << "plain text that the tty demuxer would happily play\n";
  ExpectError(txt, "not a media file");
  ExpectError(Make("tone.m4a", "-f lavfi -i sine=frequency=440:duration=0.5 -c:a aac"),
              "no video stream");
  // An AVI whose codec tag no decoder knows (MPEG-4 with its FourCC replaced).
  {
    const std::string avi = Make("mpeg4.avi",
                                 "-f lavfi -i testsrc=size=160x120:rate=24 -t 0.5 -c:v mpeg4");
    std::ifstream in(avi, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (size_t at = bytes.find("FMP4"); at != std::string::npos; at = bytes.find("FMP4", at))
      bytes.replace(at, 4, "QQQQ");
    const std::string unknown = Path("unknown_codec.avi");
    std::ofstream(unknown, std::ios::binary) << bytes;
    ExpectError(unknown, "unsupported video codec: tag 'QQQQ' is unknown");
  }
  // 20000 px wide raw video: a corrupt or hostile header as far as we care.
  ExpectError(Make("wide.nut",
                   "-f lavfi -i color=c=gray:s=20000x8:r=5 -frames:v 1 "
                   "-c:v rawvideo -pix_fmt gray"),
              "absurd frame size");
}

// A file cut short decodes what it holds, then fails naming the file and
// "truncated" (the header declares more), so no shortened camera path is
// written as if it were the whole video.
// A remux that kept a broadcast's timestamps starts at 10 s; Matroska then
// declares its length as an end time from 0 (12 s for 2 s of video). Neither
// container is "truncated", and the times count from the stream's start.
TEST_F(FrameSourceTest, NonZeroStartTimeIsNotTruncation) {
  for (const char* name : {"offset.mkv", "offset.mp4"}) {
    const std::string path = Make(name,
                                  "-f lavfi -i testsrc=size=320x240:rate=24 -t 2 -c:v libx264 "
                                  "-g 12 -pix_fmt yuv420p -output_ts_offset 10");
    const auto frames = ReadAll(path);
    ASSERT_EQ(frames.size(), 48u) << name;
    EXPECT_NEAR(frames.front().time_s, 0.0, 1e-6) << name;
    EXPECT_NEAR(frames.back().time_s, 47.0 / 24, 1e-3) << name;
  }
}

TEST_F(FrameSourceTest, TruncatedFileIsAnErrorAfterItsFrames) {
  const std::string full = Make("long.mkv",
                                "-f lavfi -i testsrc=size=320x240:rate=24 -t 2 -c:v libx264 "
                                "-g 12 -pix_fmt yuv420p");
  const auto all = ReadAll(full);
  ASSERT_EQ(all.size(), 48u);
  const std::string faststart = Make("long_faststart.mp4",
                                     "-f lavfi -i testsrc=size=320x240:rate=24 -t 2 -c:v libx264 "
                                     "-g 12 -pix_fmt yuv420p -movflags +faststart");
  ASSERT_EQ(ReadAll(faststart).size(), 48u);
  const auto cut_copy = [&](const std::string& from, const std::string& name) {
    const std::string cut = Path(name);
    fs::copy_file(from, cut, fs::copy_options::overwrite_existing);
    fs::resize_file(cut, fs::file_size(from) * 6 / 10);
    return cut;
  };
  // Matroska (declared duration) and MP4 with its index first (the sample
  // table lists frames past the end of the file); decoding every frame, and
  // only the reference frames (--skip-nonref: the same error, after them).
  FrameSourceOptions skipping;
  skipping.skip_nonref_frames = true;
  for (const FrameSourceOptions& options : {FrameSourceOptions{}, skipping}) {
    for (const std::string& cut : {cut_copy(full, "cut.mkv"), cut_copy(faststart, "cut.mp4")}) {
      auto source = OpenFrameSource(cut, options);
      std::vector<Frame> part;
      Frame f;
      try {
        while (source->Next(&f)) part.push_back(f);
        ADD_FAILURE() << "no error for " << cut;
      } catch (const Error& e) {
        EXPECT_EQ(e.where(), cut);
        EXPECT_NE(e.reason().find("truncated"), std::string::npos) << e.what();
      }
      EXPECT_GT(part.size(), 5u) << cut;
      EXPECT_LT(part.size(), 48u) << cut;
      for (size_t i = 1; i < part.size(); ++i) EXPECT_GT(part[i].time_s, part[i - 1].time_s);
    }
  }
  // An audio track longer than the video is not a truncated video.
  for (const char* name : {"short_video.mkv", "short_video.mp4"}) {
    const std::string path =
        Make(name,
             "-f lavfi -i testsrc=size=160x120:rate=24 -f lavfi -i sine=duration=3 -t 3 "
             "-map 0:v -map 1:a -c:v libx264 -frames:v 24 -c:a aac");
    EXPECT_EQ(ReadAll(path).size(), 24u) << name;
  }
  // Only the header survives: no frame at all is an error.
  const std::string stub = Path("stub.mkv");
  fs::copy_file(full, stub, fs::copy_options::overwrite_existing);
  fs::resize_file(stub, 600);
  ExpectError(stub, "");
}

// An AVI that dropped frames (a capture that skipped them, a variable-rate
// export) keeps an empty slot for each: its header declares 46 frames, it
// holds 16, and it is whole. Its frames come at their slots' times. The same
// file cut in half is still truncated.
TEST_F(FrameSourceTest, AviWithDroppedFrameSlotsIsWhole) {
  const std::string sparse = Make("sparse.avi",
                                  "-f lavfi -i testsrc=size=160x120:rate=24 -t 2 "
                                  "-vf \"select='not(mod(n,3))'\" -fps_mode passthrough "
                                  "-c:v mpeg4 -q:v 4");
  const auto frames = ReadAll(sparse);
  ASSERT_EQ(frames.size(), 16u);
  EXPECT_NEAR(frames.back().time_s, 45.0 / 24, 1e-6);
  for (size_t i = 1; i < frames.size(); ++i)
    EXPECT_NEAR(frames[i].time_s - frames[i - 1].time_s, 3.0 / 24, 1e-6);
  const std::string cut = Path("sparse_cut.avi");
  fs::copy_file(sparse, cut, fs::copy_options::overwrite_existing);
  fs::resize_file(cut, fs::file_size(sparse) / 2);
  ExpectError(cut, "truncated");
}

// An MP4 with its index first whose data was spliced: the index still lists
// all 48 frames, every packet is read, but past the splice the bytes are
// another film's and do not decode. An error saying how many frames are
// missing, decoding every frame or only the reference frames; one frame
// missing is a warning only; frames an edit list hides (a stream copy cut
// mid-GOP) are not missing.
TEST_F(FrameSourceTest, FramesTheIndexListsButTheDataLacksAreAnError) {
  const std::string ours = Make("splice_a.mp4",
                                "-f lavfi -i testsrc=size=320x240:rate=24 -t 2 -c:v libx264 "
                                "-g 12 -pix_fmt yuv420p -movflags +faststart");
  const std::string theirs = Make("splice_b.mp4",
                                  "-f lavfi -i mandelbrot=size=320x240:rate=24 -t 2 -c:v libx264 "
                                  "-g 12 -pix_fmt yuv420p -movflags +faststart");
  ASSERT_EQ(ReadAll(ours).size(), 48u);
  auto bytes_of = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  const std::string a = bytes_of(ours), b = bytes_of(theirs);
  ASSERT_GT(b.size(), a.size());
  const size_t splice = a.size() * 45 / 100;
  const std::string spliced = Path("spliced.mp4");
  std::ofstream(spliced, std::ios::binary) << a.substr(0, splice) + b.substr(splice, a.size() - splice);
  FrameSourceOptions skipping;
  skipping.skip_nonref_frames = true;
  for (const FrameSourceOptions& options : {FrameSourceOptions{}, skipping}) {
    auto source = OpenFrameSource(spliced, options);
    size_t given = 0;
    Frame f;
    try {
      while (source->Next(&f)) given += 1 + f.skipped_before_s.size();
      ADD_FAILURE() << "no error for " << spliced;
    } catch (const Error& e) {
      given += source->SkippedAtEnd().size();
      EXPECT_EQ(e.where(), spliced);
      EXPECT_NE(e.reason().find("of the 48 frames declared could not be decoded"),
                std::string::npos)
          << e.what();
      if (!options.skip_nonref_frames) {
        EXPECT_NE(e.reason().find(std::to_string(48 - given) + " of the 48"), std::string::npos)
            << e.what() << " after " << given;
      }
    }
    EXPECT_GT(given, 5u);
  }
  // Without B-frames, the last packet is a frame nothing refers to: zeroed,
  // 47 of 48 frames decode, and a warning names the file.
  const std::string no_b = Make("splice_no_b.mp4",
                                "-f lavfi -i testsrc=size=320x240:rate=24 -t 2 -c:v libx264 "
                                "-g 12 -bf 0 -pix_fmt yuv420p -movflags +faststart");
  const std::string last_packet = Path("last_packet.txt");
  const std::string probe = "ffprobe -v error -select_streams v -show_entries packet=size,pos "
                            "-of csv=p=0 '" + no_b + "' | tail -1 > '" + last_packet + "'";
  ASSERT_EQ(std::system(probe.c_str()), 0);
  long pos = 0, size = 0;
  char comma = 0;
  std::ifstream(last_packet) >> size >> comma >> pos;  // ffprobe's order, whatever is asked
  ASSERT_GT(pos, 0);
  std::string one_lost = bytes_of(no_b);
  ASSERT_LE(static_cast<size_t>(pos + size), one_lost.size());
  one_lost.replace(pos, size, std::string(size, '\0'));
  const std::string lost = Path("one_lost.mp4");
  std::ofstream(lost, std::ios::binary) << one_lost;
  ::testing::internal::CaptureStderr();
  auto lossy = OpenFrameSource(lost);
  size_t frames = 0;
  for (Frame f; lossy->Next(&f);) ++frames;
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");  // the source prints nothing
  EXPECT_EQ(frames, 47u);
  const std::vector<std::string> warnings = lossy->Warnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("1 of the 48 frames declared"), std::string::npos) << warnings[0];
  // Cut mid-GOP by a stream copy: an edit list hides the frames before the
  // cut, which are decoded (they are references) but never shown.
  const std::string source = Make("gop48.mp4",
                                  "-f lavfi -i testsrc=size=160x120:rate=24 -t 4 -c:v libx264 "
                                  "-g 48 -pix_fmt yuv420p");
  const std::string trimmed = Make("trimmed.mp4", "-ss 1.3 -i '" + source + "' -t 1.5 -c copy");
  auto cut = OpenFrameSource(trimmed);
  EXPECT_NO_THROW({ for (Frame f; cut->Next(&f);) {} });
  EXPECT_TRUE(cut->Warnings().empty());
}

TEST_F(FrameSourceTest, ImageFolderAndPattern) {
  const fs::path folder = *dir_ / "images";
  fs::create_directories(folder);
  for (int i = 1; i <= 5; ++i) {
    cv::Mat img(100, 200, CV_8UC3, cv::Scalar(10 * i, 20 * i, 30 * i));
    char name[32];
    std::snprintf(name, sizeof(name), "img_%03d.png", i);
    cv::imwrite((folder / name).string(), img);
  }
  std::ofstream(folder / "readme.txt") << "ignored\n";
  FrameSourceOptions o;
  o.max_working_side = 100;
  o.image_sequence_fps = 10;
  for (const std::string& path : {folder.string(), (folder / "img_%03d.png").string()}) {
    auto source = OpenFrameSource(path, o);
    EXPECT_EQ(source->info().width, 200);
    EXPECT_EQ(source->info().height, 100);
    std::vector<Frame> frames;
    Frame f;
    while (source->Next(&f)) frames.push_back(f);
    ASSERT_EQ(frames.size(), 5u) << path;
    for (int i = 0; i < 5; ++i) {
      EXPECT_NEAR(frames[i].time_s, i / 10.0, 1e-12);
      EXPECT_EQ(frames[i].gray.size(), cv::Size(100, 50));
      EXPECT_DOUBLE_EQ(frames[i].scale, 0.5);
      EXPECT_NEAR(frames[i].bgr.at<cv::Vec3b>(10, 10)[2], 30 * (i + 1), 1);
    }
  }
  ExpectError((folder / "nothing_%05d.png").string(), "no image matches");
  ExpectError((folder / "bad_%s.png").string(), "conversion");
  const fs::path empty_folder = *dir_ / "no_images";
  fs::create_directories(empty_folder);
  ExpectError(empty_folder.string(), "no image files");
}

// A VFX plate: plate.%04d.png starting at 1001 (FFmpeg's image2 alone looks
// at 0..4), its numbers kept, a gap ending the sequence with a warning; a
// folder ordered by the numbers (999 before 1000), not by name.
TEST_F(FrameSourceTest, PlateNumbersFromTheFileNames) {
  const fs::path plates = *dir_ / "plates";
  fs::create_directories(plates);
  const cv::Mat img(36, 64, CV_8UC3, cv::Scalar(40, 80, 120));
  for (int n : {1001, 1002, 1003, 1004, 1007}) {
    char name[32];
    std::snprintf(name, sizeof(name), "plate.%04d.png", n);
    cv::imwrite((plates / name).string(), img);
  }
  cv::imwrite((plates / "plate.01001.png").string(), img);  // other padding: not the pattern's
  FrameSourceOptions o;
  o.image_sequence_fps = 25;
  auto source = OpenFrameSource((plates / "plate.%04d.png").string(), o);
  EXPECT_EQ(source->info().source_frames, (std::vector<int>{1001, 1002, 1003, 1004}));
  EXPECT_DOUBLE_EQ(source->info().fps, 25);
  std::vector<Frame> frames;
  for (Frame f; source->Next(&f);) frames.push_back(f);
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_EQ(frames[0].index, 0);
  EXPECT_NEAR(frames[3].time_s, 3 / 25.0, 1e-12);
  ASSERT_EQ(source->Warnings().size(), 1u);
  EXPECT_NE(source->Warnings()[0].find("1 image(s) after the gap at number 1005 ignored"),
            std::string::npos)
      << source->Warnings()[0];

  const fs::path unpadded = *dir_ / "unpadded";
  fs::create_directories(unpadded);
  for (int n : {998, 999, 1000, 1001}) cv::imwrite((unpadded / ("p." + std::to_string(n) + ".png")).string(), img);
  EXPECT_EQ(OpenFrameSource(unpadded.string())->info().source_frames,
            (std::vector<int>{998, 999, 1000, 1001}));
  cv::imwrite((unpadded / "cover.png").string(), img);  // a name without a number: by name, none kept
  EXPECT_TRUE(OpenFrameSource(unpadded.string())->info().source_frames.empty());
}

// What VFX delivers besides PNG: 16-bit PNG and TIFF, float OpenEXR (scene
// linear, shown through a 2.2 gamma) by OpenCV, 10-bit DPX by FFmpeg; a
// file neither reads is one line naming it.
TEST_F(FrameSourceTest, VfxPlateFormats) {
  const cv::Scalar bgr8(40, 120, 200);
  cv::Mat img8(48, 64, CV_8UC3, bgr8);
  cv::Mat img16, linear;
  img8.convertTo(img16, CV_16UC3, 257.0);
  img8.convertTo(linear, CV_32FC3, 1 / 255.0);
  cv::pow(linear, 2.2, linear);  // what a viewer shows as img8
  struct Case {
    std::string name;
    cv::Mat image;
  };
  const fs::path folder = *dir_ / "formats";
  fs::create_directories(folder);
  for (const Case& c : {Case{"a.png", img16}, Case{"b.tif", img16}, Case{"c.exr", linear}})
    ASSERT_TRUE(cv::imwrite((folder / c.name).string(), c.image)) << c.name;
  // Each as a two-image folder of its own.
  for (const std::string name : {"a.png", "b.tif", "c.exr"}) {
    const fs::path one = *dir_ / ("one_" + name);
    fs::create_directories(one);
    fs::copy_file(folder / name, one / ("f0001" + fs::path(name).extension().string()));
    fs::copy_file(folder / name, one / ("f0002" + fs::path(name).extension().string()));
    const std::vector<Frame> frames = ReadAll(one.string());
    ASSERT_EQ(frames.size(), 2u) << name;
    const cv::Vec3b px = frames[0].bgr.at<cv::Vec3b>(10, 10);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(px[ch], bgr8[ch], 2) << name << " channel " << ch;
  }
  const fs::path dpx = *dir_ / "dpx";
  fs::create_directories(dpx);
  for (const std::string n : {"1001", "1002"})
    Make("dpx/plate." + n + ".dpx",
         "-f lavfi -i color=c=0xc87828:size=64x48 -frames:v 1 -pix_fmt gbrp10le");
  const std::vector<Frame> frames = ReadAll((dpx / "plate.%04d.dpx").string());
  ASSERT_EQ(frames.size(), 2u);
  const cv::Vec3b px = frames[1].bgr.at<cv::Vec3b>(10, 10);
  EXPECT_NEAR(px[0], 0x28, 3);
  EXPECT_NEAR(px[1], 0x78, 3);
  EXPECT_NEAR(px[2], 0xc8, 3);

  const fs::path bad = *dir_ / "bad";
  fs::create_directories(bad);
  for (const std::string name : {"f0001.exr", "f0001.dpx"}) {
    fs::remove_all(bad);
    fs::create_directories(bad);
    std::ofstream(bad / name) << "not an image\n";
    try {
      ReadAll(bad.string());
      ADD_FAILURE() << "no error for " << name;
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), (bad / name).string());
      EXPECT_EQ(e.reason().rfind(name == "f0001.exr" ? "not an image OpenCV can read"
                                                     : "not an image FFmpeg can read",
                                 0),
                0u)
          << e.what();
    }
  }
}

// A PNG or JPEG cut short in the middle of a sequence is an error naming
// that image (not a grey half-frame, not a second line from libpng/libjpeg).
TEST_F(FrameSourceTest, TruncatedImageInASequence) {
  cv::Mat img(120, 160, CV_8UC3);
  cv::randu(img, 0, 255);
  for (const std::string ext : {"png", "jpg"}) {
    const fs::path folder = *dir_ / ("cut_" + ext);
    fs::create_directories(folder);
    for (int i = 0; i < 4; ++i)
      cv::imwrite((folder / ("f" + std::to_string(i) + "." + ext)).string(), img);
    EXPECT_EQ(ReadAll(folder.string()).size(), 4u) << ext << ": complete files";
    const fs::path cut = folder / ("f2." + ext);
    fs::resize_file(cut, fs::file_size(cut) / 2);
    try {
      ReadAll(folder.string());
      ADD_FAILURE() << "no error for the cut " << ext;
    } catch (const Error& e) {
      EXPECT_EQ(e.where(), cut.string());
      EXPECT_NE(e.reason().find("truncated"), std::string::npos) << e.what();
    }
  }
}

// A bit flipped inside a PNG of a sequence: one error naming that image, and
// not a line of libpng's (or OpenCV's) own on stderr before it.
TEST_F(FrameSourceTest, CorruptImageIsOneLineWithoutCodecOutput) {
  cv::Mat img(120, 160, CV_8UC3);
  cv::randu(img, 0, 255);
  const fs::path folder = *dir_ / "flipped";
  fs::create_directories(folder);
  for (int i = 0; i < 3; ++i) cv::imwrite((folder / ("f" + std::to_string(i) + ".png")).string(), img);
  const fs::path bad = folder / "f1.png";
  std::string bytes;
  {
    std::ifstream in(bad, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  bytes[bytes.size() / 2] ^= 0x10;  // inside the image data; IEND still ends the file
  std::ofstream(bad, std::ios::binary | std::ios::trunc) << bytes;
  std::string message;
  ::testing::internal::CaptureStderr();
  try {
    ReadAll(folder.string());
  } catch (const Error& e) {
    message = e.what();
  }
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(printed, "");
  EXPECT_EQ(message.rfind(bad.string() + ": not an image OpenCV can read", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(FrameSourceOptionsTest, Check) {
  FrameSourceOptions o;
  EXPECT_NO_THROW(o.Check());
  o.max_working_side = -1;
  EXPECT_THROW(o.Check(), UsageError);
  o = {};
  o.decode_threads = -2;
  EXPECT_THROW(o.Check(), UsageError);
  o = {};
  o.color_max_side = -1;
  EXPECT_THROW(o.Check(), UsageError);
  o = {};
  o.image_sequence_fps = 0;
  EXPECT_THROW(o.Check(), UsageError);
}

}  // namespace
}  // namespace hapcine
