#pragma once
// Loading Novint's firmware into a Falcon (needed after every power-up).
// The image is Novint's and may not be redistributed: the user points us at
// their own copy (--firmware PATH); nothing is bundled.
//
// One attempt (novint-falcon.md): purge, 16 ms latency, 9600 baud 8N1, no
// flow control; RTS low, DTR low, DTR high; handshake 0A 43 0D -> 0A 44 2C 0D
// (repeated); DTR low, baud divisor 0x15, 'A' echoed; the image in 62-byte
// writes, each byte echoed and compared; then normal mode (1 ms latency,
// divisor 2, purge). Attempts often fail on real hardware, so the whole
// sequence is retried.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "haptics/usb_transport.h"

namespace hapcine {

struct FirmwareOptions {
  int max_attempts = 20;          // whole-sequence retries (10-20 are common)
  int handshake_tries = 100;      // 0A 43 0D repeats per attempt
  int handshake_timeout_ms = 20;  // wait for each handshake answer
  int echo_timeout_ms = 500;      // wait for each chunk's echo
  // Optional: polled between handshakes and attempts; true stops loading
  // with Error "... cancelled" (the player passes StopRequested: Ctrl-C).
  std::function<bool()> cancelled;
  void Check() const;  // throws UsageError
};

// Reads the image; Error if missing, empty or implausibly large (> 64 KiB).
std::vector<uint8_t> ReadFirmwareFile(const std::string& path);

// Puts `usb` into normal mode (shared by the loader and FalconDevice).
bool SetFalconNormalMode(UsbTransport& usb);

// Loads `image`. Returns the number of attempts used; throws hapcine::Error
// "<device>: firmware load failed after N attempts (<last reason>)".
// `progress` (optional) gets one line per failed attempt.
int LoadFalconFirmware(UsbTransport& usb, const std::vector<uint8_t>& image,
                       const FirmwareOptions& options,
                       const std::function<void(const std::string&)>& progress = {});

// True if firmware already runs: in normal mode, `packets` zero-force
// packets get valid replies.
bool FalconFirmwareRunning(UsbTransport& usb, int packets = 20);

// Reads exactly n payload bytes (status bytes stripped) within timeout_ms.
// Returns the number of bytes obtained (< n on timeout/error).
int ReadFtdiPayload(UsbTransport& usb, uint8_t* out, int n, int timeout_ms);

}  // namespace hapcine
