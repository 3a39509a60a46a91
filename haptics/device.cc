#include "haptics/device.h"

namespace hapcine {

const char* DeviceFaultName(DeviceFault f) {
  switch (f) {
    case DeviceFault::kNone:
      return "none";
    case DeviceFault::kTransferError:
      return "USB transfer error (device unplugged?)";
    case DeviceFault::kNoData:
      return "device stopped answering";
    case DeviceFault::kNotOpen:
      return "device not open";
  }
  return "unknown";
}

void ZeroAndClose(HapSeat& seat) noexcept {
  for (auto& d : seat.devices) {
    if (!d) continue;
    try {
      // Several packets: one may be lost, and the firmware keeps the last.
      for (int i = 0; i < 3; ++i) d->Exchange(Eigen::Vector3d::Zero());
    } catch (...) {
    }
    d->Close();
  }
}

}  // namespace hapcine
