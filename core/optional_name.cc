#include "core/optional_name.h"

#include <atomic>
#include <memory>
#include <mutex>
#include <unordered_map>

#include "core/error.h"

namespace hapcine {
namespace {

// Append-only: texts are never removed, so a pointer read once stays valid.
// Readers of a slot need no lock: a name's id reached this thread through
// whatever handed it the name, after the store below.
struct NameTable {
  std::mutex mutex;
  std::unordered_map<std::string, uint16_t> ids;
  std::atomic<const std::string*> texts[OptionalName::kCapacity] = {};
};

NameTable& Table() {
  static NameTable* table = new NameTable;  // never destroyed: names outlive statics
  return *table;
}

}  // namespace

bool OptionalName::TryMake(const std::string& text, OptionalName* out) {
  NameTable& t = Table();
  std::lock_guard<std::mutex> lock(t.mutex);
  auto it = t.ids.find(text);
  if (it == t.ids.end()) {
    if (t.ids.size() >= kCapacity) return false;
    const uint16_t id = static_cast<uint16_t>(t.ids.size() + 1);
    it = t.ids.emplace(text, id).first;
    t.texts[id - 1].store(&it->first, std::memory_order_release);
  }
  out->id_ = it->second;
  return true;
}

OptionalName::OptionalName(const std::string& text) {
  if (!TryMake(text, this)) {
    throw Error("names", "more than " + std::to_string(kCapacity) + " distinct texts");
  }
}

const std::string& OptionalName::operator*() const {
  return *Table().texts[id_ - 1].load(std::memory_order_acquire);
}

const std::string& OptionalName::value() const {
  if (!id_) throw std::bad_optional_access();
  return **this;
}

std::ostream& operator<<(std::ostream& out, const OptionalName& name) {
  return out << (name ? *name : std::string("(none)"));
}

}  // namespace hapcine
