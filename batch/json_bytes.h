#pragma once
// Film paths and names in the batch's JSON files. JSON strings are UTF-8,
// but a Linux file name is bytes ("a\xff.mp4" is a valid film): such a text
// is stored as {"hex": "61ff2e6d7034"} and read back byte for byte, while
// every valid UTF-8 text stays a plain JSON string (as older files have it).

#include <nlohmann/json.hpp>
#include <string>

namespace hapcine::batch {

bool IsValidUtf8(const std::string& text);

// A JSON value for `bytes`: a string when it is valid UTF-8, else {"hex": ...}.
nlohmann::json JsonFromBytes(const std::string& bytes);

// The bytes of a value written by JsonFromBytes (a string or {"hex": ...}).
// Throws nlohmann::json::exception on anything else.
std::string BytesFromJson(const nlohmann::json& value);

}  // namespace hapcine::batch
