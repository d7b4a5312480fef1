#pragma once
// What a V4L2 camera offers (thesis 2.2 and 5.2.1: today's counterpart of the frame
// grabber): its formats with their frame sizes and frame intervals, its controls
// (exposure, gain, brightness, focus ...), a capture card's inputs and TV standards
// and choosing them, and the choice of format, size and rate
// closest to a request. Used by the capture source (camera_source.h), by
// `imagepro-cli devices` and by the GUI's device settings.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/camera/device_io.h"
#include "core/camera/pixel_format.h"
#include "core/common/status.h"
#include "core/settings/options.h"

namespace imagepro {

// Seconds per frame as a fraction (V4L2 frame interval); 0/0 when unknown.
struct FrameInterval {
  std::uint32_t numerator = 0;
  std::uint32_t denominator = 0;
  // Frames per second; 0 when unknown.
  double rateHz() const {
    return numerator == 0 ? 0.0 : static_cast<double>(denominator) / static_cast<double>(numerator);
  }
  bool operator==(const FrameInterval&) const = default;
};

// The frame intervals a device offers at one size: a list, or a range.
struct FrameRates {
  std::vector<FrameInterval> discrete;  // as the driver lists them
  bool is_range = false;                // then: any interval between these
  FrameInterval shortest;               // highest rate of a range
  FrameInterval longest;                // lowest rate of a range
  bool empty() const { return discrete.empty() && !is_range; }
};

// One frame size, or a range of sizes min..max in steps.
struct FrameSize {
  int width = 0;   // the size; for a range the largest
  int height = 0;
  bool is_range = false;
  int min_width = 0, min_height = 0, step_width = 1, step_height = 1;
  FrameRates rates;  // for a range: the rates at its largest size
};

struct FormatInfo {
  std::uint32_t fourcc = 0;
  std::string description;               // the driver's words
  std::optional<PixelFormat> format;     // nullopt: ImagePro cannot read it
  bool emulated = false;                 // converted by libv4l2 (costs CPU)
  std::vector<FrameSize> sizes;          // empty when the driver does not list them
};

enum class ControlType : std::uint8_t { Integer, Boolean, Menu, IntegerMenu, Button, Integer64, Other };

struct ControlMenuItem {
  std::int64_t value = 0;
  std::string name;
};

struct CameraControl {
  std::uint32_t id = 0;
  std::string name;       // the driver's words ("Exposure Time, Absolute")
  std::string key;        // lower case, words joined by '_' ("exposure_time_absolute")
  ControlType type = ControlType::Integer;
  std::int64_t minimum = 0, maximum = 0, step = 1, default_value = 0;
  std::int64_t value = 0;           // current value (0 for buttons and write-only)
  bool read_only = false;
  bool inactive = false;            // e.g. exposure time while exposure is automatic
  std::vector<ControlMenuItem> menu;  // Menu and IntegerMenu
};

// One input of a capture card (VIDIOC_ENUMINPUT): "Composite0", "S-Video" ...
struct VideoInput {
  std::uint32_t index = 0;
  std::string name;
  bool tuner = false;           // a TV tuner's input rather than a camera's or a socket's
  std::uint64_t standards = 0;  // the TV standards it takes (a V4L2 standard mask; 0: none)
};

// One TV standard a capture card offers (VIDIOC_ENUMSTD): "PAL-BG", "NTSC-M" ...
struct VideoStandard {
  std::uint64_t id = 0;  // its V4L2 standard mask
  std::string name;
  double frame_rate_hz = 0.0;
};

struct DeviceInfo {
  std::string path;
  std::string card;    // product name
  std::string driver;
  std::string bus;
  bool video_capture = false;  // false: another kind of node (metadata, output ...)
  bool streaming = false;      // memory-mapped streaming offered
  std::vector<FormatInfo> formats;
  std::vector<CameraControl> controls;
  // A capture card's inputs and TV standards; empty for a device without them (most
  // USB cameras have one input and no standard).
  std::vector<VideoInput> inputs;
  int current_input = -1;  // -1: the device does not say
  std::vector<VideoStandard> standards;
  std::uint64_t current_standard = 0;  // 0: none, or the device does not say
};

// The V4L2 device nodes /dev/video* of `folder` in natural order ("video2" before
// "video10"). Empty when there is none.
std::vector<std::string> listVideoDevices(const std::string& folder = "/dev");

// Opens `path`, reads its capabilities, formats (with sizes and intervals) and
// controls, and closes it again. Errors: CameraNotFound (no node, or not a V4L2
// device), CameraPermissionDenied, CameraBusy; `error` names the device.
Status queryDevice(DeviceIo& io, const std::string& path, DeviceInfo& info, std::string& error);

// Sets one control of a device that is not streaming through this program (a
// streaming CameraSource has its own setControl). `key` is a control key or its name
// in any case. InvalidSettings names an unknown control or a value out of its range.
Status setDeviceControl(DeviceIo& io, const std::string& path, const std::string& key, std::int64_t value,
                        std::string& error);

// The V4L2 standard mask of a TV standard group (0 for Keep).
std::uint64_t tvStandardMask(TvStandard standard);
// The groups (PAL, NTSC, SECAM), in that order, that input `input` takes (-1: the
// current one); for a device without inputs, those its listed standards fall into.
// Empty for a device or an input without standards.
std::vector<TvStandard> tvStandardsOffered(const DeviceInfo& info, int input = -1);

// Makes input `input` (-1: leave it) and then `standard` (Keep: leave it) the device's,
// the order a capture card needs (the standards are an input's). CameraNoSuchInput
// when the device has no input of that number (`error` lists those it has),
// CameraStandardRefused when the input does not take the standard (`error` names what
// it takes), CameraDisconnected for a vanished device.
Status selectInputAndStandard(DeviceIo& io, int fd, const std::string& path, int input, TvStandard standard,
                              std::string& error);

// "Exposure Time, Absolute" -> "exposure_time_absolute".
std::string controlKey(const std::string& name);

// Checks `value` against the control's type and range; empty when it fits, else why not.
std::string controlValueProblem(const CameraControl& control, std::int64_t value);

// The format, size and frame interval to ask the driver for.
struct CaptureChoice {
  std::uint32_t fourcc = 0;
  PixelFormat format = PixelFormat::Grey;
  int width = 0;
  int height = 0;
  FrameInterval interval;  // 0/0: leave the driver's rate
};

// Picks among the readable formats, in this order of importance: the size nearest
// to width x height (|dw| + |dh|; a range is snapped to its steps; 0 x 0 asks for
// the largest that reaches the rate), then a rate that reaches rate_hz, then the
// cheapest conversion to grey (conversionCost; converted-by-libv4l2 formats last).
// The interval is the listed one nearest to rate_hz (rate_hz = 0: leave the
// driver's). A format whose sizes are not listed is taken at the requested size, for
// the driver to adjust. CameraNoSupportedFormat when no format is readable.
Status chooseCapture(const std::vector<FormatInfo>& formats, int width, int height, double rate_hz,
                     CaptureChoice& choice, std::string& error);

}  // namespace imagepro
