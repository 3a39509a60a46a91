#pragma once
// The one line a command prints when an exception escapes it:
// "<file>: <reason>" for hapcine::Error, and for anything else a reason the
// user can act on ("out of memory"), with the file being read named when an
// InputScope (core/input_file.h) noted it. Bytes quoted from inputs are
// escaped, so the line stays one line and whole.

#include <exception>
#include <string>

namespace hapcine {

// `text` with every control byte written as an escape ("\n", "\0", "\x1b"):
// a file name or a field quoted from an input can neither break the message
// into lines nor cut it short (a NUL ends what() for anyone printing it).
std::string EscapeControlChars(const std::string& text);

// The message for `error` (non-null), without the "hapcine <cmd>: " prefix.
std::string EscapedExceptionMessage(const std::exception_ptr& error);

}  // namespace hapcine
