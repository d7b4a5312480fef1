#include "core/camera/camera_source.h"

#include "core/common/image_limits.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/camera/v4l2_access.h"

namespace imagepro {

namespace {

using Clock = std::chrono::steady_clock;

double steadySeconds() { return std::chrono::duration<double>(Clock::now().time_since_epoch()).count(); }

// Setup failures that are not about the format: the device went, is used, or is barred.
Status setupFailure(int err, Status otherwise) {
  switch (err) {
    case ENODEV:
    case ENXIO: return Status::CameraNotFound;
    case EBUSY: return Status::CameraBusy;
    case EACCES:
    case EPERM: return Status::CameraPermissionDenied;
    default: return otherwise;
  }
}

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

// "YUYV 640x480": the format and size S_FMT asks for.
std::string askedText(const CaptureChoice& choice) {
  return fourccText(choice.fourcc) + " " + sizeText(choice.width, choice.height);
}

// The memory-mapped capture buffer `index`, as QUERYBUF and QBUF take it.
v4l2_buffer mmapBuffer(std::uint32_t index) {
  v4l2_buffer b{};
  b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  b.memory = V4L2_MEMORY_MMAP;
  b.index = index;
  return b;
}

std::string rateText(double hz) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g Hz", hz);
  return buf;
}

}  // namespace

bool isCameraFailure(Status s) {
  switch (s) {
    case Status::CameraNotFound:
    case Status::CameraPermissionDenied:
    case Status::CameraBusy:
    case Status::CameraNoSupportedFormat:
    case Status::CameraFormatRefused:
    case Status::CameraDisconnected: return true;
    default: return false;
  }
}

CameraSource::CameraSource(CameraRequest request, DeviceIo& io) : request_(std::move(request)), io_(io) {
  format_.device = request_.device;
}

CameraSource::~CameraSource() {
  std::lock_guard lock(mutex_);
  closeDevice();
}

Status CameraSource::fail(Status s, std::string message) {
  failure_ = s;
  error_ = std::move(message);
  return s;
}

Status CameraSource::start() {
  std::lock_guard lock(mutex_);
  if (streaming_) return Status::Ok;
  const Status s = openAndNegotiate();
  if (!ok(s)) closeDevice();
  return s;
}

void CameraSource::stop() {
  std::lock_guard lock(mutex_);
  closeDevice();
  failure_ = Status::Ok;
  stopped_ = true;
}

Status CameraSource::restart() {
  std::lock_guard lock(mutex_);
  closeDevice();
  const Status s = openAndNegotiate();
  if (!ok(s)) {
    closeDevice();
    return s;
  }
  ++stats_.restarts;
  return s;
}

bool CameraSource::streaming() const {
  std::lock_guard lock(mutex_);
  return streaming_;
}

Status CameraSource::openAndNegotiate() {
  failure_ = Status::Ok;
  stopped_ = false;
  error_.clear();
  DeviceInfo info;
  CaptureChoice choice;
  Status s = openDevice(info);
  if (ok(s)) s = chooseFormat(choice);
  if (ok(s)) s = setFormat(choice, info.card);
  if (ok(s)) s = setFrameRate(choice);
  if (ok(s)) s = mapBuffers();
  if (ok(s)) s = startStreaming(askedText(choice));
  return s;
}

Status CameraSource::failSetup(int err, Status otherwise, std::string_view during, std::string_view asked) {
  const Status why = setupFailure(err, otherwise);
  std::string message = request_.device + ": " + std::string(statusMessage(why));
  if (!asked.empty()) message += ": " + std::string(asked);
  message += " (";
  if (!during.empty()) message += std::string(during) + ": ";
  return fail(why, message + v4l2::errnoText(err) + ")");
}

