#include "testpaths/test_paths.h"

namespace hapcine::test_paths {

const char* SourceDir() { return HAPCINE_TEST_SOURCE_DIR; }
const char* BinaryDir() { return HAPCINE_TEST_BINARY_DIR; }
const char* HapcineExe() { return HAPCINE_TEST_EXE; }

}  // namespace hapcine::test_paths
