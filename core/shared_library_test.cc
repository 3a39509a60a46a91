#include "core/shared_library.h"

#include <gtest/gtest.h>

#include <string>

#include "core/error.h"

namespace hapcine {
namespace {

TEST(SharedLibrary, OpensAndFindsASymbol) {
  void* libm = OpenSharedLibrary("libm.so.6", "the C maths library");
  using CosFn = double (*)(double);
  auto cos_fn = reinterpret_cast<CosFn>(FindSymbol(libm, "cos"));
  ASSERT_NE(cos_fn, nullptr);
  EXPECT_DOUBLE_EQ(cos_fn(0.0), 1.0);
  EXPECT_EQ(FindSymbol(libm, "no_such_function_in_libm"), nullptr);
  CloseSharedLibrary(libm);
  CloseSharedLibrary(nullptr);  // no-op
}

TEST(SharedLibrary, MissingLibraryIsOneLineNamingItAndWhatItIsFor) {
  try {
    OpenSharedLibrary("libhapcine_does_not_exist.so.9", "the test library (install nothing)");
    FAIL() << "opened a library that does not exist";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("libhapcine_does_not_exist.so.9"), std::string::npos) << m;
    EXPECT_NE(m.find("cannot load the test library (install nothing): "), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace hapcine
