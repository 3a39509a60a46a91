#include "batch/library.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace hapcine::batch {
namespace {
namespace fs = std::filesystem;

class TempDir {
 public:
  TempDir() {
    char tmpl[] = "/tmp/hapcine_batch_lib_XXXXXX";
    path_ = ::mkdtemp(tmpl);
  }
  ~TempDir() { fs::remove_all(path_); }
  const std::string& path() const { return path_; }
  std::string Write(const std::string& rel, const std::string& content) const {
    const fs::path p = fs::path(path_) / rel;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << content;
    return p.string();
  }

 private:
  std::string path_;
};

TEST(LibraryTest, VideoExtensionsAreCaseInsensitive) {
  for (const char* e : {"mp4", "MKV", "mov", "avi", "webm", "m4v", "mpg", "ts", "Mts", "mxf"}) {
    EXPECT_TRUE(IsVideoExtension(e)) << e;
  }
  for (const char* e : {"", "txt", "csv", "mp3", "jpg", "mp4x", "srt"}) {
    EXPECT_FALSE(IsVideoExtension(e)) << e;
  }
}

TEST(LibraryTest, FolderIsScannedRecursivelyForVideosOnly) {
  TempDir d;
  d.Write("a.mp4", "x");
  d.Write("sub/deeper/b.MKV", "x");
  d.Write("notes.txt", "x");
  d.Write("é clip.mp4", "x");
  d.Write(".hidden/c.mp4", "x");
  d.Write(".d.mp4", "x");
  const std::vector<std::string> got = ListLibrary(d.path());
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[0], d.path() + "/a.mp4");
  EXPECT_EQ(got[1], d.path() + "/sub/deeper/b.MKV");
  EXPECT_EQ(got[2], d.path() + "/é clip.mp4");
}

TEST(LibraryTest, TextManifestSkipsCommentsResolvesRelativePathsAndDeduplicates) {
  TempDir d;
  const std::string m = d.Write("list.txt",
                                "# my films\n\n  films/b.mp4  \n/abs/a.mkv\nfilms/../films/b.mp4\n"
                                "notes.txt\n");
  const std::vector<std::string> got = ListLibrary(m);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[0], "/abs/a.mkv");
  EXPECT_EQ(got[1], d.path() + "/films/b.mp4");
  EXPECT_EQ(got[2], d.path() + "/notes.txt");  // listed explicitly: taken whatever its extension
}

TEST(LibraryTest, CsvManifestUsesPathColumn) {
  TempDir d;
  const std::string m = d.Write(
      "lib.csv", "title,Path,year\n\"A, the film\",\"x/a \"\"q\"\".mp4\",1999\nB,/b.mp4,2001\n");
  const std::vector<std::string> got = ListLibrary(m);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0], "/b.mp4");
  EXPECT_EQ(got[1], d.path() + "/x/a \"q\".mp4");
}

TEST(LibraryTest, CsvManifestWithoutPathColumnIsAnError) {
  TempDir d;
  const std::string m = d.Write("lib.csv", "file,year\na.mp4,1\n");
  EXPECT_THROW(ListLibrary(m), Error);
}

TEST(LibraryTest, AVideoFileIsALibraryOfOne) {
  TempDir d;
  const std::string film = d.Write("Film One.MKV", std::string("\x1a\x45\xdf\xa3\0\0", 6));
  EXPECT_EQ(ListLibrary(film), std::vector<std::string>{film});
}

TEST(LibraryTest, BinaryManifestIsAnErrorNamingIt) {
  TempDir d;
  const std::string m = d.Write("films.bin", std::string("a.mp4\n\x89PNG\0\0\x7e", 14));
  try {
    ListLibrary(m);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), m + ":2");
    EXPECT_NE(e.reason().find("not a text manifest"), std::string::npos) << e.what();
  }
}

TEST(LibraryTest, MissingLibraryIsAnError) {
  EXPECT_THROW(ListLibrary("/nonexistent/hapcine/library"), Error);
}

TEST(LibraryTest, FilmIdIsStableUniqueAndKeepsNonAsciiNames) {
  const std::string a = FilmId("/films/é clip.mp4");
  EXPECT_EQ(a, FilmId("/films/é clip.mp4"));
  EXPECT_EQ(a.rfind("é clip-", 0), 0u) << a;
  EXPECT_EQ(a.size(), std::string("é clip-").size() + 8);
  EXPECT_NE(FilmId("/films/a/x.mp4"), FilmId("/films/b/x.mp4"));
  EXPECT_EQ(FilmId("/f/日本.mkv").rfind("日本-", 0), 0u);
  EXPECT_EQ(FilmId("/f/.mp4")[0], '_');                   // never a hidden folder
  EXPECT_EQ(FilmId("/f/a\nb.mp4").substr(0, 4), "a_b-");  // no control characters
}

TEST(LibraryTest, FilmIdCutsLongNamesOnCharacterBoundary) {
  std::string name;
  for (int i = 0; i < 60; ++i) name += "é";  // 120 bytes
  const std::string id = FilmId("/f/" + name + ".mp4");
  const std::string stem = id.substr(0, id.size() - 9);
  EXPECT_LE(stem.size(), 80u);
  EXPECT_EQ(stem.size() % 2, 0u);  // whole two-byte characters only
}

TEST(LibraryTest, OutputStemFitsTheLongestOutputNameIn255Bytes) {
  const std::vector<std::string> models = {"cinematic", "semantic"};
  EXPECT_EQ(OutputStem("film", models), "film");
  const std::string stem(240, 'f');
  const std::string cut = OutputStem(stem, models);
  EXPECT_EQ((cut + ".cinematic.haptic.csv").size(), 255u);
  EXPECT_EQ(stem.compare(0, cut.size(), cut), 0);
  // Two-byte characters: never split.
  std::string wide;
  while (wide.size() < 240) wide += "é";
  const std::string wide_cut = OutputStem(wide, models);
  EXPECT_LE((wide_cut + ".cinematic.haptic.csv").size(), 255u);
  EXPECT_EQ(wide_cut.size() % 2, 0u);
}

TEST(LibraryTest, SplitArgsHonoursQuotes) {
  EXPECT_EQ(SplitArgs(""), std::vector<std::string>{});
  EXPECT_EQ(SplitArgs("  --a 1  --b 'x y' \"z \\\"w\\\"\" c\\ d"),
            (std::vector<std::string>{"--a", "1", "--b", "x y", "z \"w\"", "c d"}));
  EXPECT_EQ(SplitArgs("'it'\\''s' ''"), (std::vector<std::string>{"it's", ""}));
  EXPECT_THROW(SplitArgs("--a 'open"), UsageError);
}

}  // namespace
}  // namespace hapcine::batch
