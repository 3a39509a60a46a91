#include "core/stop_signal.h"

#include <gtest/gtest.h>

#include <csignal>

namespace hapcine {
namespace {

TEST(StopSignal, FlagIsSetBySigintAndSigterm) {
  ClearStopRequest();
  InstallStopSignals();
  EXPECT_FALSE(StopRequested());
  std::raise(SIGINT);
  EXPECT_TRUE(StopRequested());
  EXPECT_EQ(StopSignal(), SIGINT);
  ClearStopRequest();
  std::raise(SIGTERM);
  EXPECT_TRUE(StopRequested());
  EXPECT_EQ(StopSignal(), SIGTERM);
  ClearStopRequest();
  RequestStop();  // the program's own request names no signal
  EXPECT_TRUE(StopRequested());
  EXPECT_EQ(StopSignal(), 0);
  ClearStopRequest();
  RestoreStopSignals();
}

TEST(StopSignal, ScopedInstallRestoresThePreviousHandler) {
  struct sigaction before {};
  sigaction(SIGTERM, nullptr, &before);
  {
    ScopedStopSignals scoped;
    struct sigaction during {};
    sigaction(SIGTERM, nullptr, &during);
    EXPECT_NE(during.sa_handler, before.sa_handler);
  }
  struct sigaction after {};
  sigaction(SIGTERM, nullptr, &after);
  EXPECT_EQ(after.sa_handler, before.sa_handler);
  ClearStopRequest();
}

}  // namespace
}  // namespace hapcine
