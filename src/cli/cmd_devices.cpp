// imagepro-cli devices: the V4L2 cameras of this machine with the formats, frame
// sizes and rates they offer, a capture card's inputs and TV standards, and their
// controls; sets controls with --set.
#include <cstdio>
#include <cstdlib>

#include "cli/command.h"
#include "core/camera/camera_info.h"
#include "core/settings/enum_names.h"

namespace imagepro::cli {
namespace {

std::string rateText(double hz) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", hz);
  return buf;
}

std::string ratesText(const FrameRates& rates) {
  if (rates.is_range) return rateText(rates.longest.rateHz()) + "-" + rateText(rates.shortest.rateHz()) + " Hz";
  if (rates.discrete.empty()) return "rates not listed";
  std::string text;
  for (const FrameInterval& i : rates.discrete) text += (text.empty() ? "" : ", ") + rateText(i.rateHz());
  return text + " Hz";
}

const char* conversionText(const FormatInfo& f) {
  if (!f.format) return "not readable";
  switch (conversionCost(*f.format)) {
    case 0: return "grey in place";
    case 1: return "luma copied";
    case 2: return "converted to grey";
    default: return "decoded";
  }
}

const char* typeText(ControlType t) {
  switch (t) {
    case ControlType::Integer: return "integer";
    case ControlType::Boolean: return "boolean";
    case ControlType::Menu: return "menu";
    case ControlType::IntegerMenu: return "int menu";
    case ControlType::Button: return "button";
    case ControlType::Integer64: return "int64";
    case ControlType::Other: return "other";
  }
  return "?";
}

void printControl(const CameraControl& c) {
  std::string text;
  switch (c.type) {
    case ControlType::Integer:
    case ControlType::Integer64:
      text = std::to_string(c.minimum) + ".." + std::to_string(c.maximum);
      if (c.step > 1) text += " step " + std::to_string(c.step);
      text += ", default " + std::to_string(c.default_value) + ", value " + std::to_string(c.value);
      break;
    case ControlType::Boolean:
    case ControlType::Menu:
    case ControlType::IntegerMenu:
      text = "default " + std::to_string(c.default_value) + ", value " + std::to_string(c.value);
      for (const ControlMenuItem& item : c.menu)
        text += (&item == &c.menu.front() ? ": " : ", ") + std::to_string(item.value) + " " + item.name;
      break;
    case ControlType::Button:
    case ControlType::Other: break;
  }
  if (c.read_only) text += " (read-only)";
  if (c.inactive) text += " (inactive)";
  std::printf("    %-32s %-9s %s\n", c.key.c_str(), typeText(c.type), text.c_str());
}

void printDevice(const DeviceInfo& info) {
  std::printf("%s: %s (%s, %s)\n", info.path.c_str(), info.card.c_str(), info.driver.c_str(), info.bus.c_str());
  if (!info.video_capture) {
    std::printf("  not a video capture node (a camera's second node carries metadata)\n");
    return;
  }
  if (!info.streaming) std::printf("  no memory-mapped streaming: ImagePro cannot capture from it\n");
  std::printf("  formats:\n");
  if (info.formats.empty()) std::printf("    none listed\n");
  for (const FormatInfo& f : info.formats) {
    std::printf("    %s  %s (%s%s)\n", fourccText(f.fourcc).c_str(), f.description.c_str(), conversionText(f),
                f.emulated ? ", converted by libv4l2" : "");
    for (const FrameSize& s : f.sizes) {
      if (s.is_range)
        std::printf("      %dx%d..%dx%d step %dx%d: %s\n", s.min_width, s.min_height, s.width, s.height,
                    s.step_width, s.step_height, ratesText(s.rates).c_str());
      else
        std::printf("      %dx%d: %s\n", s.width, s.height, ratesText(s.rates).c_str());
    }
  }
  // A capture card's: printed only for a device that lists them.
  if (!info.inputs.empty()) std::printf("  inputs (--input N):\n");
  for (const VideoInput& in : info.inputs) {
    std::string takes;
    for (const TvStandard t : tvStandardsOffered(info, static_cast<int>(in.index)))
      takes += (takes.empty() ? "" : ", ") + std::string(enumLabel(t));
    std::printf("    %u  %s%s%s%s\n", in.index, in.name.c_str(), in.tuner ? " (tuner)" : "",
                takes.empty() ? "" : (", takes " + takes).c_str(),
                static_cast<int>(in.index) == info.current_input ? " (current)" : "");
  }
  if (!info.standards.empty()) std::printf("  TV standards of the current input (--standard PAL|NTSC|SECAM):\n");
  for (const VideoStandard& st : info.standards)
    std::printf("    %-10s %s frames/s%s\n", st.name.c_str(), rateText(st.frame_rate_hz).c_str(),
                st.id != 0 && (st.id & info.current_standard) == st.id ? " (current)" : "");
  std::printf("  controls:\n");
  if (info.controls.empty()) std::printf("    none\n");
  for (const CameraControl& c : info.controls) printControl(c);
}

// "exposure_auto=1,brightness=20" applied in order.
void setControls(const std::string& device, const std::string& assignments) {
  std::size_t start = 0;
  while (start <= assignments.size()) {
    const std::size_t comma = std::min(assignments.find(',', start), assignments.size());
    const std::string item = assignments.substr(start, comma - start);
    const std::size_t eq = item.find('=');
    char* end = nullptr;
    const long long value = eq == std::string::npos ? 0 : std::strtoll(item.c_str() + eq + 1, &end, 10);
    if (eq == std::string::npos || eq == 0 || end == item.c_str() + eq + 1 || *end != '\0')
      throw UsageError("--set: \"" + item + "\" is not NAME=VALUE");
    std::string error;
    if (!ok(setDeviceControl(systemDeviceIo(), device, item.substr(0, eq), value, error))) throw InputError(error);
    std::printf("%s: %s = %lld\n", device.c_str(), item.substr(0, eq).c_str(), value);
    start = comma + 1;
  }
}

int run(const Args& args) {
  args.rejectUnknown({"set", "dir"});
  std::vector<std::string> devices = args.positionals();
  if (const auto set = args.value("set")) {
    if (devices.size() != 1) throw UsageError("--set needs exactly one DEVICE");
    setControls(devices.front(), *set);
    return 0;
  }
  const bool named = !devices.empty();
  if (!named) devices = listVideoDevices(args.valueOr("dir", "/dev"));
  if (devices.empty()) {
    std::printf("no video devices found\n");
    return 0;
  }
  for (const std::string& path : devices) {
    DeviceInfo info;
    std::string error;
    const Status s = queryDevice(systemDeviceIo(), path, info, error);
    if (!ok(s) && named && devices.size() == 1) throw InputError(error);
    if (!ok(s))
      std::printf("%s: %s\n", path.c_str(), error.c_str() + (error.rfind(path + ": ", 0) == 0 ? path.size() + 2 : 0));
    else
      printDevice(info);
  }
  return 0;
}

const CommandRegistration kRegistration{{
    "devices",
    "list the cameras (V4L2) with their formats, sizes, rates and controls",
    "usage: imagepro-cli devices [DEVICE...] [--dir FOLDER]\n"
    "       imagepro-cli devices DEVICE --set NAME=VALUE[,NAME=VALUE...]\n\n"
    "Lists every /dev/video* node (or the DEVICEs given): the card, the pixel formats\n"
    "with how ImagePro reads them, their frame sizes and rates, a capture card's inputs\n"
    "and TV standards (composite, S-Video: PAL, NTSC, SECAM), and the controls with\n"
    "their ranges and current values. Prints \"no video devices found\" when there are none.\n"
    "  --dir FOLDER             look for video* nodes in FOLDER instead of /dev\n"
    "  --set NAME=VALUE,...     set controls by the names listed (e.g. brightness=20);\n"
    "                           the camera keeps them for later captures\n"
    "Capture from one with: imagepro-cli reconstruct --camera DEVICE [--size WxH] [--fps N]\n"
    "                                               [--input N] [--standard PAL|NTSC|SECAM]",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
