#include "haptics/falcon_firmware.h"

#include <chrono>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "core/input_file.h"
#include "haptics/falcon_protocol.h"

namespace hapcine {

void FirmwareOptions::Check() const {
  if (max_attempts < 1 || max_attempts > 1000)
    throw UsageError("firmware max_attempts must be in [1, 1000]");
  if (handshake_tries < 1) throw UsageError("firmware handshake_tries must be >= 1");
  if (handshake_timeout_ms < 1 || echo_timeout_ms < 1)
    throw UsageError("firmware timeouts must be >= 1 ms");
}

std::vector<uint8_t> ReadFirmwareFile(const std::string& path) {
  if (path.empty())
    throw Error("firmware",
                "no firmware file given: pass --firmware PATH to your copy of Novint's image "
                "(e.g. nVent_firmware.bin; it cannot be distributed with hapcine)");
  InputFile file(path, std::ios::binary);
  std::ifstream& in = file.stream();
  std::vector<uint8_t> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (data.empty()) throw Error(path, "firmware file is empty");
  if (data.size() > 65536)
    throw Error(path, "firmware file is " + std::to_string(data.size()) +
                          " bytes: too large for a Falcon image (expected ~8.5 KB)");
  return data;
}

int ReadFtdiPayload(UsbTransport& usb, uint8_t* out, int n, int timeout_ms) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::milliseconds(timeout_ms);
  int got = 0;
  uint8_t raw[512], payload[512];
  while (got < n) {
    const int r = usb.BulkRead(raw, sizeof(raw), 5);
    if (r < 0) return got;
    const size_t m = StripFtdiStatus(raw, static_cast<size_t>(r), payload);
    for (size_t i = 0; i < m && got < n; ++i) out[got++] = payload[i];
    if (got < n && Clock::now() > deadline) break;
  }
  return got;
}

bool SetFalconNormalMode(UsbTransport& usb) {
  return usb.Control(ftdi::kLatencyTimer, 1) && usb.Control(ftdi::kBaudRate, ftdi::kBaudNormal) &&
         usb.Control(ftdi::kReset, ftdi::kPurgeRx) && usb.Control(ftdi::kReset, ftdi::kPurgeTx);
}

namespace {

// One attempt; returns "" on success, else the reason.
std::string TryLoad(UsbTransport& usb, const std::vector<uint8_t>& image,
                    const FirmwareOptions& o) {
  if (!(usb.Control(ftdi::kReset, ftdi::kPurgeRx) && usb.Control(ftdi::kReset, ftdi::kPurgeTx) &&
        usb.Control(ftdi::kLatencyTimer, 16) && usb.Control(ftdi::kBaudRate, ftdi::kBaud9600) &&
        usb.Control(ftdi::kLineSettings, 8) && usb.Control(ftdi::kFlowControl, 0) &&
        usb.Control(ftdi::kModemControl, ftdi::kRtsLow) &&
        usb.Control(ftdi::kModemControl, ftdi::kDtrLow) &&
        usb.Control(ftdi::kModemControl, ftdi::kDtrHigh)))
    return "FTDI set-up control transfer failed";
  static const uint8_t kHello[3] = {0x0A, 0x43, 0x0D};
  static const uint8_t kAnswer[4] = {0x0A, 0x44, 0x2C, 0x0D};
  bool greeted = false;
  for (int t = 0; t < o.handshake_tries && !greeted; ++t) {
    if (o.cancelled && o.cancelled()) return "cancelled";
    if (usb.BulkWrite(kHello, 3, 100) != 3) return "USB write failed during the handshake";
    uint8_t reply[4] = {0, 0, 0, 0};
    greeted = ReadFtdiPayload(usb, reply, 4, o.handshake_timeout_ms) == 4 &&
              std::equal(reply, reply + 4, kAnswer);
  }
  if (!greeted)
    return "no bootloader answer to 0A 43 0D after " + std::to_string(o.handshake_tries) + " tries";
  if (!(usb.Control(ftdi::kModemControl, ftdi::kDtrLow) &&
        usb.Control(ftdi::kBaudRate, ftdi::kBaudFirmware)))
    return "FTDI control transfer failed after the handshake";
  const uint8_t a = 'A';
  uint8_t echo = 0;
  if (usb.BulkWrite(&a, 1, 100) != 1 || ReadFtdiPayload(usb, &echo, 1, o.echo_timeout_ms) != 1 ||
      echo != 'A')
    return "bootloader did not echo 'A'";
  uint8_t back[62];
  for (size_t off = 0; off < image.size(); off += 62) {
    const int n = static_cast<int>(std::min<size_t>(62, image.size() - off));
    if (usb.BulkWrite(image.data() + off, n, 1000) != n)
      return "USB write failed while streaming firmware";
    if (ReadFtdiPayload(usb, back, n, o.echo_timeout_ms) != n)
      return "firmware echo timed out at byte " + std::to_string(off);
    for (int i = 0; i < n; ++i)
      if (back[i] != image[off + i])
        return "firmware echo mismatch at byte " + std::to_string(off + i);
  }
  if (!SetFalconNormalMode(usb)) return "FTDI control transfer failed entering normal mode";
  if (!FalconFirmwareRunning(usb))
    return "image streamed but the firmware does not answer (wrong file?)";
  return "";
}

}  // namespace

int LoadFalconFirmware(UsbTransport& usb, const std::vector<uint8_t>& image,
                       const FirmwareOptions& options,
                       const std::function<void(const std::string&)>& progress) {
  options.Check();
  if (image.empty()) throw Error(usb.Describe(), "empty firmware image");
  std::string reason;
  for (int attempt = 1; attempt <= options.max_attempts; ++attempt) {
    reason = TryLoad(usb, image, options);
    if (reason.empty()) return attempt;
    if (options.cancelled && options.cancelled())
      throw Error(usb.Describe(), "firmware load cancelled");
    if (progress)
      progress("firmware attempt " + std::to_string(attempt) + "/" +
               std::to_string(options.max_attempts) + " failed: " + reason);
  }
  throw Error(usb.Describe(), "firmware load failed after " + std::to_string(options.max_attempts) +
                                  " attempts (last: " + reason +
                                  "); unplug and replug the Falcon's power and USB, "
                                  "check the firmware file, and try again");
}

bool FalconFirmwareRunning(UsbTransport& usb, int packets) {
  FalconCommand zero;
  uint8_t out[kFalconPacketSize];
  EncodeCommand(zero, out);
  FalconPacketParser parser;
  int valid = 0;
  uint8_t raw[256], payload[256];
  for (int i = 0; i < packets; ++i) {
    if (usb.BulkWrite(out, kFalconPacketSize, 100) != kFalconPacketSize) return false;
    const int r = usb.BulkRead(raw, sizeof(raw), 5);
    if (r < 0) return false;
    parser.Push(payload, StripFtdiStatus(raw, static_cast<size_t>(r), payload));
    FalconReply reply;
    while (parser.Next(&reply)) ++valid;
  }
  return valid >= packets / 2;
}

}  // namespace hapcine
