#include "app/calibration_wizard/calibration_images.h"

#include <QFileInfo>
#include <QObject>

#include <algorithm>
#include <cmath>

#include "app/main_window/results_text.h"
#include "core/calibration/spacing.h"
#include "core/pipeline/engine.h"
#include "core/source/image_file.h"
#include "core/source/virtual_renderer.h"

namespace imagepro::app {

Status readCalibrationImage(const QString& path, cv::Mat& grey, QString& error) {
  std::string why;
  const Status status = readGreyImage(path.toStdString(), grey, why);
  error = QString::fromStdString(why);
  if (!ok(status) && error.isEmpty()) error = QObject::tr("%1 cannot be read").arg(QFileInfo(path).fileName());
  return status;
}

Pose virtualCalibrationView(int slot) {
  return recommendedCalibrationViews(kVirtualCalibrationDistanceMm)[static_cast<size_t>(std::clamp(slot, 0, 3))];
}

void renderVirtualCalibrationImage(const Settings& settings, int slot, cv::Mat& grey) {
  renderPattern(settings.camera(), settings.target, settings.pattern, settings.virtual_scene,
                virtualCalibrationView(slot), grey, static_cast<std::uint64_t>(slot) + 1);
}

void analyseCalibrationImage(const Settings& settings, CalibrationImage& image) {
  image.target_status = image.spot_status = Status::Stopped;
  image.target.reset();
  image.spots.clear();
  image.first = {};
  const CameraModel& camera = settings.camera();
  image.camera_size = cv::Size(camera.width, camera.height);
  if (image.grey.empty() || image.grey.type() != CV_8UC1) {
    image.first.status = Status::EmptyFrame;
    return;
  }
  if (image.grey.cols != camera.width || image.grey.rows != camera.height) {
    image.first.status = Status::FrameSizeMismatch;
    return;
  }
  SpotFinderWorkspace finder;
  image.spot_status = findPatternSpots(image.grey, settings.pipeline.threshold, finder, image.spots);

  // The pattern's pose from its target as calibrate.h's targetPatternLocator finds it (each
  // image on its own, through the whole pipeline with distortion correction), keeping the
  // detected outline to show.
  Settings located = settings;
  located.pipeline.tracking.mode = TrackingMode::Off;
  located.pipeline.level = ApplicationLevel::Reconstruction;
  located.pipeline.reconstruction.distortion_correction = true;
  Engine engine(located);
  FrameResult result;
  const PatternLocator locate = [&](const cv::Mat& grey, const CameraModel& estimate, Pose& pose) {
    Settings current = located;
    current.camera() = estimate;
    engine.setSettings(current);
    engine.resetTracking();
    Frame frame;
    frame.image = grey;
    engine.process(frame, result);
    image.target_status = result.status;
    if (!result.targets.empty()) image.target = result.targets.front().ellipse;
    if (ok(result.status) && !result.pose) image.target_status = Status::NoTarget;
    if (ok(image.target_status)) pose = *result.pose;
    return image.target_status;
  };

  // The procedure's first iteration on this image alone: its report is what that iteration
  // will make of the image in the run (the fit of one image does not matter here).
  Settings once = settings;
  once.pipeline.calibration.max_iterations = 1;
  CalibrationResult first;
  calibrateDistortion(once, std::span<const cv::Mat>(&image.grey, 1), first, {}, locate);
  if (!first.images.empty()) image.first = first.images.front();
  if (image.target_status == Status::Stopped) {  // the spots failed first: show the target anyway
    CameraModel ideal = camera;
    ideal.distortion = {};
    Pose pose;
    locate(image.grey, ideal, pose);
  }
}

namespace {

// One decimal, without a "-0.0".
QString angle(double deg) { return QString::number(std::abs(deg) < 0.05 ? 0.0 : deg, 'f', 1); }

QString poseText(const Pose& p) {
  return QObject::tr("pattern at Rx %1, Ry %2, Rz %3 deg, Tz %4 mm")
      .arg(angle(p.rx_deg), angle(p.ry_deg), angle(p.rz_deg))
      .arg(p.tz_mm, 0, 'f', 0);
}

// What the user can do about an image's error.
QString remedy(const CalibrationImage& image, const CalibrationImageReport& r) {
  switch (r.status) {
    case Status::FrameSizeMismatch:
      return QObject::tr("The image is %1 x %2 px, the settings' camera %3 x %4: open an image of this camera or "
                         "change the camera in Settings.")
          .arg(image.grey.cols)
          .arg(image.grey.rows)
          .arg(image.camera_size.width)
          .arg(image.camera_size.height);
    case Status::TooFewMatches:
      return QObject::tr("Only %1 of %2 spots matched: the pattern's spots must fill the image around its target.")
          .arg(r.match.matched)
          .arg(r.spots_expected);
    case Status::MatchAmbiguity:
      return QObject::tr("%1 of %2 spots are ambiguous: the distortion is too strong for the spot spacing, or "
                         "spot-like marks lie next to the spots (thesis 4.3).")
          .arg(r.match.ambiguous)
          .arg(r.match.matched + r.match.ambiguous);
    default:
      break;
  }
  if (r.status == image.target_status)
    return QObject::tr("The pattern's pose comes from its target (thesis 4.6 step 3): the whole target must be in "
                       "view, near the image centre.");
  if (r.status == image.spot_status) return QObject::tr("The pattern's spots cannot be told from the sheet.");
  return {};
}

}  // namespace

QString calibrationImageSummary(const CalibrationImage& image, const CalibrationImageReport* run) {
  if (image.grey.empty())
    return QObject::tr("No image. Open a file, capture the running source's frame or render a virtual view.");
  const CalibrationImageReport& r = run ? *run : image.first;
  QString text;
  if (ok(r.status)) {
    text = run ? QObject::tr("Used: %1 of %2 spots matched in the last iteration (%3 ambiguous, %4 found), %5.")
               : QObject::tr("Ready: %1 of %2 spots matched with zero distortion (%3 ambiguous, %4 found), "
                             "target found, %5.");
    text = text.arg(r.match.matched).arg(r.spots_expected).arg(r.match.ambiguous).arg(r.spots_found).arg(poseText(r.pose));
  } else {
    text = (run ? QObject::tr("Left out of the calibration: %1.") : QObject::tr("Not usable: %1."))
               .arg(statusInWords(r.status));
    const QString hint = remedy(image, r);
    if (!hint.isEmpty()) text += QLatin1Char(' ') + hint;
  }
  return text;
}

}  // namespace imagepro::app
