#include "study/hash.h"

#include "core/error.h"
#include "core/hash.h"
#include "core/input_file.h"
#include <cstdio>
#include <fstream>

namespace hapcine::study {

std::string HashFile(const std::string& path) { return Fnv1a64FileHex(path); }

std::string HashString(const std::string& bytes) { return Fnv1a64Hex(bytes); }

}  // namespace hapcine::study
