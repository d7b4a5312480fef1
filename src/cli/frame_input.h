#pragma once
// Turns the command line's input (image files, folders, list files, --virtual,
// --camera, --video) into a FrameSource, shared by every command that runs the pipeline.
#include <memory>

#include "cli/command.h"
#include "core/camera/camera_source.h"
#include "core/source/source.h"

namespace imagepro::cli {

// Options understood: positionals (images, folders, lists: core/source/image_inputs.h), --virtual,
// --camera DEV [--size WxH] [--fps N], --video FILE, and --frames N (how many; the
// virtual source defaults to 100, camera and video run until they end).
// Throws UsageError when no input is given, InputError when it cannot be opened
// (a missing camera: one line naming the device). A camera stream ends after the
// first failure that needs a restart (CameraDisconnected ...), which is reported.
std::unique_ptr<FrameSource> openFrameInput(const Args& args, const Settings& settings);

// The source the command line's input is: --camera Camera, --virtual Virtual, --video and
// image files File; without any (a command that renders) Virtual.
SourceKind frameInputSource(const Args& args);
// loadConfig(args) with that source in use, so the pipeline takes its camera model.
Settings loadConfigForInput(const Args& args);

// The camera of --camera DEV, streaming: the settings' camera_source size, rate, input
// and standard (its size 0 x 0: the Camera source's camera model's) unless --size WxH,
// --fps N, --input N, --standard PAL|NTSC|SECAM; then its stored controls, each one the
// device lacks or refuses a warning on stderr. Throws UsageError for a malformed
// --size / --fps / --input / --standard, InputError naming the device when it cannot
// be opened (CameraNotFound, CameraNoSuchInput ...).
std::unique_ptr<CameraSource> openCamera(const Args& args, const Settings& settings);

// A frame's source error for stderr: the error as it stands when it names the frame
// already (a file's path does), else "frame: error".
std::string frameProblem(const std::string& frame, const std::string& error);

// The option names openFrameInput reads, for rejectUnknown and --help.
inline const std::vector<std::string> kFrameInputOptions{"virtual", "frames", "camera", "size",
                                                         "fps",     "input",  "standard", "video"};
inline constexpr const char* kFrameInputHelp =
    "input: IMAGES... (files, folders in natural order, or lists of paths: any other text file,\n"
    "          one path a line)\n"
    "       or --virtual [--frames N] (the Virtual source of the settings, default 100 frames)\n"
    "       or --camera /dev/videoN [--size WxH] [--fps N] [--frames N] (a V4L2 camera; default size\n"
    "          and rate the settings' camera_source, or the camera model's size, 25 frames/s; its\n"
    "          stored controls are set; imagepro-cli devices lists the cameras)\n"
    "          [--input N] [--standard PAL|NTSC|SECAM] (a capture card's input and TV standard,\n"
    "          as imagepro-cli devices lists them; default the settings' camera_source's)\n"
    "       or --video FILE [--frames N] (AVI, MP4, MKV ..., every frame as fast as possible)";

}  // namespace imagepro::cli
