#include "lazy_imgcodecs/lazy_imgcodecs.h"

#include <opencv2/imgcodecs.hpp>

#include "core/error.h"
#include "core/shared_library.h"

namespace hapcine {
namespace {

// The exact signatures <opencv2/imgcodecs.hpp> declares; the static_casts
// below fail to compile if OpenCV changes one, and the symbol names are these
// signatures' Itanium C++ ABI manglings (std::string is the C++11 ABI's).
using ImreadFn = cv::Mat (*)(const cv::String&, int);
using ImwriteFn = bool (*)(const cv::String&, cv::InputArray, const std::vector<int>&);
using ImencodeFn = bool (*)(const cv::String&, cv::InputArray, std::vector<uchar>&,
                            const std::vector<int>&);
static_assert(sizeof(static_cast<ImreadFn>(&cv::imread)) > 0);
static_assert(sizeof(static_cast<ImwriteFn>(&cv::imwrite)) > 0);
static_assert(sizeof(static_cast<ImencodeFn>(&cv::imencode)) > 0);

constexpr const char* kImreadSymbol =
    "_ZN2cv6imreadERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEEi";
constexpr const char* kImwriteSymbol =
    "_ZN2cv7imwriteERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEERKNS_11_InputArrayE"
    "RKSt6vectorIiSaIiEE";
constexpr const char* kImencodeSymbol =
    "_ZN2cv8imencodeERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEERKNS_11_InputArrayE"
    "RSt6vectorIhSaIhEERKSB_IiSaIiEE";

struct Imgcodecs {
  ImreadFn imread = nullptr;
  ImwriteFn imwrite = nullptr;
  ImencodeFn imencode = nullptr;
};

template <typename Fn>
void Bind(void* lib, const std::string& soname, const char* symbol, const char* name, Fn* fn) {
  *fn = reinterpret_cast<Fn>(FindSymbol(lib, symbol));
  if (!*fn) throw Error(soname, std::string("has no cv::") + name + " of the OpenCV " +
                                    CV_VERSION + " headers hapcine was built with");
}

// Opens `soname` and resolves the three functions; on failure closes it and
// throws.
Imgcodecs Open(const std::string& soname) {
  void* lib =
      OpenSharedLibrary(soname, "OpenCV's image codecs (install Debian's libopencv-imgcodecs406)");
  Imgcodecs f;
  try {
    Bind(lib, soname, kImreadSymbol, "imread", &f.imread);
    Bind(lib, soname, kImwriteSymbol, "imwrite", &f.imwrite);
    Bind(lib, soname, kImencodeSymbol, "imencode", &f.imencode);
  } catch (...) {
    CloseSharedLibrary(lib);
    throw;
  }
  return f;  // the library stays open for the process's lifetime
}

// Opened once per process (thread-safe); a failure is thrown again on every
// call rather than cached.
const Imgcodecs& Real() {
  static const Imgcodecs f = Open(HAPCINE_IMGCODECS_SONAME);
  return f;
}

}  // namespace

const char* ImgcodecsSoname() { return HAPCINE_IMGCODECS_SONAME; }
void LoadImgcodecs() { Real(); }
void CheckImgcodecsLibrary(const std::string& soname) { Open(soname); }

}  // namespace hapcine

// The definitions the linker finds instead of libopencv_imgcodecs'.
namespace cv {

Mat imread(const String& filename, int flags) { return hapcine::Real().imread(filename, flags); }

bool imwrite(const String& filename, InputArray img, const std::vector<int>& params) {
  return hapcine::Real().imwrite(filename, img, params);
}

bool imencode(const String& ext, InputArray img, std::vector<uchar>& buf,
              const std::vector<int>& params) {
  return hapcine::Real().imencode(ext, img, buf, params);
}

}  // namespace cv
