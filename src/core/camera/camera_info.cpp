#include "core/camera/camera_info.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <system_error>
#include <tuple>

#include "core/camera/v4l2_access.h"
#include "core/settings/enum_names.h"
#include "core/source/image_file.h"

namespace imagepro {

namespace v4l2 {

namespace {

// Fixed-size, possibly unterminated driver strings.
template <std::size_t N>
std::string driverText(const __u8 (&text)[N]) {
  const auto* chars = reinterpret_cast<const char*>(text);
  return std::string(chars, strnlen(chars, N));
}

FrameInterval interval(const v4l2_fract& f) { return {f.numerator, f.denominator}; }

FrameRates readRates(DeviceIo& io, int fd, std::uint32_t fourcc, int width, int height) {
  FrameRates rates;
  for (std::uint32_t i = 0; i < 256; ++i) {
    v4l2_frmivalenum e{};
    e.index = i;
    e.pixel_format = fourcc;
    e.width = static_cast<std::uint32_t>(width);
    e.height = static_cast<std::uint32_t>(height);
    if (xioctl(io, fd, VIDIOC_ENUM_FRAMEINTERVALS, &e) < 0) break;
    if (e.type == V4L2_FRMIVAL_TYPE_DISCRETE) {
      rates.discrete.push_back(interval(e.discrete));
    } else {
      rates.is_range = true;
      rates.shortest = interval(e.stepwise.min);
      rates.longest = interval(e.stepwise.max);
      break;
    }
  }
  return rates;
}

std::vector<FrameSize> readSizes(DeviceIo& io, int fd, std::uint32_t fourcc) {
  std::vector<FrameSize> sizes;
  for (std::uint32_t i = 0; i < 1024; ++i) {
    v4l2_frmsizeenum e{};
    e.index = i;
    e.pixel_format = fourcc;
    if (xioctl(io, fd, VIDIOC_ENUM_FRAMESIZES, &e) < 0) break;
    FrameSize s;
    if (e.type == V4L2_FRMSIZE_TYPE_DISCRETE) {
      s.width = static_cast<int>(e.discrete.width);
      s.height = static_cast<int>(e.discrete.height);
      s.min_width = s.width;
      s.min_height = s.height;
    } else {
      s.is_range = true;
      s.width = static_cast<int>(e.stepwise.max_width);
      s.height = static_cast<int>(e.stepwise.max_height);
      s.min_width = static_cast<int>(e.stepwise.min_width);
      s.min_height = static_cast<int>(e.stepwise.min_height);
      s.step_width = std::max(1, static_cast<int>(e.stepwise.step_width));
      s.step_height = std::max(1, static_cast<int>(e.stepwise.step_height));
    }
    s.rates = readRates(io, fd, fourcc, s.width, s.height);
    sizes.push_back(std::move(s));
    if (e.type != V4L2_FRMSIZE_TYPE_DISCRETE) break;
  }
  return sizes;
}

ControlType controlType(std::uint32_t type) {
  switch (type) {
    case V4L2_CTRL_TYPE_INTEGER: return ControlType::Integer;
    case V4L2_CTRL_TYPE_BOOLEAN: return ControlType::Boolean;
    case V4L2_CTRL_TYPE_MENU: return ControlType::Menu;
    case V4L2_CTRL_TYPE_INTEGER_MENU: return ControlType::IntegerMenu;
    case V4L2_CTRL_TYPE_BUTTON: return ControlType::Button;
    case V4L2_CTRL_TYPE_INTEGER64: return ControlType::Integer64;
    default: return ControlType::Other;
  }
}

// One control's value through the extended interface (needed for 64-bit values).
int readExtended(DeviceIo& io, int fd, std::uint32_t id, std::int64_t& value) {
  v4l2_ext_control c{};
  c.id = id;
  v4l2_ext_controls cs{};
  cs.which = V4L2_CTRL_WHICH_CUR_VAL;
  cs.count = 1;
  cs.controls = &c;
  if (xioctl(io, fd, VIDIOC_G_EXT_CTRLS, &cs) < 0) return -1;
  value = c.value64;
  return 0;
}

}  // namespace

int xioctl(DeviceIo& io, int fd, unsigned long request, void* arg) {
  int r;
  do {
    r = io.ioctl(fd, request, arg);
  } while (r < 0 && errno == EINTR);
  return r;
}

std::string errnoText(int err) { return std::system_category().message(err); }

Status openFailure(int err) {
  switch (err) {
    case EACCES:
    case EPERM: return Status::CameraPermissionDenied;
    case EBUSY: return Status::CameraBusy;
    default: return Status::CameraNotFound;  // ENOENT, ENXIO, ENODEV, ENOTDIR ...
  }
}

Status openDevice(DeviceIo& io, const std::string& path, int& fd, std::string& error) {
  fd = io.open(path.c_str());
  if (fd >= 0) return Status::Ok;
  const int err = errno;
  const Status s = openFailure(err);
  error = path + ": " + std::string(statusMessage(s)) + " (" + errnoText(err) + ")";
  if (s == Status::CameraPermissionDenied) error += "; is the user in the 'video' group?";
  return s;
}

Status readCapabilities(DeviceIo& io, int fd, DeviceInfo& info, std::string& error) {
  v4l2_capability cap{};
  if (xioctl(io, fd, VIDIOC_QUERYCAP, &cap) < 0) {
    const int err = errno;
    error = info.path + ": not a V4L2 device (" + errnoText(err) + ")";
    return Status::CameraNotFound;
  }
  info.card = driverText(cap.card);
  info.driver = driverText(cap.driver);
  info.bus = driverText(cap.bus_info);
  const std::uint32_t caps = (cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities;
  info.video_capture = (caps & V4L2_CAP_VIDEO_CAPTURE) != 0;
  info.streaming = (caps & V4L2_CAP_STREAMING) != 0;
  return Status::Ok;
}

void readFormats(DeviceIo& io, int fd, std::vector<FormatInfo>& formats) {
  formats.clear();
  for (std::uint32_t i = 0; i < 256; ++i) {
    v4l2_fmtdesc d{};
    d.index = i;
    d.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (xioctl(io, fd, VIDIOC_ENUM_FMT, &d) < 0) break;
    FormatInfo f;
    f.fourcc = d.pixelformat;
    f.description = driverText(d.description);
    f.format = pixelFormatFromFourcc(d.pixelformat);
    f.emulated = (d.flags & V4L2_FMT_FLAG_EMULATED) != 0;
    f.sizes = readSizes(io, fd, d.pixelformat);
    formats.push_back(std::move(f));
  }
}

void readControls(DeviceIo& io, int fd, std::vector<CameraControl>& controls) {
  controls.clear();
  std::uint32_t id = 0;
  for (int guard = 0; guard < 4096; ++guard) {
    v4l2_queryctrl q{};
    q.id = id | V4L2_CTRL_FLAG_NEXT_CTRL;
    if (xioctl(io, fd, VIDIOC_QUERYCTRL, &q) < 0 || (q.id & ~V4L2_CTRL_FLAG_NEXT_CTRL) <= id) break;
    id = q.id;
    if ((q.flags & V4L2_CTRL_FLAG_DISABLED) || q.type == V4L2_CTRL_TYPE_CTRL_CLASS) continue;
    CameraControl c;
    c.id = q.id;
    c.name = driverText(q.name);
    c.key = controlKey(c.name);
    c.type = controlType(q.type);
    c.minimum = q.minimum;
    c.maximum = q.maximum;
    c.step = q.step;
    c.default_value = q.default_value;
    c.read_only = (q.flags & V4L2_CTRL_FLAG_READ_ONLY) != 0;
    c.inactive = (q.flags & V4L2_CTRL_FLAG_INACTIVE) != 0;
    const bool readable = !(q.flags & V4L2_CTRL_FLAG_WRITE_ONLY) && c.type != ControlType::Button &&
                          c.type != ControlType::Other;
    if (readable && c.type == ControlType::Integer64) {
      readExtended(io, fd, c.id, c.value);
    } else if (readable) {
      v4l2_control v{};
      v.id = c.id;
      if (xioctl(io, fd, VIDIOC_G_CTRL, &v) == 0) c.value = v.value;
    }
    if (c.type == ControlType::Menu || c.type == ControlType::IntegerMenu) {
      for (std::int64_t i = std::max<std::int64_t>(0, c.minimum); i <= c.maximum && i < 256; ++i) {
        v4l2_querymenu m{};
        m.id = c.id;
        m.index = static_cast<std::uint32_t>(i);
        if (xioctl(io, fd, VIDIOC_QUERYMENU, &m) < 0) continue;  // gaps are allowed
        ControlMenuItem item;
        item.value = i;
        if (c.type == ControlType::Menu) {
          item.name = driverText(m.name);
        } else {
          std::int64_t menu_value;
          std::memcpy(&menu_value, reinterpret_cast<const char*>(&m) + offsetof(v4l2_querymenu, value),
                      sizeof menu_value);  // packed struct: no reference to the member
          item.name = std::to_string(menu_value);
        }
        c.menu.push_back(std::move(item));
      }
    }
    controls.push_back(std::move(c));
  }
}

Status writeControl(DeviceIo& io, int fd, const CameraControl& control, std::int64_t value, std::string& error) {
  if (const std::string problem = controlValueProblem(control, value); !problem.empty()) {
    error = control.key + ": " + problem;
    return Status::InvalidSettings;
  }
  int r;
  if (control.type == ControlType::Integer64) {
    v4l2_ext_control c{};
    c.id = control.id;
    c.value64 = value;
    v4l2_ext_controls cs{};
    cs.which = V4L2_CTRL_WHICH_CUR_VAL;
    cs.count = 1;
    cs.controls = &c;
    r = xioctl(io, fd, VIDIOC_S_EXT_CTRLS, &cs);
  } else {
    v4l2_control c{};
    c.id = control.id;
    c.value = static_cast<std::int32_t>(value);
    r = xioctl(io, fd, VIDIOC_S_CTRL, &c);
  }
  if (r == 0) return Status::Ok;
  const int err = errno;
  if (err == ENODEV || err == EIO) {
    error = control.key + ": " + std::string(statusMessage(Status::CameraDisconnected));
    return Status::CameraDisconnected;
  }
  error = control.key + " = " + std::to_string(value) + " refused by the driver (" + errnoText(err) + ")";
  if (err == EACCES || err == EBUSY) error += "; is its automatic mode on?";
  return Status::InvalidSettings;
}

void readInputsAndStandards(DeviceIo& io, int fd, DeviceInfo& info) {
  for (std::uint32_t i = 0; i < 64; ++i) {
    v4l2_input in{};
    in.index = i;
    if (xioctl(io, fd, VIDIOC_ENUMINPUT, &in) < 0) break;
    info.inputs.push_back({in.index, driverText(in.name), in.type == V4L2_INPUT_TYPE_TUNER, in.std});
  }
  int current = -1;
  if (!info.inputs.empty() && xioctl(io, fd, VIDIOC_G_INPUT, &current) == 0) info.current_input = current;
  for (std::uint32_t i = 0; i < 64; ++i) {
    v4l2_standard st{};
    st.index = i;
    if (xioctl(io, fd, VIDIOC_ENUMSTD, &st) < 0) break;
    const double rate = st.frameperiod.numerator == 0
                            ? 0.0
                            : static_cast<double>(st.frameperiod.denominator) / st.frameperiod.numerator;
    info.standards.push_back({st.id, driverText(st.name), rate});
  }
  v4l2_std_id now = 0;
  if (!info.standards.empty() && xioctl(io, fd, VIDIOC_G_STD, &now) == 0) info.current_standard = now;
}

}  // namespace v4l2

std::uint64_t tvStandardMask(TvStandard standard) {
  switch (standard) {
    case TvStandard::Keep: return 0;
    case TvStandard::Pal: return V4L2_STD_PAL;
    case TvStandard::Ntsc: return V4L2_STD_NTSC;
    case TvStandard::Secam: return V4L2_STD_SECAM;
  }
  return 0;
}

std::vector<TvStandard> tvStandardsOffered(const DeviceInfo& info, int input) {
  const int chosen = input >= 0 ? input : info.current_input;
  std::uint64_t takes = 0;
  if (chosen >= 0 && static_cast<std::size_t>(chosen) < info.inputs.size())
    takes = info.inputs[static_cast<std::size_t>(chosen)].standards;
  else if (info.inputs.empty())
    for (const VideoStandard& s : info.standards) takes |= s.id;
  std::vector<TvStandard> offered;
  for (const TvStandard t : {TvStandard::Pal, TvStandard::Ntsc, TvStandard::Secam})
    if ((takes & tvStandardMask(t)) != 0) offered.push_back(t);
  return offered;
}

namespace {

// "0 Composite0, 1 S-Video".
std::string inputsText(const std::vector<VideoInput>& inputs) {
  std::string text;
  for (const VideoInput& in : inputs) text += (text.empty() ? "" : ", ") + std::to_string(in.index) + " " + in.name;
  return text;
}

// "PAL-BG, NTSC-M": the listed standards an input takes.
std::string standardsText(const std::vector<VideoStandard>& standards, std::uint64_t mask) {
  std::string text;
  for (const VideoStandard& s : standards)
    if ((s.id & mask) != 0) text += (text.empty() ? "" : ", ") + s.name;
  return text;
}

// The Status and the words for a refused S_INPUT / S_STD.
Status selectionFailure(int err, Status refused, const std::string& what, std::string& error) {
  const bool gone = err == ENODEV || err == EIO;
  const Status s = gone ? Status::CameraDisconnected : err == EBUSY ? Status::CameraBusy : refused;
  error = what + ": " + std::string(statusMessage(s)) + " (" + v4l2::errnoText(err) + ")";
  return s;
}

}  // namespace

Status selectInputAndStandard(DeviceIo& io, int fd, const std::string& path, int input, TvStandard standard,
                              std::string& error) {
  if (input < 0 && standard == TvStandard::Keep) return Status::Ok;
  DeviceInfo info;
  v4l2::readInputsAndStandards(io, fd, info);
  if (input >= 0) {
    if (static_cast<std::size_t>(input) >= info.inputs.size()) {
      error = path + ": no input " + std::to_string(input) +
              (info.inputs.empty() ? " (the device lists no inputs)" : " (its inputs: " + inputsText(info.inputs) + ")");
      return Status::CameraNoSuchInput;
    }
    int index = input;
    if (v4l2::xioctl(io, fd, VIDIOC_S_INPUT, &index) < 0)
      return selectionFailure(errno, Status::CameraNoSuchInput, path + ": input " + std::to_string(input), error);
    info.current_input = input;
  }
  if (standard == TvStandard::Keep) return Status::Ok;
  const std::string name(enumLabel(standard));
  const bool known_input = info.current_input >= 0 && static_cast<std::size_t>(info.current_input) < info.inputs.size();
  // An input says which standards it takes; a device without inputs, its list does.
  std::uint64_t takes = 0;
  for (const VideoStandard& s : info.standards) takes |= s.id;
  if (known_input) takes = info.inputs[static_cast<std::size_t>(info.current_input)].standards;
  const std::string where =
      known_input ? "input " + std::to_string(info.current_input) + " (" +
                        info.inputs[static_cast<std::size_t>(info.current_input)].name + ")"
                  : std::string("the device");
  v4l2_std_id id = tvStandardMask(standard) & takes;
  if (id == 0) {
    const std::string offered = standardsText(info.standards, takes);
    error = path + ": " + where + " takes no " + name +
            (offered.empty() ? " (it takes no TV standard)" : " (it takes " + offered + ")");
    return Status::CameraStandardRefused;
  }
  if (v4l2::xioctl(io, fd, VIDIOC_S_STD, &id) < 0)
    return selectionFailure(errno, Status::CameraStandardRefused, path + ": " + name + " on " + where, error);
  return Status::Ok;
}

std::vector<std::string> listVideoDevices(const std::string& folder) {
  std::vector<std::string> paths;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() > 5 && name.compare(0, 5, "video") == 0 &&
        std::all_of(name.begin() + 5, name.end(), [](char c) { return c >= '0' && c <= '9'; }))
      paths.push_back(it->path().string());
  }
  std::sort(paths.begin(), paths.end(), naturalLess);
  return paths;
}

