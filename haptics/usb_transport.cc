#include "haptics/usb_transport.h"

#include <libusb.h>

#include <cstdio>
#include <sstream>

#include "core/error.h"

namespace hapcine {
namespace {

constexpr int kControlTimeoutMs = 1000;

// One libusb context per process, created on first use and kept: libusb
// contexts are cheap and closing one under an open handle is undefined.
libusb_context* Context() {
  static libusb_context* ctx = [] {
    libusb_context* c = nullptr;
    const int rc = libusb_init(&c);
    if (rc != 0) throw Error("libusb", std::string("cannot initialise: ") + libusb_error_name(rc));
    return c;
  }();
  return ctx;
}

std::string ReadSerial(libusb_device_handle* h, const libusb_device_descriptor& desc) {
  if (desc.iSerialNumber == 0) return "";
  unsigned char buf[128];
  const int n = libusb_get_string_descriptor_ascii(h, desc.iSerialNumber, buf, sizeof(buf));
  return n > 0 ? std::string(reinterpret_cast<char*>(buf), n) : "";
}

class LibusbTransport : public UsbTransport {
 public:
  LibusbTransport(libusb_device_handle* h, std::string serial)
      : h_(h), serial_(std::move(serial)) {}
  ~LibusbTransport() override {
    libusb_release_interface(h_, 0);
    libusb_close(h_);
  }
  bool Control(uint8_t request, uint16_t value) override {
    return libusb_control_transfer(h_, 0x40, request, value, 0, nullptr, 0, kControlTimeoutMs) >= 0;
  }
  int BulkWrite(const uint8_t* data, int n, int timeout_ms) override {
    int done = 0;
    const int rc = libusb_bulk_transfer(h_, kFalconEndpointOut, const_cast<uint8_t*>(data), n,
                                        &done, timeout_ms < 1 ? 1 : timeout_ms);
    if (rc != 0 && rc != LIBUSB_ERROR_TIMEOUT) return -1;
    return done;
  }
  int BulkRead(uint8_t* buf, int capacity, int timeout_ms) override {
    int done = 0;
    // A timeout of 0 means "wait forever" to libusb: never pass it.
    const int rc = libusb_bulk_transfer(h_, kFalconEndpointIn, buf, capacity, &done,
                                        timeout_ms < 1 ? 1 : timeout_ms);
    if (rc != 0 && rc != LIBUSB_ERROR_TIMEOUT) return -1;
    return done;  // partial data on timeout is kept (libusb documents it)
  }
  std::string Describe() const override { return "Falcon serial " + serial_; }

 private:
  libusb_device_handle* h_;
  std::string serial_;
};

}  // namespace

std::vector<UsbDeviceInfo> ListFalconUsbDevices() {
  libusb_context* ctx = Context();
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(ctx, &list);
  std::vector<UsbDeviceInfo> out;
  for (ssize_t i = 0; i < n; ++i) {
    libusb_device_descriptor desc;
    if (libusb_get_device_descriptor(list[i], &desc) != 0) continue;
    if (desc.idVendor != kFalconVendorId || desc.idProduct != kFalconProductId) continue;
    UsbDeviceInfo info;
    info.bus = libusb_get_bus_number(list[i]);
    info.address = libusb_get_device_address(list[i]);
    libusb_device_handle* h = nullptr;
    const int rc = libusb_open(list[i], &h);
    if (rc == 0) {
      info.serial = ReadSerial(h, desc);
      libusb_close(h);
    } else if (rc == LIBUSB_ERROR_ACCESS) {
      info.problem = "permission denied (install scripts/99-hapcine-falcon.rules)";
    } else {
      info.problem = libusb_error_name(rc);
    }
    out.push_back(info);
  }
  if (list) libusb_free_device_list(list, 1);
  return out;
}

std::string DescribeFalconUsbDevices(const std::vector<UsbDeviceInfo>& devices) {
  if (devices.empty()) return "no USB device 0403:cb48 (Novint Falcon) found";
  std::ostringstream s;
  s << devices.size() << " USB device(s) 0403:cb48 found:";
  for (const auto& d : devices) {
    s << " [bus " << d.bus << " address " << d.address << " serial '"
      << (d.serial.empty() ? "?" : d.serial) << "'";
    if (!d.problem.empty()) s << ": " << d.problem;
    s << "]";
  }
  return s.str();
}

std::string DescribeAllUsbDevices() {
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(Context(), &list);
  std::ostringstream s;
  int shown = 0;
  for (ssize_t i = 0; i < n; ++i) {
    libusb_device_descriptor desc;
    if (libusb_get_device_descriptor(list[i], &desc) != 0) continue;
    char id[16];
    std::snprintf(id, sizeof(id), "%04x:%04x", desc.idVendor, desc.idProduct);
    s << (shown++ ? ", " : "USB devices present: ") << id;
  }
  if (list) libusb_free_device_list(list, 1);
  if (shown == 0) return "libusb sees no USB devices at all (no access to /dev/bus/usb?)";
  return s.str();
}

std::unique_ptr<UsbTransport> OpenLibusbTransport(const std::string& serial) {
  libusb_context* ctx = Context();
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(ctx, &list);
  libusb_device_handle* found = nullptr;
  std::string found_serial;
  int matches = 0;
  for (ssize_t i = 0; i < n; ++i) {
    libusb_device_descriptor desc;
    if (libusb_get_device_descriptor(list[i], &desc) != 0) continue;
    if (desc.idVendor != kFalconVendorId || desc.idProduct != kFalconProductId) continue;
    libusb_device_handle* h = nullptr;
    if (libusb_open(list[i], &h) != 0) continue;
    const std::string s = ReadSerial(h, desc);
    if (serial.empty() || s == serial) {
      ++matches;
      if (!found) {
        found = h;
        found_serial = s;
        continue;
      }
    }
    libusb_close(h);
  }
  if (list) libusb_free_device_list(list, 1);
  const std::string who = serial.empty() ? "Falcon" : "Falcon serial '" + serial + "'";
  if (!found) throw Error(who, "cannot open: " + DescribeFalconUsbDevices(ListFalconUsbDevices()));
  if (serial.empty() && matches > 1) {
    libusb_close(found);
    throw Error(who, "several Falcons connected: choose with a seat config (--seat-config); " +
                         DescribeFalconUsbDevices(ListFalconUsbDevices()));
  }
  libusb_set_auto_detach_kernel_driver(found, 1);  // ftdi_sio may own it
  const int rc = libusb_claim_interface(found, 0);
  if (rc != 0) {
    libusb_close(found);
    throw Error(who, std::string("cannot claim interface 0: ") + libusb_error_name(rc));
  }
  return std::make_unique<LibusbTransport>(found, found_serial);
}

}  // namespace hapcine
