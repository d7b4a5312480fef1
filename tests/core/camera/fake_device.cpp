#include "fake_device.h"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/camera/pixel_format.h"

namespace imagepro::test {

namespace {

constexpr std::int64_t kBufferOffsetStep = 0x100000;

void copyName(__u8* dst, std::size_t n, const std::string& text) {
  std::memset(dst, 0, n);
  std::memcpy(dst, text.data(), std::min(n - 1, text.size()));
}

std::size_t imageBytes(std::uint32_t fourcc, std::size_t bpl, int width, int height) {
  const auto h = static_cast<std::size_t>(height);
  const auto half = static_cast<std::size_t>((height + 1) / 2);
  const auto f = pixelFormatFromFourcc(fourcc);
  if (!f) return bpl * h;
  switch (*f) {
    case PixelFormat::Nv12:
    case PixelFormat::Nv21: return bpl * h + bpl * half;
    case PixelFormat::Yuv420:
    case PixelFormat::Yvu420: return bpl * h + 2 * (bpl / 2) * half;
    case PixelFormat::Mjpeg: return static_cast<std::size_t>(width) * h * 2 + 4096;
    default: return bpl * h;
  }
}

}  // namespace

FakeDevice::FakeDevice() {
  current.width = 640;
  current.height = 480;
  current.pixelformat = makeFourcc('Y', 'U', 'Y', 'V');
  current.bytesperline = 1280;
  current.sizeimage = 1280 * 480;
}

void FakeDevice::vanish() {
  std::lock_guard lock(mutex_);
  present_ = false;
  ++generation_;
  streaming_ = false;
  queued_.clear();
}

void FakeDevice::reappear() {
  std::lock_guard lock(mutex_);
  present_ = true;
  // A new device: its buffers are those of the new descriptors.
  if (std::none_of(mapped_.begin(), mapped_.end(), [](bool m) { return m; })) {
    buffers_.clear();
    mapped_.clear();
  }
}

int FakeDevice::openDescriptors() const {
  std::lock_guard lock(mutex_);
  return static_cast<int>(fds_.size());
}

int FakeDevice::mappedBuffers() const {
  std::lock_guard lock(mutex_);
  return static_cast<int>(std::count(mapped_.begin(), mapped_.end(), true));
}

bool FakeDevice::streaming() const {
  std::lock_guard lock(mutex_);
  return streaming_;
}

int FakeDevice::fail(int err) {
  errno = err;
  return -1;
}

int FakeDevice::open(const char* p) {
  std::lock_guard lock(mutex_);
  if (p != path || !present_) return fail(ENOENT);
  if (open_errno != 0) return fail(open_errno);
  ++opens;
  const int fd = next_fd_++;
  fds_[fd] = generation_;
  return fd;
}

int FakeDevice::close(int fd) {
  std::lock_guard lock(mutex_);
  if (fds_.erase(fd) == 0) return fail(EBADF);
  ++closes;
  if (fds_.empty()) {  // the last user gone: the driver frees its buffers
    streaming_ = false;
    queued_.clear();
    if (std::none_of(mapped_.begin(), mapped_.end(), [](bool m) { return m; })) {
      buffers_.clear();
      mapped_.clear();
    }
  }
  return 0;
}

void* FakeDevice::map(int fd, std::size_t length, std::int64_t offset) {
  std::lock_guard lock(mutex_);
  const auto it = fds_.find(fd);
  if (it == fds_.end()) return errno = EBADF, nullptr;
  if (it->second != generation_) return errno = ENODEV, nullptr;
  const auto index = static_cast<std::size_t>(offset / kBufferOffsetStep);
  if (offset % kBufferOffsetStep != 0 || index >= buffers_.size() || length != buffers_[index].size() ||
      mapped_[index])
    return errno = EINVAL, nullptr;
  mapped_[index] = true;
  return buffers_[index].data();
}

int FakeDevice::unmap(void* address, std::size_t length) {
  std::lock_guard lock(mutex_);
  for (std::size_t i = 0; i < buffers_.size(); ++i) {
    if (buffers_[i].data() == address && mapped_[i] && buffers_[i].size() == length) {
      mapped_[i] = false;
      return 0;
    }
  }
  return fail(EINVAL);
}

int FakeDevice::waitReadable(int fd, int timeout_ms) {
  std::lock_guard lock(mutex_);
  wait_timeouts.push_back(timeout_ms);
  const auto it = fds_.find(fd);
  if (it == fds_.end()) return fail(EBADF);
  if (it->second != generation_) return 1;  // error pending: the next ioctl says which
  return streaming_ && !stalled && !queued_.empty() ? 1 : 0;
}

int FakeDevice::ioctl(int fd, unsigned long request, void* arg) {
  std::lock_guard lock(mutex_);
  const auto it = fds_.find(fd);
  if (it == fds_.end()) return fail(EBADF);
  if (it->second != generation_) return fail(ENODEV);
  return handle(request, arg);
}

const FakeFormat* FakeDevice::findFormat(std::uint32_t fourcc) const {
  for (const FakeFormat& f : formats)
    if (f.fourcc == fourcc) return &f;
  return nullptr;
}

const FakeSize* FakeDevice::findSize(const FakeFormat& f, int width, int height) const {
  for (const FakeSize& s : f.sizes)
    if (s.width == width && s.height == height) return &s;
  return nullptr;
}

std::size_t FakeDevice::fill(std::uint8_t* data, std::size_t length, std::uint32_t sequence) const {
  const int w = static_cast<int>(current.width);
  const int h = static_cast<int>(current.height);
  const std::size_t bpl = current.bytesperline;
  std::memset(data, 0xEE, length);  // padding and anything not written below
  const auto format = pixelFormatFromFourcc(current.pixelformat);
  if (!format) return current.sizeimage;
  if (*format == PixelFormat::Mjpeg) {
    cv::Mat grey(h, w, CV_8UC1);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) grey.at<std::uint8_t>(y, x) = referenceLuma(x, y, sequence);
    std::vector<std::uint8_t> jpeg;
    cv::imencode(".jpg", grey, jpeg, {cv::IMWRITE_JPEG_QUALITY, 100});
    const std::size_t n = std::min(jpeg.size(), length);
    std::memcpy(data, jpeg.data(), n);
    return n;
  }
  for (int y = 0; y < h; ++y) {
    std::uint8_t* line = data + static_cast<std::size_t>(y) * bpl;
    for (int x = 0; x < w; ++x) {
      const std::uint8_t v = referenceLuma(x, y, sequence);
      switch (*format) {
        case PixelFormat::Yuyv:
          line[2 * x] = v;
          line[2 * x + 1] = static_cast<std::uint8_t>(x % 2 ? 0x30 : 0xC0);
          break;
        case PixelFormat::Uyvy:
          line[2 * x + 1] = v;
          line[2 * x] = static_cast<std::uint8_t>(x % 2 ? 0x30 : 0xC0);
          break;
        case PixelFormat::Rgb24:
        case PixelFormat::Bgr24:
          line[3 * x] = line[3 * x + 1] = line[3 * x + 2] = v;
          break;
        default: line[x] = v; break;
      }
    }
  }
  // Chroma planes of the 4:2:0 formats: anything but the luma.
  const std::size_t luma_bytes = bpl * static_cast<std::size_t>(h);
  if (*format == PixelFormat::Nv12 || *format == PixelFormat::Nv21 || *format == PixelFormat::Yuv420 ||
      *format == PixelFormat::Yvu420)
    std::memset(data + luma_bytes, 0x80, std::min<std::size_t>(length, current.sizeimage) - luma_bytes);
  return current.sizeimage;
}

