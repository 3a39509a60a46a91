#include "study/keypress.h"

#include <termios.h>
#include <unistd.h>

#include <cerrno>

namespace hapcine::study {

bool IsTerminal(int fd) { return ::isatty(fd) == 1; }

std::optional<char> ReadKeyPress(int fd) {
  termios saved{};
  if (::tcgetattr(fd, &saved) != 0) return std::nullopt;
  termios raw = saved;
  raw.c_lflag &= ~(ICANON | ECHO | ISIG);  // no line editing, no echo, ^C is a byte
  raw.c_cc[VMIN] = 1;
  raw.c_cc[VTIME] = 0;
  ::tcflush(fd, TCIFLUSH);  // type-ahead from the playback is not an answer
  if (::tcsetattr(fd, TCSANOW, &raw) != 0) return std::nullopt;
  char c = 0;
  ssize_t n;
  do {
    n = ::read(fd, &c, 1);
  } while (n < 0 && errno == EINTR);
  ::tcsetattr(fd, TCSANOW, &saved);
  if (n != 1) return std::nullopt;
  return c;
}

}  // namespace hapcine::study
