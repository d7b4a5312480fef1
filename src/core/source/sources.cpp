#include "core/source/sources.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <opencv2/imgproc.hpp>

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

// A set's members side by side on one moving body, in the target's plane: member k's
// card lies k card widths and gaps along the first member's +X, so the live demo of a set
// shows every member (the first at the scene's pose: the frame's truth).
constexpr double kSetCardGapMm = 20.0;

Pose memberPose(const Pose& first, std::size_t k, double spacingMm) {
  const Eigen::Matrix3d R = rotationMatrix(first);
  return poseFromRt(R, translation(first) + R * Eigen::Vector3d(static_cast<double>(k) * spacingMm, 0.0, 0.0));
}

// The pixels `pose`'s card may reach in the image (its corners' polygon, as the lens bends
// them, grown by the blur's reach); false when a corner lies behind the camera.
bool cardMask(const CameraModel& camera, const Pose& pose, double halfMm, double blurPx, cv::Mat& mask) {
  const Eigen::Matrix3d R = rotationMatrix(pose);
  const Eigen::Vector3d T = translation(pose);
  std::array<cv::Point, 4> corners;
  const std::array<Eigen::Vector2d, 4> local{Eigen::Vector2d(-halfMm, -halfMm), Eigen::Vector2d(halfMm, -halfMm),
                                             Eigen::Vector2d(halfMm, halfMm), Eigen::Vector2d(-halfMm, halfMm)};
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d Pc = R * Eigen::Vector3d(local[i].x(), local[i].y(), 0.0) + T;
    if (!(Pc.z() > 1.0)) return false;
    const Eigen::Vector2d q = distortPixel(camera, projectIdeal(camera, Pc));
    if (!q.allFinite() || std::abs(q.x()) > 1e5 || std::abs(q.y()) > 1e5) return false;
    corners[i] = cv::Point(static_cast<int>(std::lround(q.x())), static_cast<int>(std::lround(q.y())));
  }
  mask.create(camera.height, camera.width, CV_8UC1);
  mask.setTo(0);
  cv::fillConvexPoly(mask, corners.data(), 4, cv::Scalar(255));
  const int grow = static_cast<int>(std::ceil(3.0 * blurPx)) + 3;  // the blur's reach and the bent edges
  cv::dilate(mask, mask, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * grow + 1, 2 * grow + 1)));
  return true;
}

// Draws members 1.. of the set over `image` (the first member drawn at `first`): each is
// rendered in the same scene with the same noise, and its card's pixels are copied in.
void drawOtherMembers(const Settings& settings, const CameraModel& camera, const Pose& first, std::uint64_t seed,
                      cv::Mat& image) {
  const VirtualSceneOptions& scene = settings.virtual_scene;
  thread_local cv::Mat member, mask;
  for (std::size_t k = 1; k < settings.targets.size(); ++k) {
    const TargetGeometry& g = settings.targets[k].geometry;
    const double half = std::max(0.5 * scene.card_size_mm, g.radius_mm);
    const Pose pose = memberPose(first, k, 2.0 * half + kSetCardGapMm);
    if (!cardMask(camera, pose, half, scene.blur_sigma_px, mask)) continue;
    renderTarget(camera, g, scene, pose, member, seed);
    member.copyTo(image, mask);
  }
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
  // With a set of targets, every member side by side, the first at the scene's pose (the
  // pattern carries the first alone).
  const TargetGeometry& target = settings.targets.empty() ? settings.target : settings.targets.front().geometry;
  if (content == VirtualContent::Pattern) {
    renderPattern(camera, target, settings.pattern, scene, pose, out.image, seed);
  } else {
    renderTarget(camera, target, scene, pose, out.image, seed);
    if (settings.targets.size() > 1 && !out.image.empty()) drawOtherMembers(settings, camera, pose, seed, out.image);
  }
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