int FakeDevice::handle(unsigned long request, void* arg) {
  switch (request) {
    case VIDIOC_QUERYCAP: {
      auto& cap = *static_cast<v4l2_capability*>(arg);
      cap = v4l2_capability{};
      copyName(cap.driver, sizeof cap.driver, "fakecam");
      copyName(cap.card, sizeof cap.card, card);
      copyName(cap.bus_info, sizeof cap.bus_info, "platform:fake");
      cap.device_caps = device_caps;
      cap.capabilities = device_caps | V4L2_CAP_DEVICE_CAPS;
      return 0;
    }
    case VIDIOC_ENUM_FMT: {
      auto& d = *static_cast<v4l2_fmtdesc*>(arg);
      if (d.type != V4L2_BUF_TYPE_VIDEO_CAPTURE || d.index >= formats.size()) return fail(EINVAL);
      const FakeFormat& f = formats[d.index];
      d.pixelformat = f.fourcc;
      d.flags = f.emulated ? V4L2_FMT_FLAG_EMULATED : 0;
      copyName(d.description, sizeof d.description, f.description);
      return 0;
    }
    case VIDIOC_ENUM_FRAMESIZES: {
      auto& e = *static_cast<v4l2_frmsizeenum*>(arg);
      const FakeFormat* f = findFormat(e.pixel_format);
      if (f == nullptr || e.index >= f->sizes.size()) return fail(EINVAL);
      e.type = V4L2_FRMSIZE_TYPE_DISCRETE;
      e.discrete.width = static_cast<std::uint32_t>(f->sizes[e.index].width);
      e.discrete.height = static_cast<std::uint32_t>(f->sizes[e.index].height);
      return 0;
    }
    case VIDIOC_ENUM_FRAMEINTERVALS: {
      auto& e = *static_cast<v4l2_frmivalenum*>(arg);
      const FakeFormat* f = findFormat(e.pixel_format);
      const FakeSize* s = f ? findSize(*f, static_cast<int>(e.width), static_cast<int>(e.height)) : nullptr;
      if (s == nullptr || e.index >= s->intervals.size()) return fail(EINVAL);
      e.type = V4L2_FRMIVAL_TYPE_DISCRETE;
      e.discrete = {s->intervals[e.index].numerator, s->intervals[e.index].denominator};
      return 0;
    }
    case VIDIOC_G_FMT: {
      auto& fmt = *static_cast<v4l2_format*>(arg);
      if (fmt.type != V4L2_BUF_TYPE_VIDEO_CAPTURE) return fail(EINVAL);
      fmt.fmt.pix = current;
      return 0;
    }
    case VIDIOC_S_FMT: {
      auto& fmt = *static_cast<v4l2_format*>(arg);
      if (fmt.type != V4L2_BUF_TYPE_VIDEO_CAPTURE) return fail(EINVAL);
      if (s_fmt_errno != 0) return fail(s_fmt_errno);
      if (!buffers_.empty()) return fail(EBUSY);
      v4l2_pix_format& pix = fmt.fmt.pix;
      // Like a driver: an unknown format becomes the first one, the size the nearest listed.
      const FakeFormat* f = findFormat(pix.pixelformat);
      if (f == nullptr && !formats.empty()) f = &formats.front();
      if (f != nullptr) {
        pix.pixelformat = f->fourcc;
        const FakeSize* best = nullptr;
        for (const FakeSize& s : f->sizes) {
          const auto d = [&](const FakeSize& c) {
            return std::abs(c.width - static_cast<int>(pix.width)) + std::abs(c.height - static_cast<int>(pix.height));
          };
          if (best == nullptr || d(s) < d(*best)) best = &s;
        }
        if (best != nullptr) {
          pix.width = static_cast<std::uint32_t>(best->width);
          pix.height = static_cast<std::uint32_t>(best->height);
        }
      }
      const auto known = pixelFormatFromFourcc(pix.pixelformat);
      const std::size_t min_line = known ? minimumBytesPerLine(*known, static_cast<int>(pix.width)) : pix.width;
      pix.bytesperline = static_cast<std::uint32_t>(min_line == 0 ? 0 : min_line + line_padding);
      pix.sizeimage = static_cast<std::uint32_t>(
          imageBytes(pix.pixelformat, pix.bytesperline, static_cast<int>(pix.width), static_cast<int>(pix.height)));
      pix.field = V4L2_FIELD_NONE;
      if (adjust_format) adjust_format(pix);
      current = pix;
      return 0;
    }
    case VIDIOC_G_PARM:
    case VIDIOC_S_PARM: {
      auto& parm = *static_cast<v4l2_streamparm*>(arg);
      if (parm.type != V4L2_BUF_TYPE_VIDEO_CAPTURE) return fail(EINVAL);
      if (request == VIDIOC_S_PARM) {
        if (!timeperframe) return fail(ENOTTY);
        // The listed interval nearest to the one asked for.
        const FrameInterval asked{parm.parm.capture.timeperframe.numerator,
                                  parm.parm.capture.timeperframe.denominator};
        const FakeFormat* f = findFormat(current.pixelformat);
        const FakeSize* s = f ? findSize(*f, static_cast<int>(current.width), static_cast<int>(current.height)) : nullptr;
        if (s != nullptr && !s->intervals.empty() && asked.numerator != 0) {
          FrameInterval best = s->intervals.front();
          for (const FrameInterval& i : s->intervals)
            if (std::abs(i.rateHz() - asked.rateHz()) < std::abs(best.rateHz() - asked.rateHz())) best = i;
          interval = best;
        }
      }
      parm.parm.capture = v4l2_captureparm{};
      parm.parm.capture.capability = timeperframe ? V4L2_CAP_TIMEPERFRAME : 0;
      parm.parm.capture.timeperframe = {interval.numerator, interval.denominator};
      return 0;
    }
    case VIDIOC_REQBUFS: {
      auto& req = *static_cast<v4l2_requestbuffers*>(arg);
      if (req.type != V4L2_BUF_TYPE_VIDEO_CAPTURE || req.memory != V4L2_MEMORY_MMAP) return fail(EINVAL);
      if (streaming_) return fail(EBUSY);
      if (std::any_of(mapped_.begin(), mapped_.end(), [](bool m) { return m; })) return fail(EBUSY);
      req.count = std::min(req.count, max_buffers);
      buffers_.assign(req.count, std::vector<std::uint8_t>(current.sizeimage));
      mapped_.assign(req.count, false);
      queued_.clear();
      return 0;
    }
    case VIDIOC_QUERYBUF: {
      auto& b = *static_cast<v4l2_buffer*>(arg);
      if (b.index >= buffers_.size()) return fail(EINVAL);
      b.length = static_cast<std::uint32_t>(buffers_[b.index].size());
      b.m.offset = static_cast<std::uint32_t>(b.index * kBufferOffsetStep);
      return 0;
    }
    case VIDIOC_QBUF: {
      auto& b = *static_cast<v4l2_buffer*>(arg);
      if (b.index >= buffers_.size() || std::find(queued_.begin(), queued_.end(), b.index) != queued_.end())
        return fail(EINVAL);
      queued_.push_back(b.index);
      return 0;
    }
    case VIDIOC_DQBUF: {
      auto& b = *static_cast<v4l2_buffer*>(arg);
      if (!streaming_) return fail(EINVAL);
      if (vanish_after >= 0 && delivered >= static_cast<std::uint32_t>(vanish_after)) {
        const int err = vanish_errno;
        vanish();
        return fail(err);
      }
      if (stalled || queued_.empty()) return fail(EAGAIN);
      while (lost_sequences.count(next_sequence_)) ++next_sequence_;
      const std::uint32_t index = queued_.front();
      queued_.pop_front();
      const std::uint32_t sequence = next_sequence_++;
      std::vector<std::uint8_t>& data = buffers_[index];
      b.index = index;
      b.bytesused = static_cast<std::uint32_t>(fill(data.data(), data.size(), sequence));
      b.sequence = sequence;
      b.flags = V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC | (damaged_sequences.count(sequence) ? V4L2_BUF_FLAG_ERROR : 0);
      const double t = first_timestamp_s + sequence * (static_cast<double>(interval.numerator) / interval.denominator);
      b.timestamp.tv_sec = static_cast<time_t>(t);
      b.timestamp.tv_usec = static_cast<suseconds_t>(std::llround((t - static_cast<double>(b.timestamp.tv_sec)) * 1e6));
      b.length = static_cast<std::uint32_t>(data.size());
      ++delivered;
      return 0;
    }
    case VIDIOC_STREAMON: {
      if (streamon_errno != 0) return fail(streamon_errno);
      if (buffers_.empty()) return fail(EINVAL);
      streaming_ = true;
      return 0;
    }
    case VIDIOC_STREAMOFF: {
      streaming_ = false;
      queued_.clear();
      return 0;
    }
    case VIDIOC_QUERYCTRL: {
      auto& q = *static_cast<v4l2_queryctrl*>(arg);
      const bool next = (q.id & V4L2_CTRL_FLAG_NEXT_CTRL) != 0;
      const std::uint32_t id = q.id & ~V4L2_CTRL_FLAG_NEXT_CTRL;
      const FakeControl* found = nullptr;
      for (const FakeControl& c : controls) {
        if (next ? c.query.id > id && (found == nullptr || c.query.id < found->query.id) : c.query.id == id)
          found = &c;
      }
      if (found == nullptr) return fail(EINVAL);
      q = found->query;
      return 0;
    }
    case VIDIOC_QUERYMENU: {
      auto& m = *static_cast<v4l2_querymenu*>(arg);
      for (const FakeControl& c : controls) {
        if (c.query.id != m.id) continue;
        const auto item = c.menu.find(m.index);
        if (item == c.menu.end()) return fail(EINVAL);
        copyName(m.name, sizeof m.name, item->second);
        return 0;
      }
      return fail(EINVAL);
    }
    case VIDIOC_G_CTRL:
    case VIDIOC_S_CTRL: {
      auto& v = *static_cast<v4l2_control*>(arg);
      for (FakeControl& c : controls) {
        if (c.query.id != v.id) continue;
        if (request == VIDIOC_G_CTRL) {
          v.value = static_cast<std::int32_t>(c.value);
          return 0;
        }
        if (c.query.flags & (V4L2_CTRL_FLAG_READ_ONLY | V4L2_CTRL_FLAG_INACTIVE)) return fail(EACCES);
        if (v.value < c.query.minimum || v.value > c.query.maximum) return fail(ERANGE);
        c.value = v.value;
        if (after_set) after_set(v.id, v.value);
        return 0;
      }
      return fail(EINVAL);
    }
    case VIDIOC_ENUMINPUT: {
      auto& in = *static_cast<v4l2_input*>(arg);
      if (in.index >= inputs.size()) return fail(EINVAL);
      const FakeInput& f = inputs[in.index];
      const std::uint32_t index = in.index;
      in = v4l2_input{};
      in.index = index;
      copyName(in.name, sizeof in.name, f.name);
      in.type = f.type;
      in.std = f.standards;
      return 0;
    }
    case VIDIOC_G_INPUT:
    case VIDIOC_S_INPUT: {
      if (inputs.empty()) return fail(ENOTTY);
      auto& index = *static_cast<int*>(arg);
      if (request == VIDIOC_G_INPUT) {
        index = static_cast<int>(input);
        return 0;
      }
      if (index < 0 || static_cast<std::size_t>(index) >= inputs.size()) return fail(EINVAL);
      if (streaming_) return fail(EBUSY);
      input = static_cast<std::uint32_t>(index);
      selections.push_back("input " + std::to_string(index));
      return 0;
    }
    case VIDIOC_ENUMSTD: {
      auto& st = *static_cast<v4l2_standard*>(arg);
      const v4l2_std_id takes = inputs.empty() ? 0 : inputs[input].standards;
      std::uint32_t n = 0;
      for (const FakeStandard& f : standards) {
        if ((f.id & takes) == 0) continue;
        if (n++ != st.index) continue;
        const std::uint32_t index = st.index;
        st = v4l2_standard{};
        st.index = index;
        st.id = f.id;
        copyName(st.name, sizeof st.name, f.name);
        st.frameperiod = f.frame_period;
        return 0;
      }
      return fail(EINVAL);
    }
    case VIDIOC_G_STD:
    case VIDIOC_S_STD: {
      auto& id = *static_cast<v4l2_std_id*>(arg);
      const v4l2_std_id takes = inputs.empty() ? 0 : inputs[input].standards;
      if (takes == 0) return fail(ENODATA);
      if (request == VIDIOC_G_STD) {
        id = standard;
        return 0;
      }
      if ((id & takes) == 0) return fail(EINVAL);
      if (streaming_) return fail(EBUSY);
      // Like a driver: the first listed standard of those asked for.
      for (const FakeStandard& f : standards)
        if ((f.id & id & takes) != 0) {
          standard = f.id;
          break;
        }
      char text[32];
      std::snprintf(text, sizeof text, "standard %#llx", static_cast<unsigned long long>(standard));
      selections.emplace_back(text);
      return 0;
    }
    default: return fail(ENOTTY);
  }
}

