#pragma once
// The system calls of V4L2 capture behind one small interface: the capture logic
// (camera_source.h, camera_info.h) talks to a real device through libv4l2, and the
// tests talk to a simulated device through the same calls. Every call keeps the
// POSIX convention: failure is -1 (nullptr for map) with the reason in errno.
#include <cstddef>
#include <cstdint>

namespace imagepro {

class DeviceIo {
 public:
  virtual ~DeviceIo() = default;
  // Opens a device node read-write and non-blocking; returns the descriptor.
  virtual int open(const char* path) = 0;
  virtual int close(int fd) = 0;
  virtual int ioctl(int fd, unsigned long request, void* arg) = 0;
  // Maps `length` bytes of a driver buffer at `offset`, shared, read-write.
  virtual void* map(int fd, std::size_t length, std::int64_t offset) = 0;
  virtual int unmap(void* address, std::size_t length) = 0;
  // Waits until a buffer can be dequeued or the device reports an error (then the
  // next ioctl tells which): 1 ready, 0 nothing within timeout_ms, -1 with errno.
  virtual int waitReadable(int fd, int timeout_ms) = 0;
};

// The real devices through libv4l2 (which also offers converted formats for
// devices whose native formats need it). One shared, stateless instance.
DeviceIo& systemDeviceIo();

}  // namespace imagepro
