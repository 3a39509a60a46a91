#pragma once
// Definitions of cv::imread, cv::imwrite and cv::imencode (declared by
// <opencv2/imgcodecs.hpp>, which callers keep including) that open
// libopencv_imgcodecs on their first call and forward to it. Linking the real
// library made every hapcine command load 79 more shared libraries (GDAL and
// its database, network and science formats, GDCM, OpenEXR, ...) at start-up,
// although only image sequences, the COLMAP export and PNG plots use it.
//
// Only these three functions are defined: a call to any other function of
// OpenCV's imgcodecs module from a target linking hapcine_lazy_imgcodecs
// fails to link, and is added here (with its symbol in lazy_imgcodecs.cc).

#include <string>

namespace hapcine {

// The soname opened (the one the build found, e.g. libopencv_imgcodecs.so.406).
const char* ImgcodecsSoname();

// Opens the library and resolves the three functions now (each call does it
// on first use anyway). Throws hapcine::Error(soname, reason) naming the
// Debian package if the library cannot be opened or lacks a function.
void LoadImgcodecs();

// Opens `soname` and resolves the three functions in it without keeping the
// result: the check LoadImgcodecs() makes, for any library (tests).
void CheckImgcodecsLibrary(const std::string& soname);

}  // namespace hapcine
