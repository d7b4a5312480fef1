#pragma once
// Internal to the camera module (the only place that sees the V4L2 headers): the
// V4L2 queries shared by the device description and the capture source.
#include <linux/videodev2.h>

#include <string>
#include <vector>

#include "core/camera/camera_info.h"
#include "core/camera/device_io.h"

namespace imagepro::v4l2 {

// ioctl that repeats when a signal interrupts it.
int xioctl(DeviceIo& io, int fd, unsigned long request, void* arg);

// "No such file or directory".
std::string errnoText(int err);

// The Status for a failed open() of a device node.
Status openFailure(int err);

// Opens `path`; on failure sets `error` ("<path>: <reason> (<errno text>)").
Status openDevice(DeviceIo& io, const std::string& path, int& fd, std::string& error);

// VIDIOC_QUERYCAP into `info` (path, card, driver, bus, capture, streaming).
// CameraNotFound when the node does not answer it (not a V4L2 device).
Status readCapabilities(DeviceIo& io, int fd, DeviceInfo& info, std::string& error);

// Every capture format with its sizes and frame intervals.
void readFormats(DeviceIo& io, int fd, std::vector<FormatInfo>& formats);

// The inputs (VIDIOC_ENUMINPUT) and TV standards (VIDIOC_ENUMSTD) with the current ones;
// nothing for a device that lists none.
void readInputsAndStandards(DeviceIo& io, int fd, DeviceInfo& info);

// Every enabled control with its current value (control-class headings skipped).
void readControls(DeviceIo& io, int fd, std::vector<CameraControl>& controls);

// Checks `value` against `control` and sets it. InvalidSettings when it does not fit
// or the driver refuses it now; CameraDisconnected for a vanished device.
Status writeControl(DeviceIo& io, int fd, const CameraControl& control, std::int64_t value, std::string& error);

}  // namespace imagepro::v4l2