Status CameraSource::openDevice(DeviceInfo& info) {
  const std::string& dev = request_.device;
  std::string err;
  int fd = -1;
  Status s = v4l2::openDevice(io_, dev, fd, err);
  if (!ok(s)) return fail(s, err);
  fd_ = fd;
  info.path = dev;
  s = v4l2::readCapabilities(io_, fd_, info, err);
  if (!ok(s)) return fail(s, err);
  if (!info.video_capture)
    return fail(Status::CameraNotFound, dev + ": " + info.card +
                                            " is not a video capture node (a camera's second node carries metadata)");
  if (!info.streaming)
    return fail(Status::CameraNoSupportedFormat, dev + ": the driver offers no memory-mapped streaming");
  return Status::Ok;
}

Status CameraSource::chooseFormat(CaptureChoice& choice) {
  const std::string& dev = request_.device;
  std::string err;
  // A capture card's input and standard first: the sizes and rates it offers follow from them.
  Status s = selectInputAndStandard(io_, fd_, dev, request_.input, request_.standard, err);
  if (!ok(s)) return fail(s, err);
  std::vector<FormatInfo> formats;
  v4l2::readFormats(io_, fd_, formats);
  s = chooseCapture(formats, request_.width, request_.height, request_.frame_rate_hz, choice, err);
  if (!ok(s)) return fail(s, dev + ": " + err);
  v4l2_format fmt{};
  fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  if (choice.width <= 0 && v4l2::xioctl(io_, fd_, VIDIOC_G_FMT, &fmt) == 0) {
    choice.width = static_cast<int>(fmt.fmt.pix.width);  // no size listed or asked for: keep the current one
    choice.height = static_cast<int>(fmt.fmt.pix.height);
  }
  // Neither asked for nor accepted beyond what a frame may hold: the buffers and the
  // pipeline's images would take gigabytes before anything failed.
  if (const std::string problem = imageSizeProblem(choice.width, choice.height);
      choice.width > 0 && choice.height > 0 && !problem.empty())
    return fail(Status::ImageTooLarge, dev + ": " + std::string(statusMessage(Status::ImageTooLarge)) + ": " + problem);
  return Status::Ok;
}

Status CameraSource::setFormat(const CaptureChoice& choice, const std::string& card) {
  const std::string& dev = request_.device;
  v4l2_format fmt{};
  fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  v4l2_pix_format& pix = fmt.fmt.pix;
  pix.width = static_cast<std::uint32_t>(std::max(0, choice.width));
  pix.height = static_cast<std::uint32_t>(std::max(0, choice.height));
  pix.pixelformat = choice.fourcc;
  pix.field = V4L2_FIELD_ANY;
  const std::string asked = askedText(choice);
  if (v4l2::xioctl(io_, fd_, VIDIOC_S_FMT, &fmt) < 0) return failSetup(errno, Status::CameraFormatRefused, {}, asked);
  const auto got = pixelFormatFromFourcc(pix.pixelformat);
  if (!got)
    return fail(Status::CameraFormatRefused, dev + ": asked for " + asked + ", the driver answered with " +
                                                 fourccText(pix.pixelformat) + ", which ImagePro cannot read");
  format_ = CameraFormat{};
  format_.device = dev;
  format_.card = card;
  format_.fourcc = pix.pixelformat;
  format_.format = *got;
  format_.width = static_cast<int>(pix.width);
  format_.height = static_cast<int>(pix.height);
  format_.buffer_bytes = pix.sizeimage;
  format_.format_adjusted = pix.pixelformat != choice.fourcc;
  const bool size_asked = request_.width > 0 && request_.height > 0;
  format_.size_adjusted = size_asked && (format_.width != request_.width || format_.height != request_.height);
  if (const std::string problem = imageSizeProblem(format_.width, format_.height);
      format_.width > 0 && format_.height > 0 && !problem.empty())
    return fail(Status::ImageTooLarge, dev + ": the driver answered the request for " + asked +
                                           " with a size beyond what a frame may hold: " + problem);
  const std::size_t min_line = minimumBytesPerLine(*got, format_.width);
  format_.bytes_per_line = pix.bytesperline == 0 ? min_line : pix.bytesperline;
  if (format_.width <= 0 || format_.height <= 0 || format_.bytes_per_line < min_line)
    return fail(Status::CameraFormatRefused, dev + ": the driver answered " + asked + " with an unusable layout (" +
                                                 sizeText(format_.width, format_.height) + ", " +
                                                 std::to_string(pix.bytesperline) + " bytes per line)");
  layout_ = {*got, format_.width, format_.height, format_.bytes_per_line};
  return Status::Ok;
}

