#pragma once
// The Camera source of thesis 2.2 ("direct access to the frame grabber ... grayscale
// (8-bit) frames", 25 frames/s in 5.2.1) on a V4L2 device: format, size and rate
// negotiated with the driver (camera_info.h), memory-mapped streaming with several
// buffers, grey frames in place where the format allows (pixel_format.h), the
// driver's timestamps as frame times, the achieved rate measured, the device's
// controls listed and set. Every failure is a named Status; a device that vanishes
// while streaming (ENODEV / EIO) gives CameraDisconnected, the source closes it, and
// restart() opens it again once it is back.
#include <array>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "core/camera/camera_info.h"
#include "core/camera/device_io.h"
#include "core/camera/pixel_format.h"
#include "core/source/source.h"

namespace imagepro {

// What to ask the device for.
struct CameraRequest {
  std::string device = "/dev/video0";
  int width = 0;                 // 0 x 0: the largest size that reaches the rate
  int height = 0;
  double frame_rate_hz = 25.0;   // thesis 5.2.1; 0 leaves the driver's rate
  int input = -1;                // a capture card's input, set before the format; -1 leaves the device's
  TvStandard standard = TvStandard::Keep;  // the input's TV standard; Keep leaves the device's
  int buffers = 4;               // driver buffers in the streaming queue (2..32)
  int timeout_ms = 2000;         // longest wait for one frame before CameraTimeout
};

// What the driver agreed to.
struct CameraFormat {
  std::string device;
  std::string card;
  std::uint32_t fourcc = 0;
  PixelFormat format = PixelFormat::Grey;
  int width = 0;
  int height = 0;
  std::size_t bytes_per_line = 0;
  std::size_t buffer_bytes = 0;
  double nominal_rate_hz = 0.0;  // the driver's frame interval; 0 when it gives none
  int buffers = 0;
  bool size_adjusted = false;    // not the size asked for (the driver's or the closest offered)
  bool rate_adjusted = false;    // not the rate asked for
  bool format_adjusted = false;  // the driver answered with another pixel format
};

struct CaptureStats {
  std::int64_t frames = 0;      // delivered by next()
  std::int64_t dropped = 0;     // gaps in the driver's frame sequence numbers
  std::int64_t corrupt = 0;     // buffers flagged bad by the driver or undecodable
  std::int64_t timeouts = 0;
  std::int64_t restarts = 0;    // successful restart() calls
  double achieved_rate_hz = 0;  // over the last frames, from the driver's timestamps
};

// True for the camera errors after which next() cannot succeed without restart().
bool isCameraFailure(Status s);

// Threading: next(), start(), stop() and restart() belong to the frame loop's
// thread; format(), stats(), describe(), controls() and setControl() may be called
// from any thread while it runs.
class CameraSource final : public FrameSource {
 public:
  explicit CameraSource(CameraRequest request, DeviceIo& io = systemDeviceIo());
  ~CameraSource() override;
  CameraSource(const CameraSource&) = delete;
  CameraSource& operator=(const CameraSource&) = delete;

  // Opens the device, selects the input and the standard, negotiates, maps the buffers
  // and starts streaming. Errors: CameraNotFound, CameraPermissionDenied, CameraBusy,
  // CameraNoSuchInput, CameraStandardRefused, CameraNoSupportedFormat,
  // CameraFormatRefused, with lastError() naming the device and the reason.
  Status start();
  // Stops streaming and closes the device (nothing happens when it is not open).
  void stop();
  // stop() then start(): after CameraDisconnected, once the device is back. Frame
  // indices go on from where they were; times stay on the same clock.
  Status restart();
  bool streaming() const;

  // The next frame: waits up to timeout_ms for the driver. Frame::image is a view
  // of the driver's buffer (or of a reused conversion buffer): valid until the next
  // call of next(), stop() or the destructor; clone it to keep it. Frame::index
  // counts delivered frames from 0; Frame::timestamp_s is the driver's capture time
  // in seconds after the first frame. Statuses: CameraTimeout (streaming goes on),
  // EmptyFrame for a buffer the driver flagged or a frame that cannot be decoded
  // (streaming goes on), CameraDisconnected (the device is closed), or the start()
  // error while the source is not streaming. Frame::image is empty unless Ok.
  Status next(Frame& out) override;
  std::string lastError() const override;
  // 0: the camera paces itself (next() waits for the driver); see format() and
  // stats() for the nominal and the achieved rate.
  double frameRateHz() const override { return 0.0; }
  // "camera /dev/video0 640x480 YUYV 25 Hz (24.9 Hz achieved)".
  std::string describe() const override;

  const CameraRequest& request() const { return request_; }
  CameraFormat format() const;
  CaptureStats stats() const;
  // The device's controls with their current values (while streaming).
  Status controls(std::vector<CameraControl>& out);
  // Sets a control by id (from controls()); InvalidSettings when the value does not
  // fit or the control cannot be set now, CameraDisconnected when the device is gone.
  Status setControl(std::uint32_t id, std::int64_t value);

 private:
  struct Buffer {
    void* start = nullptr;
    std::size_t length = 0;
  };

  Status fail(Status s, std::string message);  // under the lock
  Status openAndNegotiate();                   // under the lock
  // The steps of openAndNegotiate(), in its order; each fail()s with its own words.
  Status openDevice(DeviceInfo& info);         // open, and check it captures and streams
  Status chooseFormat(CaptureChoice& choice);  // input and standard, then format, size, rate
  Status setFormat(const CaptureChoice& choice, const std::string& card);  // S_FMT; the answer checked
  Status setFrameRate(const CaptureChoice& choice);
  Status mapBuffers();
  Status startStreaming(const std::string& asked);  // queue every buffer, STREAMON
  // A setup call failed with `err`: the device went, is busy or is barred, else `otherwise`.
  // lastError(): "<device>: <status message>[: <asked>] ([<during>: ]<errno text>)".
  Status failSetup(int err, Status otherwise, std::string_view during, std::string_view asked = {});
  Status bufferFailed(const char* during, std::uint32_t index);  // failSetup() for buffer `index`
  void closeDevice();                          // under the lock
  Status disconnect(int err, const char* during);  // takes the lock
  Status requeue(int index);
  void noteTimestamp(double t);                     // under the lock

  CameraRequest request_;
  DeviceIo& io_;
  mutable std::mutex mutex_;  // guards everything below against the other threads
  int fd_ = -1;
  bool requested_buffers_ = false;
  bool streaming_ = false;
  bool stopped_ = false;         // stop() was called: next() gives EndOfStream
  Status failure_ = Status::Ok;  // why the source is not streaming, if it failed
  std::string error_;
  CameraFormat format_;
  BufferLayout layout_;
  std::vector<Buffer> buffers_;
  int held_ = -1;  // buffer lent out as the last frame's image
  cv::Mat scratch_;
  CaptureStats stats_;
  std::int64_t next_index_ = 0;
  bool have_epoch_ = false;
  double epoch_s_ = 0.0;
  bool have_sequence_ = false;
  std::uint32_t last_sequence_ = 0;
  // Ring of recent frame times for the achieved rate.
  static constexpr int kRateWindow = 32;
  std::array<double, kRateWindow> times_{};
  int times_count_ = 0;
  int times_next_ = 0;
};

}  // namespace imagepro