Status queryDevice(DeviceIo& io, const std::string& path, DeviceInfo& info, std::string& error) {
  info = DeviceInfo{};
  info.path = path;
  int fd = -1;
  Status s = v4l2::openDevice(io, path, fd, error);
  if (!ok(s)) return s;
  s = v4l2::readCapabilities(io, fd, info, error);
  if (ok(s)) {
    if (info.video_capture) v4l2::readFormats(io, fd, info.formats);
    v4l2::readControls(io, fd, info.controls);
    if (info.video_capture) v4l2::readInputsAndStandards(io, fd, info);
  }
  io.close(fd);
  return s;
}

Status setDeviceControl(DeviceIo& io, const std::string& path, const std::string& key, std::int64_t value,
                        std::string& error) {
  DeviceInfo info;
  info.path = path;
  int fd = -1;
  Status s = v4l2::openDevice(io, path, fd, error);
  if (!ok(s)) return s;
  s = v4l2::readCapabilities(io, fd, info, error);
  if (ok(s)) {
    v4l2::readControls(io, fd, info.controls);
    const std::string wanted = controlKey(key);
    const auto it = std::find_if(info.controls.begin(), info.controls.end(),
                                 [&](const CameraControl& c) { return c.key == wanted; });
    if (it == info.controls.end()) {
      error = path + ": no control \"" + key + "\"";
      s = Status::InvalidSettings;
    } else {
      s = v4l2::writeControl(io, fd, *it, value, error);
      if (!ok(s)) error = path + ": " + error;
    }
  }
  io.close(fd);
  return s;
}

