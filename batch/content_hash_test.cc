#include "batch/content_hash.h"

#include <gtest/gtest.h>

#include "batch/fake_step_for_test.h"
#include "core/error.h"

namespace hapcine::batch {
namespace {

using testutil::TempDir;
using testutil::WriteFile;

TEST(ContentIdTest, SmallFilesAreHashedWhole) {
  TempDir d;
  WriteFile(d.path() + "/a", "hello world");
  WriteFile(d.path() + "/b", "hello world");
  WriteFile(d.path() + "/c", "hello worle");
  WriteFile(d.path() + "/e", "");
  const ContentId a = SampledContentId(d.path() + "/a");
  EXPECT_EQ(a.size_bytes, 11u);
  EXPECT_EQ(a.hash.rfind("fnv1a64s:", 0), 0u);
  EXPECT_EQ(a.hash, SampledContentId(d.path() + "/b").hash);
  EXPECT_NE(a.hash, SampledContentId(d.path() + "/c").hash);
  EXPECT_EQ(SampledContentId(d.path() + "/e").size_bytes, 0u);
}

TEST(ContentIdTest, LargeFilesSampleHeadMiddleTailAndSize) {
  TempDir d;
  const size_t kMiB = 1 << 20;
  std::string base(7 * kMiB, '\0');
  for (size_t i = 0; i < base.size(); ++i) base[i] = static_cast<char>((i * 2654435761u) >> 13);
  const std::string path = d.path() + "/big";
  WriteFile(path, base);
  const std::string h0 = SampledContentId(path).hash;

  for (size_t offset : {size_t{10}, base.size() / 2, base.size() - 10}) {
    std::string changed = base;
    changed[offset] ^= 1;
    WriteFile(path, changed);
    EXPECT_NE(SampledContentId(path).hash, h0) << "change at " << offset;
  }
  WriteFile(path, base + "x");  // appended
  EXPECT_NE(SampledContentId(path).hash, h0);
  // The documented blind spot: a same-size edit outside the three windows.
  std::string outside = base;
  outside[2 * kMiB] ^= 1;
  WriteFile(path, outside);
  EXPECT_EQ(SampledContentId(path).hash, h0);
  // ... which is why duplicates are confirmed byte by byte.
  WriteFile(d.path() + "/big2", base);
  EXPECT_FALSE(FilesEqual(path, d.path() + "/big2"));
  WriteFile(path, base);
  EXPECT_TRUE(FilesEqual(path, d.path() + "/big2"));
}

TEST(ContentIdTest, FullFileHashAndErrors) {
  TempDir d;
  WriteFile(d.path() + "/a", "foobar");
  EXPECT_EQ(FullFileHash(d.path() + "/a"), "fnv1a64:85944171f73967e8");
  EXPECT_THROW(SampledContentId(d.path() + "/missing"), Error);
  EXPECT_THROW(SampledContentId(d.path()), Error);  // a folder
  EXPECT_THROW(FilesEqual(d.path() + "/a", d.path() + "/missing"), Error);
  WriteFile(d.path() + "/b", "fooba");
  EXPECT_FALSE(FilesEqual(d.path() + "/a", d.path() + "/b"));
}

}  // namespace
}  // namespace hapcine::batch
