#include "estimate/bundle/solver_log.h"

#include <glog/logging.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace hapcine {
namespace {

// Restores glog's level after each test (other tests in this binary log too).
class SolverLogTest : public ::testing::Test {
 protected:
  void SetUp() override { saved_ = FLAGS_minloglevel; }
  void TearDown() override {
    FLAGS_minloglevel = saved_;
    unsetenv("GLOG_minloglevel");
  }
  int saved_ = 0;
};

TEST_F(SolverLogTest, WarningsOfTheSolverDoNotReachStderr) {
  unsetenv("GLOG_minloglevel");
  QuietSolverLog();
  testing::internal::CaptureStderr();
  LOG(WARNING) << "Linear solver failure. Failed to compute a step";
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(err.find("Linear solver failure"), std::string::npos) << err;
}

TEST_F(SolverLogTest, ErrorsStillDo) {
  unsetenv("GLOG_minloglevel");
  QuietSolverLog();
  testing::internal::CaptureStderr();
  LOG(ERROR) << "an error the solver cannot recover from";
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("an error the solver cannot recover from"), std::string::npos) << err;
}

TEST_F(SolverLogTest, TheEnvironmentKeepsItsLevel) {
  FLAGS_minloglevel = google::GLOG_INFO;
  setenv("GLOG_minloglevel", "0", 1);
  QuietSolverLog();
  testing::internal::CaptureStderr();
  LOG(WARNING) << "shown on request";
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("shown on request"), std::string::npos) << err;
}

}  // namespace
}  // namespace hapcine
