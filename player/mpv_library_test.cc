#include "player/mpv_library.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace hapcine {
namespace {

TEST(MpvLibrary, SonameFollowsTheClientApiMajor) {
  EXPECT_EQ(MpvSoname(), "libmpv.so." + std::to_string(MPV_CLIENT_API_VERSION >> 16));
}

TEST(MpvLibrary, LoadsEveryFunction) {
  const MpvApi& api = Mpv();
  EXPECT_NE(api.create, nullptr);
  EXPECT_NE(api.initialize, nullptr);
  EXPECT_NE(api.terminate_destroy, nullptr);
  EXPECT_NE(api.set_option_string, nullptr);
  EXPECT_NE(api.set_property, nullptr);
  EXPECT_NE(api.observe_property, nullptr);
  EXPECT_NE(api.command, nullptr);
  EXPECT_NE(api.wait_event, nullptr);
  EXPECT_NE(api.wakeup, nullptr);
  EXPECT_NE(api.error_string, nullptr);
  // The table calls the real library: a known error code has mpv's text.
  EXPECT_STREQ(api.error_string(MPV_ERROR_NOMEM), "memory allocation failed");
  EXPECT_EQ(&Mpv(), &api) << "loaded once per process";
}

TEST(MpvLibrary, MissingLibraryIsOneLineNamingItAndThePackage) {
  const std::string soname = "libhapcine-no-such-mpv.so.2";
  try {
    LoadMpvApi(soname);
    FAIL() << "loaded a library that does not exist";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.where(), soname);
    EXPECT_NE(msg.find("libmpv2"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(MpvLibrary, LibraryWithoutTheFunctionsNamesTheFirstMissingOne) {
  // libm is loaded in every C++ process and has no mpv_* symbols.
  try {
    LoadMpvApi("libm.so.6");
    FAIL() << "libm passed for libmpv";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "libm.so.6");
    EXPECT_NE(std::string(e.what()).find("mpv_create"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hapcine