std::string controlKey(const std::string& name) {
  std::string key;
  bool gap = false;
  for (char c : name) {
    const bool alnum = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    if (!alnum) {
      gap = true;
      continue;
    }
    if (gap && !key.empty()) key += '_';
    gap = false;
    key += (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  }
  return key;
}

std::string controlValueProblem(const CameraControl& control, std::int64_t value) {
  if (control.read_only) return "read-only";
  switch (control.type) {
    case ControlType::Button: return {};
    case ControlType::Boolean:
      return value == 0 || value == 1 ? std::string() : "must be 0 or 1";
    case ControlType::Menu:
    case ControlType::IntegerMenu: {
      for (const ControlMenuItem& item : control.menu)
        if (item.value == value) return {};
      std::string choices;
      for (const ControlMenuItem& item : control.menu)
        choices += (choices.empty() ? "" : ", ") + std::to_string(item.value) + " (" + item.name + ")";
      return "must be one of " + choices;
    }
    case ControlType::Integer:
    case ControlType::Integer64: {
      const std::int64_t step = std::max<std::int64_t>(1, control.step);
      if (value < control.minimum || value > control.maximum || (value - control.minimum) % step != 0)
        return "must be in " + std::to_string(control.minimum) + ".." + std::to_string(control.maximum) +
               (step > 1 ? " in steps of " + std::to_string(step) : std::string());
      return {};
    }
    case ControlType::Other: return "cannot be set as a number";
  }
  return "unknown control type";
}

namespace {

FrameInterval intervalFor(double rate_hz) {
  // rate_hz frames per second -> 1000 / round(1000 rate) seconds, reduced.
  const auto denominator = static_cast<std::uint32_t>(std::lround(rate_hz * 1000.0));
  std::uint32_t numerator = 1000;
  const std::uint32_t g = std::gcd(numerator, denominator);
  return g == 0 ? FrameInterval{} : FrameInterval{numerator / g, denominator / g};
}

double highestRate(const FrameRates& rates) {
  if (rates.is_range) return rates.shortest.rateHz();
  double best = 0.0;
  for (const FrameInterval& i : rates.discrete) best = std::max(best, i.rateHz());
  return best;
}

FrameInterval chooseInterval(const FrameRates& rates, double rate_hz) {
  if (rate_hz <= 0.0) return {};
  if (rates.is_range) {
    if (rate_hz >= rates.shortest.rateHz()) return rates.shortest;
    if (rate_hz <= rates.longest.rateHz()) return rates.longest;
    return intervalFor(rate_hz);
  }
  if (rates.discrete.empty()) return intervalFor(rate_hz);  // not listed: the driver adjusts
  FrameInterval best = rates.discrete.front();
  for (const FrameInterval& i : rates.discrete) {
    const double d = std::abs(i.rateHz() - rate_hz);
    const double best_d = std::abs(best.rateHz() - rate_hz);
    if (d < best_d || (d == best_d && i.rateHz() > best.rateHz())) best = i;
  }
  return best;
}

int snap(int wanted, int lo, int hi, int step) {
  const int v = std::clamp(wanted, lo, hi);
  return std::min(hi, lo + (v - lo + step / 2) / step * step);
}

}  // namespace

Status chooseCapture(const std::vector<FormatInfo>& formats, int width, int height, double rate_hz,
                     CaptureChoice& choice, std::string& error) {
  const bool any_size = width <= 0 || height <= 0;
  // Lower is better, compared in order; see the header for the priorities.
  using Score = std::tuple<long long, double, long long, int>;
  bool found = false;
  Score best{};
  for (const FormatInfo& f : formats) {
    if (!f.format) continue;
    const int cost = conversionCost(*f.format) + (f.emulated ? 10 : 0);
    auto consider = [&](int w, int h, const FrameRates& rates) {
      const double shortfall = rate_hz > 0.0 && !rates.empty() ? std::max(0.0, rate_hz - highestRate(rates)) : 0.0;
      const long long area = static_cast<long long>(w) * h;
      const Score score = any_size ? Score{0, shortfall, -area, cost}
                                   : Score{std::abs(w - width) + std::abs(h - height), shortfall, cost, 0};
      if (found && !(score < best)) return;
      found = true;
      best = score;
      choice = {f.fourcc, *f.format, w, h, chooseInterval(rates, rate_hz)};
    };
    if (f.sizes.empty()) consider(any_size ? 0 : width, any_size ? 0 : height, FrameRates{});
    for (const FrameSize& s : f.sizes) {
      if (s.is_range && !any_size)
        consider(snap(width, s.min_width, s.width, s.step_width), snap(height, s.min_height, s.height, s.step_height),
                 s.rates);
      else
        consider(s.width, s.height, s.rates);
    }
  }
  if (found) return Status::Ok;
  std::string offered;
  for (const FormatInfo& f : formats) offered += (offered.empty() ? "" : ", ") + fourccText(f.fourcc);
  error = "no pixel format ImagePro can read among " + (offered.empty() ? std::string("none listed") : offered);
  return Status::CameraNoSupportedFormat;
}

}  // namespace imagepro
