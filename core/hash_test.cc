#include "core/hash.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace hapcine {
namespace {

TEST(Fnv1a64Test, KnownVectors) {
  // Reference values of FNV-1a 64 (Fowler/Noll/Vo test suite).
  EXPECT_EQ(Fnv1a64Hex(""), "cbf29ce484222325");
  EXPECT_EQ(Fnv1a64Hex("a"), "af63dc4c8601ec8c");
  EXPECT_EQ(Fnv1a64Hex("foobar"), "85944171f73967e8");
}

TEST(Fnv1a64Test, IncrementalEqualsOneShot) {
  Fnv1a64 h;
  h.Update("foo");
  h.Update("");
  h.Update("bar");
  EXPECT_EQ(h.Hex(), Fnv1a64Hex("foobar"));
  EXPECT_EQ(h.value(), 0x85944171f73967e8ull);
}

TEST(Fnv1a64Test, FileHashEqualsStringHash) {
  const std::string dir = ::testing::TempDir();
  const std::string path = dir + "/fnv_file.bin";
  std::string bytes(200000, '\0');  // more than one read buffer, NUL bytes included
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 7);
  std::ofstream(path, std::ios::binary) << bytes;
  EXPECT_EQ(Fnv1a64FileHex(path), Fnv1a64Hex(bytes));
  std::ofstream(path, std::ios::binary | std::ios::trunc).flush();
  EXPECT_EQ(Fnv1a64FileHex(path), Fnv1a64Hex(""));
  std::filesystem::remove(path);
}

TEST(Fnv1a64Test, UnreadableFileThrows) {
  EXPECT_THROW(Fnv1a64FileHex(::testing::TempDir() + "/no_such_file_for_fnv"), Error);
  EXPECT_THROW(Fnv1a64FileHex(::testing::TempDir()), Error);  // a directory
}

}  // namespace
}  // namespace hapcine
