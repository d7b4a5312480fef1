#pragma once
// A simulated V4L2 capture device behind DeviceIo: the formats, sizes and intervals it
// lists, how its driver answers format and rate requests, memory-mapped buffers with
// frames of a known pattern, time-outs, damaged and lost frames, a device that
// vanishes mid-stream and comes back, and controls. Tests configure the public
// fields, run the capture logic against it and inspect what happened.
#include <linux/videodev2.h>

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "core/camera/camera_info.h"
#include "core/camera/device_io.h"

namespace imagepro::test {

struct FakeSize {
  int width = 0;
  int height = 0;
  std::vector<FrameInterval> intervals;
};

struct FakeFormat {
  std::uint32_t fourcc = 0;
  std::string description;
  std::vector<FakeSize> sizes;
  bool emulated = false;
};

struct FakeControl {
  v4l2_queryctrl query{};
  std::int64_t value = 0;
  std::map<std::uint32_t, std::string> menu;  // index -> name
};

// An input of a capture card; `standards` is the V4L2 standard mask it takes.
struct FakeInput {
  std::string name;
  std::uint32_t type = V4L2_INPUT_TYPE_CAMERA;
  v4l2_std_id standards = 0;
};

struct FakeStandard {
  v4l2_std_id id = 0;
  std::string name;
  v4l2_fract frame_period{1, 25};
};

// The luma every frame carries at (x, y) in frame `sequence`.
inline std::uint8_t referenceLuma(int x, int y, std::uint32_t sequence) {
  return static_cast<std::uint8_t>((x * 7 + y * 13 + static_cast<int>(sequence) * 5) & 0xff);
}

class FakeDevice final : public DeviceIo {
 public:
  FakeDevice();

  // ---- the device
  std::string path = "/dev/video-fake";
  int open_errno = 0;  // open() fails with this (EACCES, EBUSY ...)
  std::string card = "Fake Camera";
  std::uint32_t device_caps = V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_STREAMING;
  std::vector<FakeFormat> formats;
  std::vector<FakeControl> controls;
  // A capture card's: empty for a camera without inputs or standards. VIDIOC_ENUMSTD
  // lists the standards the current input takes, as drivers do.
  std::vector<FakeInput> inputs;
  std::vector<FakeStandard> standards;
  std::uint32_t input = 0;   // the current input
  v4l2_std_id standard = 0;  // the current standard

  // ---- how the driver answers
  int s_fmt_errno = 0;                                  // S_FMT fails with this
  std::function<void(v4l2_pix_format&)> adjust_format;  // after the usual nearest-size answer
  std::uint32_t line_padding = 0;                       // bytes added to every line
  bool timeperframe = true;                             // frame interval settable
  std::uint32_t max_buffers = 8;
  int streamon_errno = 0;
  // Runs after a control is set (a driver making dependent controls active or inactive).
  std::function<void(std::uint32_t id, std::int64_t value)> after_set;

  // ---- the stream
  bool stalled = false;                   // no frame arrives
  int vanish_after = -1;                  // frames delivered before the device vanishes
  int vanish_errno = ENODEV;              // what dequeuing reports then
  std::set<std::uint32_t> lost_sequences; // never delivered (a gap in sequence numbers)
  std::set<std::uint32_t> damaged_sequences;  // delivered with V4L2_BUF_FLAG_ERROR
  double first_timestamp_s = 1000.0;

  void vanish();     // unplugged: open descriptors fail with ENODEV, open() with ENOENT
  void reappear();   // plugged in again (old descriptors stay dead)

  // ---- what happened
  int opens = 0;
  int closes = 0;
  int openDescriptors() const;
  int mappedBuffers() const;
  bool streaming() const;
  std::vector<int> wait_timeouts;  // timeout_ms of every waitReadable
  v4l2_pix_format current{};       // the format set last
  FrameInterval interval{1, 25};
  std::uint32_t delivered = 0;     // frames dequeued
  std::vector<std::string> selections;  // "input 1", "standard 0x..." in the order they were set
  const std::vector<std::uint8_t>& bufferData(std::size_t index) const { return buffers_[index]; }
  std::size_t bufferCount() const { return buffers_.size(); }

  // DeviceIo
  int open(const char* path) override;
  int close(int fd) override;
  int ioctl(int fd, unsigned long request, void* arg) override;
  void* map(int fd, std::size_t length, std::int64_t offset) override;
  int unmap(void* address, std::size_t length) override;
  int waitReadable(int fd, int timeout_ms) override;

 private:
  int fail(int err);
  int handle(unsigned long request, void* arg);
  std::size_t fill(std::uint8_t* data, std::size_t length, std::uint32_t sequence) const;
  const FakeFormat* findFormat(std::uint32_t fourcc) const;
  const FakeSize* findSize(const FakeFormat& f, int width, int height) const;

  mutable std::recursive_mutex mutex_;
  bool present_ = true;
  int generation_ = 0;
  int next_fd_ = 40;
  std::map<int, int> fds_;  // descriptor -> generation it was opened in
  std::vector<std::vector<std::uint8_t>> buffers_;
  std::vector<bool> mapped_;
  std::deque<std::uint32_t> queued_;
  bool streaming_ = false;
  std::uint32_t next_sequence_ = 0;
};

// A usual USB camera: YUYV 640x480 (30, 25, 15 Hz) and 320x240 (30 Hz), MJPG 1280x720
// (30 Hz) and 640x480 (30 Hz); brightness, an exposure menu and
// an inactive exposure time, a gain, a control-class heading and a disabled control.
void addStandardFormats(FakeDevice& device);
void addStandardControls(FakeDevice& device);
// A PXC200-like composite / S-Video card: GREY 768x576 and 640x480; inputs Composite0
// (PAL, NTSC, SECAM), Composite1 (PAL, NTSC) and S-Video (NTSC); PAL-BG, NTSC-M and
// SECAM-L listed; Composite0 in PAL-BG to begin with.
void addCaptureCard(FakeDevice& device);

}  // namespace imagepro::test
