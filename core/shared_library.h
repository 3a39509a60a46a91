#pragma once
// Opening a shared library at run time (dlopen) with an error that names it.
// Used for the libraries only some commands need, so that the others do not
// load them at start-up: libmpv (player/mpv_library.h) and OpenCV's image
// codecs (lazy_imgcodecs/).

#include <string>

namespace hapcine {

// Opens `soname` with RTLD_NOW | RTLD_LOCAL (its symbols, and those of the
// libraries it pulls in, stay out of the global scope). On failure throws
// Error(soname, "cannot load " + what + ": " + the loader's reason).
void* OpenSharedLibrary(const std::string& soname, const std::string& what);

// The address of `symbol` in a library from OpenSharedLibrary, or nullptr.
void* FindSymbol(void* library, const char* symbol);

void CloseSharedLibrary(void* library);

}  // namespace hapcine
