#pragma once
// libmpv, opened on first use instead of linked. Only the media clock of
// `hapcine play` needs mpv, and linking it made every hapcine command load 85
// more shared libraries (X11, Wayland, PulseAudio, SDL, Lua, libass,
// libavfilter, ...) and resolve their symbols at start-up (docs/player.md,
// "Start-up"). The header <mpv/client.h> still gives the types, so each
// entry below has exactly the type of the libmpv function it stands for.

#include <mpv/client.h>

#include <string>

namespace hapcine {

// The libmpv functions MpvClock calls.
struct MpvApi {
  decltype(&::mpv_create) create = nullptr;
  decltype(&::mpv_initialize) initialize = nullptr;
  decltype(&::mpv_terminate_destroy) terminate_destroy = nullptr;
  decltype(&::mpv_set_option_string) set_option_string = nullptr;
  decltype(&::mpv_set_property) set_property = nullptr;
  decltype(&::mpv_observe_property) observe_property = nullptr;
  decltype(&::mpv_command) command = nullptr;
  decltype(&::mpv_wait_event) wait_event = nullptr;
  decltype(&::mpv_wakeup) wakeup = nullptr;
  decltype(&::mpv_error_string) error_string = nullptr;
};

// The soname matching the <mpv/client.h> we compiled against: libmpv's
// soname major follows the client API's major version (ABI breaks bump both).
std::string MpvSoname();

// Opens `soname` and looks up every MpvApi entry. Throws
// hapcine::Error(soname, reason) if the library cannot be opened (with the
// Debian package to install) or lacks one of the functions. The library is
// never closed: mpv's threads may outlive any one player.
MpvApi LoadMpvApi(const std::string& soname);

// LoadMpvApi(MpvSoname()) once per process (thread-safe); a failure is
// thrown again on every call.
const MpvApi& Mpv();

}  // namespace hapcine
