#pragma once
// FFmpeg's text for one of its error codes (av_strerror), for messages.

#include <string>

namespace hapcine {

std::string AvErrorText(int code);

}  // namespace hapcine
