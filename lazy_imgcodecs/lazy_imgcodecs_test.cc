#include "lazy_imgcodecs/lazy_imgcodecs.h"

#include <dlfcn.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/error.h"

namespace hapcine {
namespace {
namespace fs = std::filesystem;

bool Loaded(const char* soname) {
  void* lib = dlopen(soname, RTLD_NOW | RTLD_NOLOAD);
  if (lib) dlclose(lib);
  return lib != nullptr;
}

// First in the file: gtest runs a file's tests in order, so when the whole
// binary runs in one process nothing has called a codec yet.
TEST(LazyImgcodecs, OpensTheLibraryOnlyOnFirstCall) {
  EXPECT_FALSE(Loaded(ImgcodecsSoname())) << "linked or opened before the first call";
  std::vector<uchar> png;
  ASSERT_TRUE(cv::imencode(".png", cv::Mat(4, 4, CV_8UC1, cv::Scalar(7)), png));
  EXPECT_TRUE(Loaded(ImgcodecsSoname()));
}

TEST(LazyImgcodecs, WritesReadsAndEncodesThroughTheRealLibrary) {
  cv::Mat image(24, 32, CV_8UC3);
  cv::randu(image, 0, 256);
  const fs::path file = fs::temp_directory_path() /
                        ("hapcine_lazy_imgcodecs_" + std::to_string(getpid()) + ".png");
  ASSERT_TRUE(cv::imwrite(file.string(), image));
  const cv::Mat back = cv::imread(file.string(), cv::IMREAD_COLOR);
  fs::remove(file);
  ASSERT_EQ(back.size(), image.size());
  ASSERT_EQ(back.type(), image.type());
  EXPECT_EQ(cv::norm(back, image, cv::NORM_INF), 0) << "PNG is lossless";
  // A missing file is OpenCV's empty image, as with the linked library.
  EXPECT_TRUE(cv::imread((fs::temp_directory_path() / "hapcine_no_such.png").string()).empty());

  std::vector<uchar> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", image, jpeg, {cv::IMWRITE_JPEG_QUALITY, 90}));
  ASSERT_GT(jpeg.size(), 3u);
  EXPECT_EQ(jpeg[0], 0xFF);  // JPEG start-of-image marker
  EXPECT_EQ(jpeg[1], 0xD8);
}

TEST(LazyImgcodecs, TheBuildsLibraryHasEverySymbol) {
  EXPECT_NO_THROW(CheckImgcodecsLibrary(ImgcodecsSoname()));
  EXPECT_NO_THROW(LoadImgcodecs());
}

TEST(LazyImgcodecs, MissingLibraryIsOneLineNamingItAndThePackage) {
  const std::string soname = "libhapcine-no-such-imgcodecs.so.406";
  try {
    CheckImgcodecsLibrary(soname);
    FAIL() << "opened a library that does not exist";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.where(), soname);
    EXPECT_NE(msg.find("libopencv-imgcodecs"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(LazyImgcodecs, LibraryWithoutTheFunctionsNamesTheFirstMissingOne) {
  try {
    CheckImgcodecsLibrary("libm.so.6");  // loaded in every C++ process, no cv::
    FAIL() << "libm passed for libopencv_imgcodecs";
  } catch (const Error& e) {
    EXPECT_EQ(e.where(), "libm.so.6");
    EXPECT_NE(std::string(e.what()).find("cv::imread"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hapcine