Status CameraSource::setFrameRate(const CaptureChoice& choice) {
  // Only drivers that announce a settable frame interval are asked.
  v4l2_streamparm parm{};
  parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  FrameInterval current;
  bool settable = false;
  if (v4l2::xioctl(io_, fd_, VIDIOC_G_PARM, &parm) == 0) {
    current = {parm.parm.capture.timeperframe.numerator, parm.parm.capture.timeperframe.denominator};
    settable = (parm.parm.capture.capability & V4L2_CAP_TIMEPERFRAME) != 0;
  }
  if (request_.frame_rate_hz > 0.0 && settable && choice.interval.numerator != 0) {
    parm = v4l2_streamparm{};
    parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    parm.parm.capture.timeperframe = {choice.interval.numerator, choice.interval.denominator};
    if (v4l2::xioctl(io_, fd_, VIDIOC_S_PARM, &parm) == 0)
      current = {parm.parm.capture.timeperframe.numerator, parm.parm.capture.timeperframe.denominator};
    else if (const int e = errno; e == EBUSY || e == ENODEV)  // any other refusal keeps the driver's rate
      return failSetup(e, Status::CameraBusy, "setting the frame rate");
  }
  format_.nominal_rate_hz = current.rateHz();
  format_.rate_adjusted =
      request_.frame_rate_hz > 0.0 && std::abs(format_.nominal_rate_hz - request_.frame_rate_hz) > 1e-3;
  return Status::Ok;
}

Status CameraSource::mapBuffers() {
  v4l2_requestbuffers req{};
  req.count = static_cast<std::uint32_t>(std::clamp(request_.buffers, 2, 32));
  req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  req.memory = V4L2_MEMORY_MMAP;
  if (v4l2::xioctl(io_, fd_, VIDIOC_REQBUFS, &req) < 0)
    return failSetup(errno, Status::CameraFormatRefused, "memory-mapped buffers");
  requested_buffers_ = true;
  if (req.count < 2)
    return fail(Status::CameraFormatRefused, request_.device + ": the driver granted " + std::to_string(req.count) +
                                                 " buffer(s), streaming needs 2");
  buffers_.assign(req.count, Buffer{});
  for (std::uint32_t i = 0; i < req.count; ++i) {
    v4l2_buffer b = mmapBuffer(i);
    if (v4l2::xioctl(io_, fd_, VIDIOC_QUERYBUF, &b) < 0) return bufferFailed("buffer ", i);
    void* start = io_.map(fd_, b.length, b.m.offset);
    if (start == nullptr) return bufferFailed("mapping buffer ", i);
    buffers_[i] = {start, b.length};
  }
  return Status::Ok;
}

Status CameraSource::startStreaming(const std::string& asked) {
  for (std::uint32_t i = 0; i < buffers_.size(); ++i) {
    v4l2_buffer b = mmapBuffer(i);
    if (v4l2::xioctl(io_, fd_, VIDIOC_QBUF, &b) < 0) return bufferFailed("queueing buffer ", i);
  }
  int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  if (v4l2::xioctl(io_, fd_, VIDIOC_STREAMON, &type) < 0) {
    const int e = errno;
    if (e == ENOSPC)
      return fail(Status::CameraBusy, request_.device + ": not enough USB bandwidth for " + asked +
                                          " (another camera on the bus?); choose a smaller size or rate");
    return failSetup(e, Status::CameraFormatRefused, "starting the stream");
  }
  streaming_ = true;
  format_.buffers = static_cast<int>(buffers_.size());
  held_ = -1;
  have_sequence_ = false;
  times_count_ = 0;
  times_next_ = 0;
  return Status::Ok;
}

