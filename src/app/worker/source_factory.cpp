#include "app/worker/source_factory.h"

#include "app/worker/image_list_source.h"

#include "core/camera/camera_settings.h"
#include "core/camera/video_file.h"
#include "core/source/image_inputs.h"
#include "core/source/sources.h"  // the Virtual source

namespace imagepro::app {

namespace {

// Files as given; folders and list files expanded to their images (the CLI's rule).
bool expandPaths(const QStringList& paths, std::vector<std::string>& files, std::string& error) {
  std::vector<std::string> inputs;
  for (const QString& p : paths) inputs.push_back(p.toStdString());
  for (ImageInput& input : expandImageInputs(inputs)) {
    if (!ok(input.status)) {
      error = input.error;
      return false;
    }
    files.push_back(std::move(input.path));  // a missing or unreadable image is reported by the source
  }
  if (files.empty()) {
    error = "no image files given";
    return false;
  }
  return true;
}

}  // namespace

std::unique_ptr<FrameSource> createSource(SourceKind kind, const Settings& settings, const QStringList& paths,
                                          std::string& error, std::vector<std::string>& warnings) {
  switch (kind) {
    case SourceKind::Virtual:
      return makeVirtualSource(settings);
    case SourceKind::File: {
      if (paths.size() == 1 && isVideoFileName(paths.front().toStdString())) {
        auto video = std::make_unique<VideoFileSource>(paths.front().toStdString());
        if (!ok(video->open())) {
          error = video->lastError();
          return nullptr;
        }
        return video;
      }
      std::vector<std::string> files;
      if (!expandPaths(paths, files, error)) return nullptr;
      return std::make_unique<ImageListSource>(std::move(files));
    }
    case SourceKind::Camera: {
      auto camera = std::make_unique<CameraSource>(cameraRequest(settings));
      if (!ok(camera->start())) {
        error = camera->lastError();
        return nullptr;
      }
      applyStoredControls(*camera, settings.camera_source.controls, warnings);
      return camera;
    }
  }
  error = "unknown source";
  return nullptr;
}

bool updateSource(FrameSource& source, SourceKind kind, const Settings& settings) {
  if (kind == SourceKind::Virtual) static_cast<VirtualSource&>(source).setSettings(settings);
  if (kind == SourceKind::Camera) {
    const CameraRequest& now = static_cast<CameraSource&>(source).request();
    const CameraRequest wanted = cameraRequest(settings);
    return now.device == wanted.device && now.width == wanted.width && now.height == wanted.height &&
           now.frame_rate_hz == wanted.frame_rate_hz && now.input == wanted.input && now.standard == wanted.standard;
  }
  return true;
}

Status setCameraControl(FrameSource* source, SourceKind kind, const std::string& device, const std::string& key,
                        std::int64_t value, std::string& error) {
  if (source && kind == SourceKind::Camera) {
    auto& camera = static_cast<CameraSource&>(*source);
    if (camera.request().device == device) return setControlByKey(camera, key, value, error);
  }
  return setDeviceControl(systemDeviceIo(), device, key, value, error);
}

void pressSourceKey(FrameSource& source, SourceKind kind, VirtualKey key) {
  if (kind == SourceKind::Virtual) static_cast<VirtualSource&>(source).pressKey(key);
}

}  // namespace imagepro::app
