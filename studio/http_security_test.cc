#include "studio/http_security.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <vector>

namespace hapcine::studio {
namespace {
namespace fs = std::filesystem;

TEST(HttpSecurity, LoopbackHosts) {
  EXPECT_TRUE(IsLoopbackHost("127.0.0.1"));
  EXPECT_TRUE(IsLoopbackHost("127.1.2.3"));
  EXPECT_TRUE(IsLoopbackHost("localhost"));
  EXPECT_TRUE(IsLoopbackHost("::1"));
  EXPECT_FALSE(IsLoopbackHost("0.0.0.0"));
  EXPECT_FALSE(IsLoopbackHost("127.0.0.1.evil.com"));
  EXPECT_FALSE(IsLoopbackHost("127.evil"));
  EXPECT_FALSE(IsLoopbackHost("192.168.1.2"));
  EXPECT_FALSE(IsLoopbackHost(""));
  EXPECT_EQ(HostWithoutPort("127.0.0.1:8787"), "127.0.0.1");
  EXPECT_EQ(HostWithoutPort("[::1]:80"), "::1");
  EXPECT_EQ(HostWithoutPort("::1"), "::1");
  EXPECT_EQ(HostWithoutPort("localhost"), "localhost");
}

TEST(HttpSecurity, TokensAreRandomAndComparedWhole) {
  const std::string a = NewToken(), b = NewToken();
  EXPECT_EQ(a.size(), 32u);
  EXPECT_NE(a, b);
  EXPECT_TRUE(TokensEqual(a, a));
  EXPECT_FALSE(TokensEqual(a, b));
  EXPECT_FALSE(TokensEqual(a, a.substr(0, 31)));
  EXPECT_FALSE(TokensEqual("", ""));
  EXPECT_EQ(RequestToken("q", "hapcine_token=c", "Bearer b"), "q");
  EXPECT_EQ(RequestToken("", "x=1; hapcine_token=c; y=2", "Bearer b"), "c");
  EXPECT_EQ(RequestToken("", "x=1", "Bearer b"), "b");
  EXPECT_EQ(RequestToken("", "", "Basic b"), "");
}

TEST(HttpSecurity, SafeRelativePathRejectsEveryEscape) {
  EXPECT_EQ(SafeRelativePath("app.js"), "app.js");
  EXPECT_EQ(SafeRelativePath("img/seat.svg"), "img/seat.svg");
  for (const std::string& bad : std::vector<std::string>{"", "../etc/passwd", "a/../../b", "/etc/passwd", "a//b", "./a",
                                ".hidden", "a/.", "a\\..\\b", std::string("a\0b", 3), "a/"}) {
    EXPECT_FALSE(SafeRelativePath(bad)) << bad;
  }
}

TEST(HttpSecurity, ResolveInsideRefusesSymlinksLeavingTheFolder) {
  const fs::path dir = fs::temp_directory_path() / ("hapcine_security_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "web" / "sub");
  std::ofstream(dir / "web" / "app.js") << "ok";
  std::ofstream(dir / "secret.txt") << "secret";
  fs::create_symlink(dir / "secret.txt", dir / "web" / "leak.txt");
  fs::create_symlink(dir, dir / "web" / "up");
  fs::create_symlink(dir / "web" / "app.js", dir / "web" / "alias.js");
  EXPECT_TRUE(ResolveInside(dir / "web", "app.js"));
  EXPECT_TRUE(ResolveInside(dir / "web", "alias.js"));  // a link that stays inside
  EXPECT_FALSE(ResolveInside(dir / "web", "leak.txt"));
  EXPECT_FALSE(ResolveInside(dir / "web", "up/secret.txt"));
  EXPECT_FALSE(ResolveInside(dir / "web", "sub"));  // a folder
  EXPECT_FALSE(ResolveInside(dir / "web", "missing.js"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace hapcine::studio
