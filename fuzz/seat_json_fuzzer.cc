// The two seat JSON readers on the same bytes: the seat geometry
// (haptics/seat_geometry.h, `--seat`) and the device map
// (haptics/device_config.h, `--seat-config`).
#include "fuzz/fuzz_input.h"
#include "haptics/device_config.h"
#include "haptics/seat_geometry.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = hapcine::fuzz::AsString(data, size);
  hapcine::fuzz::AcceptOnlyError([&] {
    const hapcine::SeatGeometry seat = hapcine::ParseSeatGeometryJson(text, "fuzz.seat.json");
    hapcine::SeatGeometryToJson(seat);
  });
  hapcine::fuzz::AcceptOnlyError([&] { hapcine::ParseSeatConfig(text, "fuzz.devices.json"); });
  return 0;
}
