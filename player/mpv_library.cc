#include "player/mpv_library.h"

#include "core/error.h"
#include "core/shared_library.h"

namespace hapcine {
namespace {

// Looks up `name` in `lib` into `fn`, with the function's own type.
template <typename Fn>
void Bind(void* lib, const std::string& soname, const char* name, Fn* fn) {
  *fn = reinterpret_cast<Fn>(FindSymbol(lib, name));
  if (!*fn) throw Error(soname, std::string("has no ") + name + " (not a libmpv of client API " +
                                    std::to_string(MPV_CLIENT_API_VERSION >> 16) + ".x)");
}

}  // namespace

std::string MpvSoname() { return "libmpv.so." + std::to_string(MPV_CLIENT_API_VERSION >> 16); }

MpvApi LoadMpvApi(const std::string& soname) {
  void* lib = OpenSharedLibrary(
      soname, "the video player library (install Debian's libmpv2, or play with --no-video)");
  MpvApi api;
  try {
    Bind(lib, soname, "mpv_create", &api.create);
    Bind(lib, soname, "mpv_initialize", &api.initialize);
    Bind(lib, soname, "mpv_terminate_destroy", &api.terminate_destroy);
    Bind(lib, soname, "mpv_set_option_string", &api.set_option_string);
    Bind(lib, soname, "mpv_set_property", &api.set_property);
    Bind(lib, soname, "mpv_observe_property", &api.observe_property);
    Bind(lib, soname, "mpv_command", &api.command);
    Bind(lib, soname, "mpv_wait_event", &api.wait_event);
    Bind(lib, soname, "mpv_wakeup", &api.wakeup);
    Bind(lib, soname, "mpv_error_string", &api.error_string);
  } catch (...) {
    CloseSharedLibrary(lib);  // nothing of it was used
    throw;
  }
  return api;
}

const MpvApi& Mpv() {
  // A function-local static whose initialiser throws is retried on the next
  // call, so a failure is reported every time rather than cached as empty.
  static const MpvApi api = LoadMpvApi(MpvSoname());
  return api;
}

}  // namespace hapcine
