#include "app/source_factory.h"

#include <filesystem>

#include "core/camera/camera_source.h"
#include "core/camera/video_file.h"
#include "core/source/image_file.h"
#include "core/source/sources.h"

namespace imagepro::app {

namespace {

// Files as given; folders and list files expanded to their images.
bool expandPaths(const QStringList& paths, std::vector<std::string>& files, std::string& error) {
  for (const QString& p : paths) {
    const std::string path = p.toStdString();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec) || (!isImageFileName(path) && std::filesystem::is_regular_file(path, ec))) {
      std::vector<std::string> listed;
      if (!ok(listImageSequence(path, listed, error))) return false;
      files.insert(files.end(), listed.begin(), listed.end());
    } else {
      files.push_back(path);  // a missing or unreadable file is reported by the source
    }
  }
  if (files.empty()) {
    error = "no image files given";
    return false;
  }
  return true;
}

}  // namespace

std::unique_ptr<FrameSource> createSource(SourceKind kind, const Settings& settings, const QStringList& paths,
                                          std::string& error) {
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
      return makeFileSource(std::move(files));
    }
    case SourceKind::Camera: {
      // The default device at the thesis's 25 Hz; device choice and controls come later.
      auto camera = std::make_unique<CameraSource>(CameraRequest{});
      if (!ok(camera->start())) {
        error = camera->lastError();
        return nullptr;
      }
      return camera;
    }
  }
  error = "unknown source";
  return nullptr;
}

void updateSource(FrameSource& source, SourceKind kind, const Settings& settings) {
  if (kind == SourceKind::Virtual) static_cast<VirtualSource&>(source).setSettings(settings);
}

void pressSourceKey(FrameSource& source, SourceKind kind, VirtualKey key) {
  if (kind == SourceKind::Virtual) static_cast<VirtualSource&>(source).pressKey(key);
}

}  // namespace imagepro::app
