#include "batch/subprocess.h"

#include <gtest/gtest.h>

#include "batch/fake_step_for_test.h"
#include "core/error.h"

namespace hapcine::batch {
namespace {

using testutil::TempDir;
using testutil::WriteFile;

TEST(SubprocessTest, ExitCodeAndLastStderrLine) {
  TempDir d;
  const std::string log = d.path() + "/log";
  ProcessResult r = RunProcess(
      {"/bin/sh", "-c", "echo out; echo first >&2; echo 'last line  ' >&2; echo >&2; exit 3"}, log);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.signal, 0);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.last_line, "last line");
  EXPECT_EQ(r.Reason(), "exit 3: last line");
  r = RunProcess({"/bin/true"}, log);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.Reason(), "exit 0");
}

TEST(SubprocessTest, SignalAndMissingProgram) {
  TempDir d;
  const std::string log = d.path() + "/log";
  ProcessResult r = RunProcess({"/bin/sh", "-c", "kill -SEGV $$"}, log);
  EXPECT_EQ(r.signal, 11);
  EXPECT_EQ(r.Reason().rfind("killed by signal 11 (", 0), 0u) << r.Reason();
  r = RunProcess({d.path() + "/nope"}, log);
  EXPECT_EQ(r.exit_code, 127);
  EXPECT_NE(r.last_line.find("cannot execute step program"), std::string::npos);
  EXPECT_THROW(RunProcess({"/bin/true"}, d.path() + "/no/such/dir/log"), Error);
  EXPECT_THROW(RunProcess({}, log), Error);
}

TEST(SubprocessTest, ArgumentsWithSpacesAndUnicodeArriveIntact) {
  TempDir d;
  const std::string log = d.path() + "/log";
  const ProcessResult r = RunProcess(
      {"/bin/sh", "-c", "printf '%s|' \"$@\" >&2", "sh", "é clip.mp4", "日本 x", ""}, log);
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.last_line, "é clip.mp4|日本 x||");
}

}  // namespace
}  // namespace hapcine::batch
