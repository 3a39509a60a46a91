// End-to-end: what the `hapcine` program prints when an input is bad. Every
// failure is exactly one line, "hapcine <command>: <file>: <reason>", exit 1
// (2 for usage); inputs that are not regular files (a FIFO, /dev/zero, a
// directory) are refused at once instead of blocking or filling memory.

#include <gtest/gtest.h>

#include <algorithm>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "core/haptic_track.h"
#include "study/plan.h"
#include "tests/run_hapcine.h"

namespace fs = std::filesystem;
using hapcine_test::Quote;
using hapcine_test::RunHapcine;
using hapcine_test::RunResult;

namespace {


// A valid camera path of `n` frames at 8 fps from `t0` (a slow pan).
std::string CameraPathText(int n, double t0) {
  std::ostringstream s;
  s.precision(17);
  s << "frame,time_s,x,y,z,qw,qx,qy,qz,fov_deg\n";
  for (int i = 0; i < n; ++i) {
    const double half = 0.002 * i;  // half the pan angle, rad
    s << i << "," << t0 + 0.125 * i << ",0,0,0," << std::cos(half) << ",0," << std::sin(half)
      << ",0,50\n";
  }
  return s.str();
}

class MessagesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("hapcine_messages_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    fifo_ = dir_ / "pipe.csv";
    ASSERT_EQ(::mkfifo(fifo_.c_str(), 0600), 0);
    path_ = dir_ / "c.camera.csv";
    std::ofstream(path_) << CameraPathText(24, 0);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  RunResult Run(const std::string& args) const { return RunHapcine(args, dir_); }

  fs::path dir_, fifo_, path_;
};

TEST_F(MessagesTest, EvalRefusesFifoDeviceAndDirectory) {
  for (const std::string& bad : {fifo_.string(), std::string("/dev/zero"), dir_.string()}) {
    const RunResult r = Run("eval --gt " + Quote(bad) + " --est " + Quote(path_));
    EXPECT_EQ(r.exit_code, 1) << bad;
    const std::string reason = bad == dir_.string() ? "is a directory" : "not a regular file";
    EXPECT_EQ(r.err, "hapcine eval: " + bad + ": " + reason + "\n");
  }
}

TEST_F(MessagesTest, PlayRefusesATrackThatIsNotARegularFile) {
  for (const std::string& bad : {fifo_.string(), std::string("/dev/zero"), dir_.string()}) {
    const RunResult r = Run("play --no-video --device none --track " + Quote(bad));
    EXPECT_EQ(r.exit_code, 1) << bad;
    const std::string reason = bad == dir_.string() ? "is a directory" : "not a regular file";
    EXPECT_EQ(r.err, "hapcine play: " + bad + ": " + reason + "\n");
  }
}

// Valid times near 1e15 s: the track counts from the first frame.
TEST_F(MessagesTest, HapticsAcceptsAHugeMediaClock) {
  const fs::path far = dir_ / "far.camera.csv";
  std::ofstream(far) << CameraPathText(24, 1e15);
  const fs::path out = dir_ / "far.haptic.csv";
  const RunResult r = Run("haptics " + Quote(far) + " -o " + Quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const hapcine::HapticTrack track = hapcine::ReadHapticTrackFile(out.string());
  EXPECT_EQ(track.samples.front().time_s, 0);
  EXPECT_EQ(track.metadata.at("time_origin_s"), "1e+15");
}

// A NUL byte (or a newline) quoted from a field neither cuts nor breaks the line.
TEST_F(MessagesTest, ControlBytesInAFieldAreEscaped) {
  std::string text = CameraPathText(3, 0);
  const size_t x = text.find("\n1,0.125,0") + 9;  // row 2 (file line 3), column x
  text.replace(x, 1, std::string("0\0junk\x1b", 7));
  std::ofstream(path_, std::ios::binary) << text;
  const RunResult r = Run("haptics " + Quote(path_) + " -o " + Quote(dir_ / "o.haptic.csv"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "hapcine haptics: " + path_.string() +
                       ":3: '0\\0junk\\x1b' in column 'x' is not a number\n");
}

TEST_F(MessagesTest, BatchUnknownModelIsAUsageErrorBeforeAnyWork) {
  std::ofstream(dir_ / "lib.txt") << "/dev/null\n";
  const fs::path out = dir_ / "out";
  const RunResult r = Run("batch " + Quote(dir_ / "lib.txt") + " -o " + Quote(out) +
                          " --models cinematic,bogus");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "hapcine batch: unknown model 'bogus' in --models (expected cinematic, semantic, "
            "random or none)\n");
  EXPECT_FALSE(fs::exists(out));
}

// A FIFO in a manifest used to block the batch while hashing, for ever.
TEST_F(MessagesTest, BatchFailsFifoAndDeviceEntriesWithoutBlocking) {
  std::ofstream(dir_ / "lib.txt") << fifo_.string() << "\n/dev/zero\n";
  const fs::path out = dir_ / "out";
  const RunResult r =
      Run("batch " + Quote(dir_ / "lib.txt") + " -o " + Quote(out) + " --progress quiet");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  std::ifstream in(out / "summary.txt");
  std::stringstream summary;
  summary << in.rdbuf();
  EXPECT_NE(summary.str().find(fifo_.string() + ": not a regular file"), std::string::npos)
      << summary.str();
  EXPECT_NE(summary.str().find("/dev/zero: not a regular file"), std::string::npos)
      << summary.str();
}

class StudyMessagesTest : public MessagesTest {
 protected:
  // A plan of one clip (a stand-in video, four tracks), then edited by
  // `edit` with its id recomputed, as a hand edit that kept the id valid.
  fs::path EditedPlan(const std::function<void(hapcine::study::StudyPlan*)>& edit) {
    const std::string video = (dir_ / "clip.mp4").string();
    std::ofstream(video) << "stand-in";
    int kind = 0;
    for (const char* c : {"cinematic", "semantic", "none", "random"}) {
      hapcine::HapticTrack t;
      t.rate_hz = 100;
      t.model = c;
      t.source = video;
      for (int i = 0; i <= 100; ++i) {
        hapcine::HapticSample s;
        s.time_s = i / 100.0;
        s.pos_m[0].x() = kind * 0.001 * std::sin(i * (kind + 1) * 0.1);
        t.samples.push_back(s);
      }
      hapcine::WriteHapticTrackFile(t, (dir_ / (std::string("clip.") + c + ".haptic.csv")).string());
      ++kind;
    }
    hapcine::study::PlanOptions o;
    o.clips = {video};
    o.participants = 1;
    hapcine::study::StudyPlan plan = hapcine::study::MakePlan(o, nullptr);
    edit(&plan);
    plan.plan_id = hapcine::study::ComputePlanId(plan);
    const fs::path path = dir_ / "plan.json";
    hapcine::study::WritePlanFile(plan, path.string());
    std::ofstream answers(dir_ / "answers.txt");
    for (int i = 0; i < 12; ++i) answers << "1\n";
    return path;
  }
  RunResult RunStudy(const fs::path& plan) const {
    return Run("study run " + Quote(plan) + " --participant P01 --player-cmd /bin/true --responses " +
               Quote(dir_ / "answers.txt"));
  }
};

TEST_F(StudyMessagesTest, EmptyTrialGroupAndUnknownConditionAreOneLine) {
  fs::path plan = EditedPlan([](hapcine::study::StudyPlan* p) {
    p->participants[0].trials[2].first.clear();  // crashed `study run`
  });
  RunResult r = RunStudy(plan);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "hapcine study: " + plan.string() + ": participant P01 trial 2: first group is empty\n");

  plan = EditedPlan([](hapcine::study::StudyPlan* p) {
    p->participants[0].trials[2].second = {"bogus"};  // printed only "map::at"
  });
  r = RunStudy(plan);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "hapcine study: " + plan.string() +
                       ": participant P01 trial 2: unknown condition 'bogus' in second group\n");
}

