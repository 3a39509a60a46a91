#include "study/keypress.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <thread>

namespace hapcine::study {
namespace {

// A pseudo-terminal: the test types on the master side, ReadKeyPress reads
// the slave side as if it were the participant's terminal.
struct Pty {
  int master = -1, slave = -1;
  Pty() {
    master = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) return;
    slave = ::open(::ptsname(master), O_RDWR | O_NOCTTY);
  }
  ~Pty() {
    if (slave >= 0) ::close(slave);
    if (master >= 0) ::close(master);
  }
  void Type(const char* keys) const { ASSERT_GT(::write(master, keys, strlen(keys)), 0); }
};

TEST(KeyPressTest, OneKeyWithoutEnterTypeAheadDiscardedTerminalRestored) {
  Pty pty;
  if (pty.slave < 0) GTEST_SKIP() << "no pseudo-terminal available";
  EXPECT_TRUE(IsTerminal(pty.slave));
  pty.Type("1");  // pressed while the stimulus played: must not answer
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  std::thread later([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    pty.Type("2");  // no newline: one key press is enough
  });
  const std::optional<char> key = ReadKeyPress(pty.slave);
  later.join();
  ASSERT_TRUE(key.has_value());
  EXPECT_EQ(*key, '2');
  termios t{};
  ASSERT_EQ(::tcgetattr(pty.slave, &t), 0);
  EXPECT_TRUE(t.c_lflag & ICANON);  // line mode and echo are back
  EXPECT_TRUE(t.c_lflag & ECHO);
  EXPECT_TRUE(t.c_lflag & ISIG);
}

TEST(KeyPressTest, CtrlCIsAByteNotASignal) {
  Pty pty;
  if (pty.slave < 0) GTEST_SKIP() << "no pseudo-terminal available";
  std::thread later([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    pty.Type("\x03");
  });
  const std::optional<char> key = ReadKeyPress(pty.slave);
  later.join();
  ASSERT_TRUE(key.has_value());
  EXPECT_EQ(*key, 3);
}

TEST(KeyPressTest, NotATerminal) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  EXPECT_FALSE(IsTerminal(fds[0]));
  EXPECT_FALSE(ReadKeyPress(fds[0]).has_value());  // tcgetattr fails: no key, no hang
  ::close(fds[0]);
  ::close(fds[1]);
}

}  // namespace
}  // namespace hapcine::study
