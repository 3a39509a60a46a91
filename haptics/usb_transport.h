#pragma once
// The USB seam under the Falcon driver. FalconDevice and the firmware loader
// talk to a UsbTransport; LibusbTransport is the real one (libusb-1.0), and
// FakeFalconTransport (fake_falcon_transport.h) is a device in software that
// speaks the protocol byte for byte, so all of the driver is tested without
// hardware.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace hapcine {

constexpr uint16_t kFalconVendorId = 0x0403;   // FTDI
constexpr uint16_t kFalconProductId = 0xCB48;  // Novint Falcon
constexpr uint8_t kFalconEndpointOut = 0x02;
constexpr uint8_t kFalconEndpointIn = 0x81;

// FTDI vendor requests (bmRequestType 0x40, wIndex 0).
namespace ftdi {
constexpr uint8_t kReset = 0;         // wValue 1 purge RX, 2 purge TX
constexpr uint8_t kModemControl = 1;  // 0x0101 DTR high, 0x0100 DTR low, 0x0200 RTS low
constexpr uint8_t kFlowControl = 2;   // 0 off
constexpr uint8_t kBaudRate = 3;      // divisor
constexpr uint8_t kLineSettings = 4;  // 8 = 8N1
constexpr uint8_t kLatencyTimer = 9;  // milliseconds
constexpr uint16_t kPurgeRx = 1, kPurgeTx = 2;
constexpr uint16_t kDtrHigh = 0x0101, kDtrLow = 0x0100, kRtsLow = 0x0200;
constexpr uint16_t kBaud9600 = 0x4138, kBaudFirmware = 0x0015, kBaudNormal = 0x0002;
}  // namespace ftdi

class UsbTransport {
 public:
  virtual ~UsbTransport() = default;
  // Vendor OUT control transfer without data (bmRequestType 0x40, wIndex 0).
  // Returns false on failure.
  virtual bool Control(uint8_t request, uint16_t value) = 0;
  // Writes n bytes to the OUT endpoint. Returns bytes written, -1 on error.
  virtual int BulkWrite(const uint8_t* data, int n, int timeout_ms) = 0;
  // Reads raw IN data (including the 2 FTDI status bytes per 64-byte
  // packet) into buf. Returns bytes read (0 on timeout), -1 on error (for
  // example the device was unplugged).
  virtual int BulkRead(uint8_t* buf, int capacity, int timeout_ms) = 0;
  virtual std::string Describe() const = 0;
};

struct UsbDeviceInfo {
  int bus = 0;
  int address = 0;
  std::string serial;   // empty if it could not be read
  std::string problem;  // why the device cannot be opened (e.g. permissions)
};

// Every 0403:cb48 device on the system. Throws Error only if libusb itself
// cannot start.
std::vector<UsbDeviceInfo> ListFalconUsbDevices();
// "none found" or one line per device, for error messages.
std::string DescribeFalconUsbDevices(const std::vector<UsbDeviceInfo>& devices);
// Every USB device libusb sees, as "vid:pid" (Falcon or not), for the "no
// Falcon" message: "USB devices present: 1d6b:0002, 046d:c52b" or a note
// that libusb sees none at all.
std::string DescribeAllUsbDevices();

// Opens the Falcon with FTDI serial `serial` (empty: the only one present),
// detaching ftdi_sio and claiming interface 0. Throws hapcine::Error naming
// what was found when it cannot.
std::unique_ptr<UsbTransport> OpenLibusbTransport(const std::string& serial);

}  // namespace hapcine
