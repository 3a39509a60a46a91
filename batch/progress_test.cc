#include "batch/progress.h"

#include <gtest/gtest.h>

#include <sstream>

namespace hapcine::batch {
namespace {

TEST(ProgressTest, EtaCountsPendingAndTheRestOfRunningFilms) {
  EXPECT_LT(ProgressReporter::Eta(-1, {}, 10, 2), 0.0);  // unknown before any film finished
  EXPECT_DOUBLE_EQ(ProgressReporter::Eta(10, {}, 10, 2), 50.0);
  EXPECT_DOUBLE_EQ(ProgressReporter::Eta(10, {}, 0, 2), 0.0);
  EXPECT_DOUBLE_EQ(ProgressReporter::Eta(5, {}, 3, 0), 15.0);  // workers clamped to 1
  // Two running films 4 s and 12 s in (a film takes 10 s), 2 pending:
  // (6 + 0 + 2 x 10) / 2 workers.
  EXPECT_DOUBLE_EQ(ProgressReporter::Eta(10, {4, 12}, 2, 2), 13.0);
  EXPECT_DOUBLE_EQ(ProgressReporter::Eta(-1, {}, 0, 2), 0.0);  // nothing left
}

TEST(ProgressTest, InstantFailuresDoNotMakeTheEtaShort) {
  // Three 0.5 s failures, one 10 s film done: the mean is the done film's.
  EXPECT_DOUBLE_EQ(ProgressReporter::MeanFilmSeconds(1, 10, 3, 1.5, 2), 10.0);
  // Only failures so far and films still running: unknown, not 0.5 s.
  EXPECT_LT(ProgressReporter::MeanFilmSeconds(0, 0, 3, 1.5, 2), 0.0);
  // Only failures and nothing running: their mean.
  EXPECT_DOUBLE_EQ(ProgressReporter::MeanFilmSeconds(0, 0, 3, 1.5, 0), 0.5);
}

TEST(ProgressTest, LinesModePrintsOneLinePerFilmWithReason) {
  std::ostringstream out;
  ProgressReporter p(out, ProgressReporter::Mode::kLines, 2, 1);
  p.Finished("a-1234abcd", "done", 2.0, false, "");
  p.Finished("b-1234abcd", "failed", 0.5, false, "estimate: exit 1: bad");
  p.Close();
  EXPECT_EQ(out.str(),
            "batch: [1/2] done a-1234abcd (2.0s)\n"
            "batch: [2/2] failed b-1234abcd (0.5s): estimate: exit 1: bad\n");
}

TEST(ProgressTest, BarModeRedrawsInPlace) {
  std::ostringstream out;
  ProgressReporter p(out, ProgressReporter::Mode::kBar, 4, 2);
  p.Finished("a", "done", 2.0, false, "");
  p.Close();
  const std::string s = out.str();
  EXPECT_NE(s.find("\r\033[Kbatch [#######.......................] 1/4 films"), std::string::npos) << s;
  EXPECT_NE(s.find("ETA 3.0s"), std::string::npos) << s;
  EXPECT_EQ(s.back(), '\n');
}

TEST(ProgressTest, QuietModePrintsNothing) {
  std::ostringstream out;
  ProgressReporter p(out, ProgressReporter::Mode::kQuiet, 1, 1);
  p.Finished("a", "done", 1.0, false, "");
  p.Tick();
  p.Close();
  EXPECT_TRUE(out.str().empty());
}

}  // namespace
}  // namespace hapcine::batch
