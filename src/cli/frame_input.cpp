#include "cli/frame_input.h"

#include <cctype>
#include <cstdio>
#include <stdexcept>

#include "cli/image_inputs.h"
#include "core/camera/camera_settings.h"
#include "core/camera/video_file.h"
#include "core/common/image_limits.h"
#include "core/settings/enum_names.h"
#include "core/source/sources.h"

namespace imagepro::cli {

namespace {

// A source around another: everything but next() is the inner source's.
class WrappedSource : public FrameSource {
 public:
  explicit WrappedSource(std::unique_ptr<FrameSource> inner) : inner_(std::move(inner)) {}
  std::string lastError() const override { return inner_->lastError(); }
  double frameRateHz() const override { return inner_->frameRateHz(); }
  std::string describe() const override { return inner_->describe(); }

 protected:
  std::unique_ptr<FrameSource> inner_;
};

// Ends an endless source after a number of frames.
class FrameLimit final : public WrappedSource {
 public:
  FrameLimit(std::unique_ptr<FrameSource> inner, std::int64_t frames)
      : WrappedSource(std::move(inner)), left_(frames) {}
  Status next(Frame& out) override {
    if (left_ <= 0) return Status::EndOfStream;
    --left_;
    return inner_->next(out);
  }

 private:
  std::int64_t left_;
};

// Ends a camera stream after a failure that needs a restart: the loop gets the
// failure once (so it is reported), then EndOfStream.
class EndAfterCameraFailure final : public WrappedSource {
 public:
  using WrappedSource::WrappedSource;
  Status next(Frame& out) override {
    if (failed_) return Status::EndOfStream;
    const Status s = inner_->next(out);
    failed_ = isCameraFailure(s);
    return s;
  }

 private:
  bool failed_ = false;
};

// Image files decoded without the decoders' own stderr lines: the frame's row and
// lastError() name the problem once.
class QuietDecoding final : public WrappedSource {
 public:
  using WrappedSource::WrappedSource;
  Status next(Frame& out) override {
    const DecoderMessagesSilenced quiet;
    return inner_->next(out);
  }
};

// "640x480" -> width and height.
void parseSize(const std::string& text, int& width, int& height) {
  const auto x = text.find('x');
  try {
    std::size_t used_w = 0, used_h = 0;
    if (x != std::string::npos) {
      width = std::stoi(text.substr(0, x), &used_w);
      height = std::stoi(text.substr(x + 1), &used_h);
    }
    if (x != std::string::npos && used_w == x && used_h == text.size() - x - 1 && width > 0 && height > 0) {
      if (const std::string problem = imageSizeProblem(width, height); !problem.empty())
        throw UsageError("--size: " + problem);
      return;
    }
  } catch (const std::invalid_argument&) {
  } catch (const std::out_of_range&) {
  }
  throw UsageError("--size: \"" + text + "\" is not WIDTHxHEIGHT, e.g. 640x480");
}

// --size, --fps, --input and --standard belong to a camera.
void rejectCameraOptions(const Args& args) {
  for (const char* option : {"size", "fps", "input", "standard"})
    if (args.has(option)) throw UsageError(std::string("--") + option + " goes with --camera");
}

// --standard's value in any case ("PAL", "pal").
TvStandard standardOption(const Args& args, TvStandard fallback) {
  const auto text = args.value("standard");
  if (!text) return fallback;
  std::string key = *text;
  for (char& c : key) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const auto parsed = parseEnum<TvStandard>(key);
  if (!parsed) throw UsageError("--standard: \"" + *text + "\" is not one of PAL, NTSC, SECAM, keep");
  return *parsed;
}

std::unique_ptr<FrameSource> openCameraOrVideo(const Args& args, const Settings& settings) {
  std::unique_ptr<FrameSource> source;
  if (args.has("camera")) {
    source = std::make_unique<EndAfterCameraFailure>(openCamera(args, settings));
  } else {
    rejectCameraOptions(args);
    auto video = std::make_unique<VideoFileSource>(*args.value("video"), VideoPacing::AsFastAsPossible);
    if (!ok(video->open())) throw InputError(video->lastError());
    source = std::move(video);
  }
  if (!args.has("frames")) return source;
  const int frames = args.integer("frames", 0);
  if (frames < 1) throw UsageError("--frames must be at least 1");
  return std::make_unique<FrameLimit>(std::move(source), frames);
}

}  // namespace

std::unique_ptr<CameraSource> openCamera(const Args& args, const Settings& settings) {
  CameraRequest request = cameraRequest(settings);
  request.device = args.valueOr("camera", request.device);
  if (const auto size = args.value("size")) parseSize(*size, request.width, request.height);
  request.frame_rate_hz = args.number("fps", request.frame_rate_hz);
  if (args.has("fps") && !(request.frame_rate_hz > 0.0)) throw UsageError("--fps must be above 0");
  request.input = args.integer("input", request.input);
  if (args.has("input") && request.input < 0)
    throw UsageError("--input must be 0 or more (imagepro-cli devices numbers them)");
  request.standard = standardOption(args, request.standard);
  auto camera = std::make_unique<CameraSource>(request);
  if (!ok(camera->start())) throw InputError(camera->lastError());
  std::vector<std::string> problems;
  applyStoredControls(*camera, settings.camera_source.controls, problems);
  for (const std::string& p : problems) std::fprintf(stderr, "warning: %s\n", p.c_str());
  return camera;
}

SourceKind frameInputSource(const Args& args) {
  if (args.has("camera")) return SourceKind::Camera;
  if (args.has("video") || !args.positionals().empty()) return SourceKind::File;
  return SourceKind::Virtual;
}

Settings loadConfigForInput(const Args& args) {
  Settings settings = loadConfig(args);
  settings.source = frameInputSource(args);
  return settings;
}

std::string frameProblem(const std::string& frame, const std::string& error) {
  return error.find(frame) != std::string::npos ? error : frame + ": " + error;
}

std::unique_ptr<FrameSource> openFrameInput(const Args& args, const Settings& settings) {
  const int inputs = args.has("virtual") + args.has("camera") + args.has("video") + !args.positionals().empty();
  if (inputs > 1) throw UsageError("give one input: image files, --virtual, --camera or --video");
  if (args.has("camera") || args.has("video")) return openCameraOrVideo(args, settings);
  rejectCameraOptions(args);
  if (args.has("virtual")) {
    if (!args.positionals().empty()) throw UsageError("give either --virtual or image files, not both");
    const int frames = args.integer("frames", 100);
    if (frames < 1) throw UsageError("--frames must be at least 1");
    return std::make_unique<FrameLimit>(makeVirtualSource(settings), frames);
  }
  if (args.positionals().empty()) throw UsageError("no input: give image files, a folder, or --virtual");
  std::vector<std::string> paths;
  for (ImageInput& input : expandImageInputs(args.positionals())) {
    // A folder or list that names no image stops the command; a missing or corrupt
    // image is reported in its own row and the others go on.
    if (!ok(input.status)) throw InputError(input.error);
    paths.push_back(std::move(input.path));
  }
  return std::make_unique<QuietDecoding>(makeFileSource(std::move(paths)));
}

}  // namespace imagepro::cli
