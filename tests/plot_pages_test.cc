// End-to-end: `hapcine plot` on a two-hour track stays readable: pages of N
// minutes (fig-001.png ...), one page per shot, a --from/--to range given as
// running time, cut lines where the `shot` column changes.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "datasets/plot_figure.h"
#include "tests/run_hapcine.h"

namespace fs = std::filesystem;
using hapcine_test::Quote;
using hapcine_test::RunHapcine;

namespace {

class PlotPagesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("hapcine_plot_pages_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    // Two hours at 10 Hz, a new shot every 20 minutes (six shots).
    std::ofstream out(dir_ / "film.haptic.csv");
    out << "# rate_hz=10\n# model=cinematic\n# source=film.mp4\n"
           "time_s,head_x,head_y,head_z,left_x,left_y,left_z,right_x,right_y,right_z,shot\n";
    for (int i = 0; i < 72000; ++i) {
      const double t = i / 10.0;
      char row[160];
      std::snprintf(row, sizeof row, "%.1f,%.4f,0,0,0,%.4f,0,0,0,0,%d\n", t,
                    0.02 * std::sin(t / 7), 0.01 * std::cos(t / 3), i / 12000);
      out << row;
    }
  }
  void TearDown() override { fs::remove_all(dir_); }
  size_t CountPng() const {
    size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir_)) n += e.path().extension() == ".png";
    return n;
  }
  fs::path dir_;
};

TEST_F(PlotPagesTest, TwoHoursInTenMinutePages) {
  const auto r = RunHapcine("plot haptic " + Quote(dir_ / "film.haptic.csv") +
                                " --page-minutes 10 --format png -o " + Quote(dir_ / "fig"),
                            dir_);
  ASSERT_EQ(r.exit_code, 0) << hapcine_test::Slurp(dir_ / "stderr.txt");
  EXPECT_EQ(CountPng(), 12u);
  EXPECT_TRUE(fs::exists(dir_ / "fig-001.png"));
  EXPECT_TRUE(fs::exists(dir_ / "fig-012.png"));
  EXPECT_FALSE(fs::exists(dir_ / "fig.png"));
  // Page 2 (10-20 min) has no cut, page 3 (20-30 min) starts with one.
  const hapcine::PlotColor c = hapcine::CutLineColor();
  auto cut_pixels = [&](const char* name) {
    const cv::Mat img = cv::imread((dir_ / name).string(), cv::IMREAD_COLOR);
    int n = 0;
    for (int y = 0; y < img.rows; ++y)
      for (int x = 0; x < img.cols * 3 / 4; ++x) {  // the data areas, not the legend
        const cv::Vec3b p = img.at<cv::Vec3b>(y, x);
        n += p[0] == c.b && p[1] == c.g && p[2] == c.r;
      }
    return n;
  };
  EXPECT_EQ(cut_pixels("fig-002.png"), 0);
  EXPECT_GT(cut_pixels("fig-003.png"), 300);  // three panels tall, two pixels wide
}

TEST_F(PlotPagesTest, OnePagePerShotAndARunningTimeRange) {
  auto r = RunHapcine("plot haptic " + Quote(dir_ / "film.haptic.csv") +
                          " --page-per-shot --format svg -o " + Quote(dir_ / "shot"),
                      dir_);
  ASSERT_EQ(r.exit_code, 0) << hapcine_test::Slurp(dir_ / "stderr.txt");
  EXPECT_TRUE(fs::exists(dir_ / "shot-006.svg"));
  EXPECT_FALSE(fs::exists(dir_ / "shot-007.svg"));
  r = RunHapcine("plot haptic " + Quote(dir_ / "film.haptic.csv") +
                     " --from 1:00:00 --to 1:05:30 --format png -o " + Quote(dir_ / "range"),
                 dir_);
  ASSERT_EQ(r.exit_code, 0) << hapcine_test::Slurp(dir_ / "stderr.txt");
  EXPECT_EQ(CountPng(), 1u);
  r = RunHapcine("plot haptic " + Quote(dir_ / "film.haptic.csv") +
                     " --from 1:10 --to 0:30 -o " + Quote(dir_ / "bad"),
                 dir_);
  EXPECT_EQ(r.exit_code, 2);
  r = RunHapcine("plot haptic " + Quote(dir_ / "film.haptic.csv") + " --from 1:75 -o " +
                     Quote(dir_ / "bad"),
                 dir_);
  EXPECT_EQ(r.exit_code, 2);
}

}  // namespace
