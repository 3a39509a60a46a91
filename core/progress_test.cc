#include "core/progress.h"

#include <gtest/gtest.h>

#include <sstream>

namespace hapcine {
namespace {

// A progress on a string, with a clock the test sets.
struct Bench {
  std::ostringstream out;
  double now = 0;
  Progress Make(ProgressMode mode, const std::string& label, const std::string& unit) {
    return Progress(out, mode, label, unit, [this] { return now; });
  }
};

TEST(ProgressTest, FormatDuration) {
  EXPECT_EQ(FormatDuration(4.24), "4.2s");
  EXPECT_EQ(FormatDuration(192), "3m12s");
  EXPECT_EQ(FormatDuration(3720), "1h02m");
  EXPECT_EQ(FormatDuration(-1), "?");
  EXPECT_EQ(FormatDuration(0.0 / 0.0), "?");
}

TEST(ProgressTest, BarAndLineTexts) {
  ProgressSnapshot s{300, 1000, 29, "24.1/s"};
  EXPECT_EQ(Progress::BarText("estimate", "frames", s),
            "estimate [#########.....................] 300/1000 frames  24.1/s  ETA 29.0s");
  EXPECT_EQ(Progress::LineText("estimate", "frames", s), "estimate: 300/1000 frames, 24.1/s, ETA 29.0s");
  // Unknown total: no bar, no ETA; fractional amounts with one decimal.
  EXPECT_EQ(Progress::BarText("play", "s", {12.25, 0, -1, ""}), "play 12.2 s");
  EXPECT_EQ(Progress::LineText("play", "", {3, 0, -1, ""}), "play: 3");
  // More done than the total (an estimated frame count): a full bar.
  EXPECT_EQ(Progress::BarText("x", "", {5, 4, 0, ""}), "x [##############################] 5/4  ETA 0.0s");
}

TEST(ProgressTest, BarRedrawsInPlaceAtMostEveryFifthOfASecond) {
  Bench b;
  b.now = 100;
  Progress p = b.Make(ProgressMode::kBar, "estimate", "frames");
  b.now = 102;
  p.Update(50, 100);  // 25/s, 2 s left
  b.now = 102.1;
  p.Update(51, 100);  // too soon: not drawn
  b.now = 104;
  p.Finish(100);
  EXPECT_EQ(b.out.str(),
            "\r\033[Kestimate [###############...............] 50/100 frames  25.0/s  ETA 2.0s\n"
            "estimate: 100 frames in 4.0s (25.0/s)\n");
}

TEST(ProgressTest, LinesEveryFiveSecondsAndLinesOfTheirOwn) {
  Bench b;
  Progress p = b.Make(ProgressMode::kLines, "haptics", "frames");
  b.now = 1;
  p.Update(10, 0);
  b.now = 3;
  p.Update(30, 0);  // 2 s after the last line: not printed
  p.Line("haptics: a warning");
  b.now = 6.5;
  p.Update(65, 0);
  p.Close();  // nothing to end
  EXPECT_EQ(b.out.str(),
            "haptics: 10 frames, 10.0/s\n"
            "haptics: a warning\n"
            "haptics: 65 frames, 10.0/s\n");
}

TEST(ProgressTest, LineClearsTheBarAndShowDrawsNow) {
  Bench b;
  Progress p = b.Make(ProgressMode::kBar, "batch", "films");
  p.Show({1, 4, 3, "elapsed 1.0s"});
  p.Show({1, 4, 3, "elapsed 1.0s"});  // not throttled
  p.Line("failed a: bad");
  p.Close();
  EXPECT_EQ(b.out.str(),
            "\r\033[Kbatch [#######.......................] 1/4 films  elapsed 1.0s  ETA 3.0s"
            "\r\033[Kbatch [#######.......................] 1/4 films  elapsed 1.0s  ETA 3.0s"
            "\r\033[Kfailed a: bad\n");
}

TEST(ProgressTest, QuietPrintsNothing) {
  Bench b;
  Progress p = b.Make(ProgressMode::kQuiet, "synth", "frames");
  for (double t : {1.0, 10.0, 20.0}) {
    b.now = t;
    p.Update(t, 20);
  }
  p.Show({1, 2, 1, ""});
  p.Line("x");
  p.Finish(2);
  EXPECT_EQ(b.out.str(), "");
}

TEST(ProgressTest, NothingDoneYetHasNoRate) {
  Bench b;
  Progress p = b.Make(ProgressMode::kLines, "convert", "frames");
  p.Update(0, 100);
  EXPECT_EQ(b.out.str(), "convert: 0/100 frames, ETA ?\n");
}

}  // namespace
}  // namespace hapcine
