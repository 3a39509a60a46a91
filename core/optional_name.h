#pragma once
// OptionalName: an optional short text drawn from a small vocabulary (a camera
// path's `model`, a haptic track's `effect`), stored in 2 bytes as an index
// into one process-wide table of the distinct texts. A film has millions of
// rows but a handful of distinct values; a std::optional<std::string> per row
// took 40 bytes. It reads like std::optional<std::string>: has_value(),
// operator bool, *name, name->, value_or(), reset(), = "text", = std::nullopt,
// and compares with strings.

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>

namespace hapcine {

class OptionalName {
 public:
  // Distinct texts a process can hold; the readers report more as an error.
  static constexpr size_t kCapacity = 65535;

  OptionalName() = default;
  OptionalName(std::nullopt_t) {}  // NOLINT: implicit, like std::optional
  // Throws hapcine::Error when the table is full (kCapacity distinct texts).
  OptionalName(const std::string& text);  // NOLINT
  OptionalName(const char* text) : OptionalName(std::string(text)) {}  // NOLINT
  OptionalName(const std::optional<std::string>& text)  // NOLINT
      : OptionalName(text ? OptionalName(*text) : OptionalName()) {}

  // Like the constructor, but returns false instead of throwing when full.
  static bool TryMake(const std::string& text, OptionalName* out);

  bool has_value() const { return id_ != 0; }
  explicit operator bool() const { return id_ != 0; }
  const std::string& operator*() const;  // undefined without a value, as std::optional
  const std::string* operator->() const { return &**this; }
  const std::string& value() const;  // throws std::bad_optional_access without a value
  std::string value_or(const std::string& fallback) const {
    return id_ ? **this : fallback;
  }
  void reset() { id_ = 0; }
  operator std::optional<std::string>() const {  // NOLINT
    return id_ ? std::optional<std::string>(**this) : std::nullopt;
  }

  friend bool operator==(const OptionalName& a, const OptionalName& b) { return a.id_ == b.id_; }
  friend bool operator!=(const OptionalName& a, const OptionalName& b) { return a.id_ != b.id_; }
  friend bool operator==(const OptionalName& a, const std::string& b) { return a && *a == b; }
  friend bool operator==(const std::string& a, const OptionalName& b) { return b == a; }
  friend bool operator!=(const OptionalName& a, const std::string& b) { return !(a == b); }
  friend bool operator!=(const std::string& a, const OptionalName& b) { return !(b == a); }
  friend bool operator==(const OptionalName& a, const char* b) { return a && *a == b; }
  friend bool operator==(const char* a, const OptionalName& b) { return b == a; }
  friend bool operator!=(const OptionalName& a, const char* b) { return !(a == b); }
  friend bool operator!=(const char* a, const OptionalName& b) { return !(b == a); }

 private:
  uint16_t id_ = 0;  // 0: no value; else 1 + index in the table
};

// A reader's interning of one column: remembers the last text, which the
// next rows mostly repeat, so most rows take no lock.
class RecentName {
 public:
  // False when the table is full (OptionalName::kCapacity distinct texts).
  bool Make(const std::string& text, OptionalName* out) {
    if (!(name_ && text == *name_) && !OptionalName::TryMake(text, &name_)) return false;
    *out = name_;
    return true;
  }

 private:
  OptionalName name_;
};

// Prints the text, or "(none)" (test failure messages).
std::ostream& operator<<(std::ostream& out, const OptionalName& name);

}  // namespace hapcine