Status CameraSource::bufferFailed(const char* during, std::uint32_t index) {
  const int e = errno;  // before building the words, which may allocate
  return failSetup(e, Status::CameraFormatRefused, during + std::to_string(index));
}

void CameraSource::closeDevice() {
  if (fd_ >= 0 && streaming_) {
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    v4l2::xioctl(io_, fd_, VIDIOC_STREAMOFF, &type);  // fails harmlessly on a vanished device
  }
  for (const Buffer& b : buffers_)
    if (b.start != nullptr) io_.unmap(b.start, b.length);
  buffers_.clear();
  if (fd_ >= 0) {
    if (requested_buffers_) {
      v4l2_requestbuffers req{};  // give the driver's buffers back (after unmapping them)
      req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      req.memory = V4L2_MEMORY_MMAP;
      v4l2::xioctl(io_, fd_, VIDIOC_REQBUFS, &req);
    }
    io_.close(fd_);
  }
  fd_ = -1;
  requested_buffers_ = false;
  streaming_ = false;
  held_ = -1;
}

Status CameraSource::disconnect(int err, const char* during) {
  std::lock_guard lock(mutex_);
  closeDevice();
  return fail(Status::CameraDisconnected, request_.device + ": " +
                                              std::string(statusMessage(Status::CameraDisconnected)) + " (" +
                                              during + ": " + v4l2::errnoText(err) + "); restart once it is back");
}

Status CameraSource::requeue(int index) {
  v4l2_buffer b = mmapBuffer(static_cast<std::uint32_t>(index));
  if (v4l2::xioctl(io_, fd_, VIDIOC_QBUF, &b) < 0) return disconnect(errno, "queueing a buffer");
  return Status::Ok;
}

void CameraSource::noteTimestamp(double t) {
  times_[static_cast<std::size_t>(times_next_)] = t;
  times_next_ = (times_next_ + 1) % kRateWindow;
  times_count_ = std::min(times_count_ + 1, kRateWindow);
  if (times_count_ < 2) return;
  const double newest = times_[static_cast<std::size_t>((times_next_ + kRateWindow - 1) % kRateWindow)];
  const double oldest = times_[static_cast<std::size_t>((times_next_ + kRateWindow - times_count_) % kRateWindow)];
  if (newest > oldest) stats_.achieved_rate_hz = (times_count_ - 1) / (newest - oldest);
}

