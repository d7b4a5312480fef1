#include "core/camera/device_io.h"

#include <fcntl.h>
#include <libv4l2.h>
#include <linux/videodev2.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

namespace imagepro {

namespace {

class SystemDeviceIo final : public DeviceIo {
 public:
  int open(const char* path) override {
    const int fd = ::open(path, O_RDWR | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return fd;
    // libv4l2 takes over V4L2 devices only: on anything else it would fail the open
    // and print to stderr, where the capability query should name the problem.
    v4l2_capability cap{};
    if (::ioctl(fd, VIDIOC_QUERYCAP, &cap) < 0) return fd;  // the libv4l2 calls pass it through
    // Converted formats are listed too (marked emulated). Should libv4l2 refuse the
    // device, the plain calls still work.
    v4l2_fd_open(fd, V4L2_ENABLE_ENUM_FMT_EMULATION);
    return fd;
  }
  int close(int fd) override { return v4l2_close(fd); }
  int ioctl(int fd, unsigned long request, void* arg) override { return v4l2_ioctl(fd, request, arg); }
  void* map(int fd, std::size_t length, std::int64_t offset) override {
    void* address = v4l2_mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_SHARED, fd, static_cast<off_t>(offset));
    return address == MAP_FAILED ? nullptr : address;
  }
  int unmap(void* address, std::size_t length) override { return v4l2_munmap(address, length); }
  int waitReadable(int fd, int timeout_ms) override {
    pollfd p{fd, POLLIN, 0};
    const int n = ::poll(&p, 1, timeout_ms);
    // POLLERR / POLLHUP (a vanished device) count as ready: the dequeue names the error.
    return n < 0 ? -1 : (n > 0 ? 1 : 0);
  }
};

}  // namespace

DeviceIo& systemDeviceIo() {
  static SystemDeviceIo io;
  return io;
}

}  // namespace imagepro
