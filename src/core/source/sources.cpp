#include "core/source/sources.h"

#include <cstdio>
#include <filesystem>

#include "core/settings/enum_names.h"
#include "core/source/virtual_renderer.h"

namespace imagepro {

namespace {

class FileSource final : public FrameSource {
 public:
  explicit FileSource(std::vector<std::string> paths) : paths_(std::move(paths)) {}

  Status next(Frame& out) override {
    if (next_ >= paths_.size()) {
      error_ = "no more files";
      return Status::EndOfStream;
    }
    const std::string& path = paths_[next_];
    out.index = static_cast<std::int64_t>(next_);
    out.timestamp_s = 0.0;
    out.name = std::filesystem::path(path).filename().string();
    out.truth.reset();
    ++next_;
    last_name_ = out.name;
    const Status s = readGreyImage(path, out.image, error_);
    if (ok(s)) error_.clear();
    return s;
  }

  std::string lastError() const override { return error_; }
  double frameRateHz() const override { return 0.0; }
  std::string describe() const override {
    if (paths_.size() == 1) return "file " + std::filesystem::path(paths_[0]).filename().string();
    std::string d = "files (" + std::to_string(paths_.size()) + ")";
    if (!last_name_.empty()) d += " " + last_name_;
    return d;
  }

 private:
  std::vector<std::string> paths_;
  size_t next_ = 0;
  std::string error_;
  std::string last_name_;
};

// Frame `index` of the scene's motion, with the key offset.
Pose framePose(const VirtualSceneOptions& scene, const Pose& offset, std::int64_t index) {
  return withOffset(virtualPoseAt(scene, static_cast<double>(index) / scene.frame_rate_hz), offset);
}

}  // namespace

std::unique_ptr<FrameSource> makeFileSource(std::vector<std::string> paths) {
  return std::make_unique<FileSource>(std::move(paths));
}

VirtualSource::VirtualSource(const Settings& settings, VirtualContent content)
    : settings_(settings), content_(content) {}

Status VirtualSource::next(Frame& out) {
  // Copy the state under the lock (plain values, no allocation), render outside it.
  Settings settings;
  VirtualContent content;
  Pose offset;
  std::int64_t index;
  {
    std::lock_guard lock(mutex_);
    settings = settings_;
    content = content_;
    offset = offset_;
    index = index_++;
  }
  const VirtualSceneOptions& scene = settings.virtual_scene;
  const Pose pose = framePose(scene, offset, index);
  const auto seed = static_cast<std::uint64_t>(index);
  // Its own camera, whichever source the settings say is in use.
  const CameraModel& camera = settings.camera(SourceKind::Virtual);
  // With a set of targets, its first member: a target the set knows (target_set.h).
  const TargetGeometry& target = settings.targets.empty() ? settings.target : settings.targets.front().geometry;
  if (content == VirtualContent::Pattern)
    renderPattern(camera, target, settings.pattern, scene, pose, out.image, seed);
  else
    renderTarget(camera, target, scene, pose, out.image, seed);
  out.index = index;
  out.timestamp_s = static_cast<double>(index) / scene.frame_rate_hz;
  out.name.clear();
  out.truth = pose;
  return out.image.empty() ? Status::EmptyFrame : Status::Ok;
}

double VirtualSource::frameRateHz() const {
  std::lock_guard lock(mutex_);
  return settings_.virtual_scene.frame_rate_hz;
}

std::string VirtualSource::describe() const {
  std::lock_guard lock(mutex_);
  const VirtualSceneOptions& s = settings_.virtual_scene;
  char rate[32];
  std::snprintf(rate, sizeof rate, "%g Hz", s.frame_rate_hz);
  std::string d = "virtual ";
  d += rate;
  d += ", ";
  // Shown to people (the status bar, the CLI's summary): the display names, not the keys.
  d += enumLabel(s.mode);
  d += ", ";
  d += enumLabel(s.motion.kind);
  if (content_ == VirtualContent::Pattern) d += ", pattern";
  return d;
}

void VirtualSource::pressKey(VirtualKey key) {
  std::lock_guard lock(mutex_);
  applyKey(key, settings_.virtual_scene, offset_);
}

void VirtualSource::setSettings(const Settings& settings) {
  std::lock_guard lock(mutex_);
  settings_ = settings;
}

void VirtualSource::setContent(VirtualContent content) {
  std::lock_guard lock(mutex_);
  content_ = content;
}

void VirtualSource::resetKeyOffset() {
  std::lock_guard lock(mutex_);
  offset_ = kZeroPoseOffset;
}

void VirtualSource::restart() {
  std::lock_guard lock(mutex_);
  index_ = 0;
}

Pose VirtualSource::keyOffset() const {
  std::lock_guard lock(mutex_);
  return offset_;
}

std::int64_t VirtualSource::nextIndex() const {
  std::lock_guard lock(mutex_);
  return index_;
}

Pose VirtualSource::poseAt(std::int64_t index) const {
  std::lock_guard lock(mutex_);
  return framePose(settings_.virtual_scene, offset_, index);
}

std::unique_ptr<VirtualSource> makeVirtualSource(const Settings& settings, VirtualContent content) {
  return std::make_unique<VirtualSource>(settings, content);
}

}  // namespace imagepro
