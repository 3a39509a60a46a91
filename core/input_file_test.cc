#include "core/input_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <new>
#include <stdexcept>
#include <string>

#include "core/camera_path.h"
#include "core/error.h"
#include "core/error_message.h"
#include "core/haptic_track.h"

namespace hapcine {
namespace {

namespace fs = std::filesystem;

class InputFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("hapcine_input_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    regular_ = (dir_ / "file.txt").string();
    std::ofstream(regular_) << "hello\n";
    fifo_ = (dir_ / "fifo").string();
    ASSERT_EQ(::mkfifo(fifo_.c_str(), 0600), 0);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  // The message of the Error `f` throws, or "" if none.
  template <typename F>
  static std::string ErrorOf(F f) {
    try {
      f();
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
  std::string regular_, fifo_;
};

TEST_F(InputFileTest, RefusesWhatIsNotARegularFileWithOneReason) {
  EXPECT_NO_THROW(CheckRegularFile(regular_));
  EXPECT_TRUE(IsRegularFile(regular_));
  EXPECT_EQ(ErrorOf([&] { CheckRegularFile(fifo_); }), fifo_ + ": not a regular file");
  EXPECT_EQ(ErrorOf([&] { CheckRegularFile("/dev/zero"); }), "/dev/zero: not a regular file");
  EXPECT_EQ(ErrorOf([&] { CheckRegularFile(dir_.string()); }),
            dir_.string() + ": is a directory");
  const std::string missing = (dir_ / "missing.csv").string();
  EXPECT_EQ(ErrorOf([&] { CheckRegularFile(missing); }), missing + ": no such file");
  EXPECT_EQ(ErrorOf([&] { CheckRegularFile(regular_ + "/below"); }),
            regular_ + "/below: no such file");
  EXPECT_FALSE(ErrorOf([&] { CheckRegularFile(""); }).empty());
  EXPECT_FALSE(IsRegularFile(fifo_));
  EXPECT_FALSE(IsRegularFile("/dev/null"));
  EXPECT_FALSE(IsRegularFile(""));
  // A symlink to a regular file is read through.
  const std::string link = (dir_ / "link").string();
  fs::create_symlink(regular_, link);
  InputFile in(link);
  std::string line;
  EXPECT_TRUE(std::getline(in.stream(), line));
  EXPECT_EQ(line, "hello");
}

// The two file contracts' readers: a FIFO would block them, /dev/zero fill
// memory, a directory read as "no header row".
TEST_F(InputFileTest, CameraPathAndHapticTrackReadersRefuseNonRegularFiles) {
  for (const std::string& bad : {fifo_, std::string("/dev/zero"), dir_.string()}) {
    const std::string reason = bad == dir_.string() ? "is a directory" : "not a regular file";
    EXPECT_EQ(ErrorOf([&] { ReadCameraPathFile(bad); }), bad + ": " + reason);
    EXPECT_EQ(ErrorOf([&] { ReadHapticTrackFile(bad); }), bad + ": " + reason);
  }
}

TEST_F(InputFileTest, ScopeNamesTheFileAnEscapingExceptionWasReading) {
  const std::string outer = "outer.csv", inner = "inner.csv";
  try {
    const InputScope a(outer);
    const InputScope b(inner);
    throw std::bad_alloc();
  } catch (const std::bad_alloc&) {
    EXPECT_EQ(InputOfEscapedException(), inner);  // the innermost
    EXPECT_EQ(EscapedExceptionMessage(std::current_exception()), "inner.csv: out of memory");
  }
  ForgetInputOfEscapedException();
  EXPECT_EQ(InputOfEscapedException(), "");
  // An exception caught inside a scope that then ends normally is forgotten.
  {
    const InputScope a(outer);
    try {
      const InputScope b(inner);
      throw std::runtime_error("handled");
    } catch (const std::runtime_error&) {
    }
  }
  EXPECT_EQ(InputOfEscapedException(), "");
  try {
    throw std::bad_alloc();
  } catch (...) {
    EXPECT_EQ(EscapedExceptionMessage(std::current_exception()), "out of memory");
  }
}

TEST(ErrorMessageTest, OneWholeLineForEveryException) {
  auto message = [](auto thrown) {
    try {
      throw thrown;
    } catch (...) {
      return EscapedExceptionMessage(std::current_exception());
    }
  };
  ForgetInputOfEscapedException();
  // A NUL or a newline quoted from an input neither cuts nor breaks the line.
  const std::string field("1.5\0junk\nmore", 13);
  EXPECT_EQ(message(Error("c.csv:3", "'" + field + "' is not a number")),
            "c.csv:3: '1.5\\0junk\\nmore' is not a number");
  EXPECT_EQ(message(Error("a\x1b[31m.csv", "bad")), "a\\x1b[31m.csv: bad");
  EXPECT_EQ(message(Error("", "no file")), "no file");
  EXPECT_EQ(message(UsageError("bad\noption")), "bad\\noption");
  // Not hapcine errors: never the bare "map::at".
  EXPECT_EQ(message(std::out_of_range("map::at")), "internal error (out of range: map::at)");
  EXPECT_EQ(message(std::runtime_error("boom")), "internal error (boom)");
  EXPECT_EQ(message(42), "internal error (unknown exception)");
  EXPECT_EQ(EscapeControlChars("tab\there\r\x7f"), "tab\\there\\r\\x7f");
  EXPECT_EQ(EscapeControlChars("caf\xc3\xa9"), "caf\xc3\xa9");  // UTF-8 is kept
}

}  // namespace
}  // namespace hapcine
