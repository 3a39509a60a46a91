#include "core/atomic_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "core/error.h"

namespace hapcine {
namespace {

std::string Slurp(const std::string& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(AtomicFileTest, NothingUnderTheFinalNameUntilCommit) {
  const std::string path = ::testing::TempDir() + "/atomic_a.txt";
  std::remove(path.c_str());
  {
    AtomicFile f(path);
    f.stream() << "hello";
    EXPECT_FALSE(std::ifstream(path).good());
    f.Commit();
  }
  EXPECT_EQ(Slurp(path), "hello");
  std::remove(path.c_str());
}

TEST(AtomicFileTest, AbandonedWriteKeepsTheOldFileAndRemovesTheTemporary) {
  const std::string path = ::testing::TempDir() + "/atomic_b.txt";
  { std::ofstream(path) << "old"; }
  std::string temp;
  {
    AtomicFile f(path);
    temp = f.temp_path();
    f.stream() << "new but unfinished";
  }
  EXPECT_EQ(Slurp(path), "old");
  EXPECT_FALSE(std::ifstream(temp).good());
  std::remove(path.c_str());
}

TEST(AtomicFileTest, UnwritableFolderIsAClearError) {
  try {
    AtomicFile f("/nonexistent-folder/x.csv");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/x.csv"), std::string::npos);
  }
}

}  // namespace
}  // namespace hapcine
