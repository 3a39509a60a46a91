#include "core/shared_library.h"

#include <dlfcn.h>

#include "core/error.h"

namespace hapcine {

void* OpenSharedLibrary(const std::string& soname, const std::string& what) {
  void* library = dlopen(soname.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!library) {
    const char* why = dlerror();
    throw Error(soname, "cannot load " + what + ": " + (why ? why : "unknown dlopen error"));
  }
  return library;
}

void* FindSymbol(void* library, const char* symbol) { return dlsym(library, symbol); }

void CloseSharedLibrary(void* library) {
  if (library) dlclose(library);
}

}  // namespace hapcine