TEST_F(StudyMessagesTest, TrackThatIsADeviceIsRefusedBeforePlaying) {
  const fs::path plan = EditedPlan([](hapcine::study::StudyPlan* p) {
    p->clips[0].tracks["random"].path = "/dev/zero";
  });
  const RunResult r = RunStudy(plan);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "hapcine study: /dev/zero: not a regular file\n");
}

// Made with the ffmpeg program, as the extract tests do.
bool Ffmpeg(const std::string& args) {
  const std::string cmd = "ffmpeg -nostdin -hide_banner -loglevel error -y " + args;
  return std::system(cmd.c_str()) == 0;
}

// Ceres bounds its threads to the cores with a warning per solve; hapcine
// bounds them first, so nothing is printed.
TEST_F(MessagesTest, EstimateWithHugeThreadCountPrintsNoSolverWarnings) {
  const fs::path video = dir_ / "pan.mp4";
  ASSERT_TRUE(Ffmpeg("-f lavfi -i testsrc=size=320x240:rate=24 -t 1 -vf scroll=h=0.002 "
                     "-c:v libx264 -pix_fmt yuv420p " + Quote(video)));
  // Beyond the option's range: one usage line naming it, before any work.
  RunResult r = Run("estimate -q " + Quote(video) + " -o " + Quote(dir_ / "pan.camera.csv") +
                    " --threads 100000");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--threads"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 2) << r.err;  // the line and "Run ... --help"
  // In range but more than the cores: the solver is given at most the cores,
  // so it prints no warning of its own.
  r = Run("estimate -q " + Quote(video) + " -o " + Quote(dir_ / "pan.camera.csv") + " --threads 256");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("num_threads"), std::string::npos) << r.err;
}

// A bit flipped in one PNG of an image folder: hapcine's line only, not
// libpng's own before it.
TEST_F(MessagesTest, CorruptImageInAFolderIsOneLine) {
  const fs::path folder = dir_ / "frames";
  fs::create_directories(folder);
  ASSERT_TRUE(Ffmpeg("-f lavfi -i testsrc=size=160x120:rate=8 -frames:v 6 " +
                     Quote(folder / "f%02d.png")));
  const fs::path bad = folder / "f03.png";
  std::string bytes;
  {
    std::ifstream in(bad, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  bytes[bytes.size() / 2] ^= 0x10;
  std::ofstream(bad, std::ios::binary | std::ios::trunc) << bytes;
  const RunResult r = Run("estimate -q " + Quote(folder) + " -o " + Quote(dir_ / "f.camera.csv"));
  EXPECT_EQ(r.exit_code, 1);
  const std::string start = "hapcine estimate: " + bad.string() + ": not an image OpenCV can read";
  EXPECT_EQ(r.err.rfind(start, 0), 0u) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;  // one line
}

}  // namespace
