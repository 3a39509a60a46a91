// Paths the tests need, from the build that made them (testpaths/CMakeLists.txt).
#pragma once

namespace hapcine::test_paths {

const char* SourceDir();   // the checkout's root
const char* BinaryDir();   // the build tree's root (tests write their files under it)
const char* HapcineExe();  // the hapcine program of this build

}  // namespace hapcine::test_paths

#define HAPCINE_SOURCE_DIR (::hapcine::test_paths::SourceDir())
#define HAPCINE_BINARY_DIR (::hapcine::test_paths::BinaryDir())
#define HAPCINE_EXE (::hapcine::test_paths::HapcineExe())