void addStandardFormats(FakeDevice& device) {
  device.formats = {
      {makeFourcc('Y', 'U', 'Y', 'V'),
       "YUYV 4:2:2",
       {{640, 480, {{1, 30}, {1, 25}, {1, 15}}}, {320, 240, {{1, 30}}}},
       false},
      {makeFourcc('M', 'J', 'P', 'G'), "Motion-JPEG", {{1280, 720, {{1, 30}}}, {640, 480, {{1, 30}}}}, false},
  };
}

void addStandardControls(FakeDevice& device) {
  auto control = [](std::uint32_t id, std::uint32_t type, const char* name, std::int32_t min, std::int32_t max,
                    std::int32_t step, std::int32_t def, std::uint32_t flags) {
    FakeControl c;
    c.query.id = id;
    c.query.type = type;
    copyName(c.query.name, sizeof c.query.name, name);
    c.query.minimum = min;
    c.query.maximum = max;
    c.query.step = step;
    c.query.default_value = def;
    c.query.flags = flags;
    c.value = def;
    return c;
  };
  device.controls.clear();
  device.controls.push_back(control(V4L2_CID_USER_CLASS, V4L2_CTRL_TYPE_CTRL_CLASS, "User Controls", 0, 0, 0, 0,
                                    V4L2_CTRL_FLAG_READ_ONLY | V4L2_CTRL_FLAG_WRITE_ONLY));
  device.controls.push_back(control(V4L2_CID_BRIGHTNESS, V4L2_CTRL_TYPE_INTEGER, "Brightness", -64, 64, 1, 0, 0));
  device.controls.push_back(control(V4L2_CID_CONTRAST, V4L2_CTRL_TYPE_INTEGER, "Contrast", 0, 100, 1, 50,
                                    V4L2_CTRL_FLAG_DISABLED));
  device.controls.push_back(control(V4L2_CID_GAIN, V4L2_CTRL_TYPE_INTEGER, "Gain", 0, 240, 16, 32, 0));
  FakeControl exposure_mode =
      control(V4L2_CID_EXPOSURE_AUTO, V4L2_CTRL_TYPE_MENU, "Auto Exposure", 0, 3, 1, 3, 0);
  exposure_mode.menu = {{1, "Manual Mode"}, {3, "Aperture Priority Mode"}};
  device.controls.push_back(exposure_mode);
  device.controls.push_back(control(V4L2_CID_EXPOSURE_ABSOLUTE, V4L2_CTRL_TYPE_INTEGER, "Exposure Time, Absolute", 3,
                                    2047, 1, 250, V4L2_CTRL_FLAG_INACTIVE));
  device.controls.push_back(control(V4L2_CID_FOCUS_AUTO, V4L2_CTRL_TYPE_BOOLEAN, "Focus, Automatic Continuous", 0,
                                    1, 1, 1, 0));
}

}  // namespace imagepro::test

namespace imagepro::test {

void addCaptureCard(FakeDevice& device) {
  device.card = "PXC200 frame grabber";
  device.formats = {{makeFourcc('G', 'R', 'E', 'Y'), "8-bit Greyscale", {{768, 576, {{1, 25}}}, {640, 480, {{1001, 30000}}}}, false}};
  device.inputs = {{"Composite0", V4L2_INPUT_TYPE_CAMERA, V4L2_STD_PAL | V4L2_STD_NTSC | V4L2_STD_SECAM},
                   {"Composite1", V4L2_INPUT_TYPE_CAMERA, V4L2_STD_PAL | V4L2_STD_NTSC},
                   {"S-Video", V4L2_INPUT_TYPE_CAMERA, V4L2_STD_NTSC}};
  device.standards = {{V4L2_STD_PAL_BG, "PAL-BG", {1, 25}},
                      {V4L2_STD_NTSC_M, "NTSC-M", {1001, 30000}},
                      {V4L2_STD_SECAM_L, "SECAM-L", {1, 25}}};
  device.input = 0;
  device.standard = V4L2_STD_PAL_BG;
}

}  // namespace imagepro::test