Status CameraSource::next(Frame& out) {
  // The frame loop's thread alone opens and closes the device, so it reads fd_,
  // streaming_ and the buffers without the lock; it takes the lock to change them.
  // The last image may be a view of a buffer about to go back to the driver (or
  // unmapped after a failure): never leave it in `out`.
  out.image.release();
  if (!streaming_) {
    if (stopped_) return Status::EndOfStream;
    if (failure_ != Status::Ok) return failure_;
    if (const Status s = start(); !ok(s)) return s;
  }
  out.name.clear();
  out.truth.reset();
  if (held_ >= 0) {
    const int index = held_;
    held_ = -1;
    if (const Status s = requeue(index); !ok(s)) return s;
  }

  const auto deadline = Clock::now() + std::chrono::milliseconds(std::max(0, request_.timeout_ms));
  v4l2_buffer b{};
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    const int r = io_.waitReadable(fd_, static_cast<int>(std::max<std::int64_t>(0, left)));
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) return disconnect(errno, "waiting for a frame");
    if (r > 0) {
      b = v4l2_buffer{};
      b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      b.memory = V4L2_MEMORY_MMAP;
      if (v4l2::xioctl(io_, fd_, VIDIOC_DQBUF, &b) == 0) break;
      if (errno != EAGAIN) return disconnect(errno, "dequeuing a frame");
    }
    if (Clock::now() >= deadline) {
      std::lock_guard lock(mutex_);
      ++stats_.timeouts;
      error_ = request_.device + ": no frame within " + std::to_string(request_.timeout_ms) + " ms";
      return Status::CameraTimeout;
    }
  }
  if (b.index >= buffers_.size()) return disconnect(EINVAL, "the driver returned an unknown buffer");

  const bool driver_time = (b.flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) == V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC &&
                           (b.timestamp.tv_sec != 0 || b.timestamp.tv_usec != 0);
  const double t = driver_time ? static_cast<double>(b.timestamp.tv_sec) + 1e-6 * static_cast<double>(b.timestamp.tv_usec)
                               : steadySeconds();
  if (!have_epoch_) {
    epoch_s_ = t;
    have_epoch_ = true;
  }
  out.index = next_index_++;
  out.timestamp_s = t - epoch_s_;
  held_ = static_cast<int>(b.index);  // requeued at the next call: the image may be a view of it

  const Buffer& buffer = buffers_[b.index];
  const bool damaged = (b.flags & V4L2_BUF_FLAG_ERROR) != 0;
  std::string err;
  Status s = Status::EmptyFrame;
  if (damaged) {
    out.image.release();
    err = "the driver flagged frame " + std::to_string(b.sequence) + " as damaged";
  } else {
    const std::size_t used = std::min<std::size_t>(b.bytesused, buffer.length);
    s = bufferToGrey(layout_, static_cast<const std::uint8_t*>(buffer.start), used, scratch_, out.image, err);
  }

  std::lock_guard lock(mutex_);
  if (have_sequence_ && b.sequence > last_sequence_ + 1) stats_.dropped += b.sequence - last_sequence_ - 1;
  have_sequence_ = true;
  last_sequence_ = b.sequence;
  if (!ok(s)) {
    ++stats_.corrupt;
    error_ = request_.device + ": " + err;
    return s;
  }
  ++stats_.frames;
  noteTimestamp(t);
  return Status::Ok;
}

std::string CameraSource::lastError() const {
  std::lock_guard lock(mutex_);
  return error_;
}

std::string CameraSource::describe() const {
  std::lock_guard lock(mutex_);
  std::string d = "camera " + request_.device;
  if (!streaming_) return failure_ == Status::Ok ? d : d + " (" + std::string(statusName(failure_)) + ")";
  d += " " + sizeText(format_.width, format_.height) + " " + fourccText(format_.fourcc);
  if (format_.nominal_rate_hz > 0.0) d += " " + rateText(format_.nominal_rate_hz);
  if (stats_.achieved_rate_hz > 0.0) d += " (" + rateText(stats_.achieved_rate_hz) + " achieved)";
  return d;
}

CameraFormat CameraSource::format() const {
  std::lock_guard lock(mutex_);
  return format_;
}

CaptureStats CameraSource::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

Status CameraSource::controls(std::vector<CameraControl>& out) {
  std::lock_guard lock(mutex_);
  int fd = fd_;
  std::string err;
  if (fd < 0) {  // not streaming: ask the device directly
    if (const Status s = v4l2::openDevice(io_, request_.device, fd, err); !ok(s)) {
      error_ = err;
      return s;
    }
  }
  v4l2::readControls(io_, fd, out);
  if (fd != fd_) io_.close(fd);
  return Status::Ok;
}

Status CameraSource::setControl(std::uint32_t id, std::int64_t value) {
  std::lock_guard lock(mutex_);
  int fd = fd_;
  std::string err;
  if (fd < 0) {
    if (const Status s = v4l2::openDevice(io_, request_.device, fd, err); !ok(s)) {
      error_ = err;
      return s;
    }
  }
  std::vector<CameraControl> all;
  v4l2::readControls(io_, fd, all);
  const auto it = std::find_if(all.begin(), all.end(), [&](const CameraControl& c) { return c.id == id; });
  Status s;
  if (it == all.end()) {
    err = "no control with id " + std::to_string(id);
    s = Status::InvalidSettings;
  } else {
    s = v4l2::writeControl(io_, fd, *it, value, err);
  }
  if (fd != fd_) io_.close(fd);
  if (!ok(s)) error_ = request_.device + ": " + err;
  return s;
}

}  // namespace imagepro
