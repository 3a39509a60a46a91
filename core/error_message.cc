#include "core/error_message.h"

#include <cstdio>
#include <new>
#include <stdexcept>

#include "core/error.h"
#include "core/input_file.h"

namespace hapcine {
namespace {

// "<file>: <reason>" when the file being read is known.
std::string WithInput(const std::string& reason) {
  const std::string input = InputOfEscapedException();
  return input.empty() ? reason : EscapeControlChars(input) + ": " + reason;
}

}  // namespace

std::string EscapeControlChars(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u != 0x7f) {
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\0') {
      out += "\\0";
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", u);
      out += buf;
    }
  }
  return out;
}

std::string EscapedExceptionMessage(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const Error& e) {
    // where() and reason() hold every byte; what() would stop at a NUL.
    const std::string reason = EscapeControlChars(e.reason());
    return e.where().empty() ? reason : EscapeControlChars(e.where()) + ": " + reason;
  } catch (const UsageError& e) {
    return EscapeControlChars(e.what());
  } catch (const std::bad_alloc&) {
    return WithInput("out of memory");
  } catch (const std::out_of_range& e) {
    // A lookup the code expected to succeed ("map::at"): a bug, not a reason.
    return WithInput(std::string("internal error (out of range: ") + EscapeControlChars(e.what()) +
                     ")");
  } catch (const std::exception& e) {
    return WithInput(std::string("internal error (") + EscapeControlChars(e.what()) + ")");
  } catch (...) {
    return WithInput("internal error (unknown exception)");
  }
}

}  // namespace hapcine
