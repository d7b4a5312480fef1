// IntrinsicsPage: the calibration run (off the GUI thread), Set and Use, and the files.
#include <QCheckBox>
#include <QDateTime>
#include <QFileDialog>
#include <QFileInfo>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QListWidget>
#include <QProgressBar>
#include <QPushButton>
#include <QTabWidget>
#include <QVBoxLayout>

#include "app/calibration_wizard/intrinsics_page.h"
#include "app/calibration_wizard/intrinsics_report_page.h"
#include "app/calibration_wizard/wizard_widgets.h"
#include "app/main_window/main_window.h"
#include "app/main_window/results_text.h"
#include "app/main_window/dialog_folder.h"
#include "core/calibration/opencv_camera_file.h"

namespace imagepro::app {

namespace {

QString cameraText(const CameraModel& c) {
  return QObject::tr("%1 x %2 px, d0 %3 mm for %4 mm pixels (fx %5, fy %6 px), principal point (%7, %8) px")
      .arg(c.width)
      .arg(c.height)
      .arg(c.image_plane_distance_mm, 0, 'f', 4)
      .arg(c.pixel_size_mm[0])
      .arg(c.fu(), 0, 'f', 2)
      .arg(c.fv(), 0, 'f', 2)
      .arg(c.u0(), 0, 'f', 2)
      .arg(c.v0(), 0, 'f', 2);
}

}  // namespace

QWidget* IntrinsicsPage::buildRunBox() {
  calibrate_ = wizardButton(tr("Calibrate"), QStringLiteral("calibrateIntrinsics"),
                            tr("Find the grid in every image, then fx, fy, the principal point and k1, k2, p1, p2 by "
                               "OpenCV's calibrateCamera, each dot's centre corrected for perspective"));
  cancel_ = wizardButton(tr("Cancel"), QStringLiteral("cancelIntrinsics"),
                         tr("Stop the calibration at its next image and drop it"));
  progress_ = wizardProgressBar(QStringLiteral("intrinsicsProgress"));
  run_status_ = wizardTextLabel(QStringLiteral("intrinsicsRunStatus"), 4);

  fit_k3_ = new QCheckBox(tr("Fit k3"));
  fit_k3_->setObjectName(QStringLiteral("fitK3"));
  fit_k3_->setToolTip(tr("Also OpenCV's k3, for a strongly curved wide-angle lens; otherwise it stays 0 (as "
                         "calibrate --intrinsics without --fit-k3)"));
  QGroupBox* box = wizardRunBox(tr("Calibration"), calibrate_, cancel_, progress_, run_status_);
  auto* layout = static_cast<QVBoxLayout*>(box->layout());
  layout->insertWidget(0, fit_k3_);
  layout->addStretch(1);

  connect(calibrate_, &QPushButton::clicked, this, &IntrinsicsPage::calibrate);
  connect(cancel_, &QPushButton::clicked, this, &IntrinsicsPage::cancelCalibration);
  setRunStatus(tr("Describe the printed grid (or write one with Write pattern PDF), add 3 or more images of it (4 to "
                  "10 best, tilted 30-50 deg about different axes, the grid near every edge and corner once), then "
                  "Calibrate."),
               false);
  return box;
}

QWidget* IntrinsicsPage::buildActions() {
  set_and_use_ = wizardButton(tr("Set and Use"), QStringLiteral("setAndUseIntrinsics"),
                              tr("Give the camera found (size, d0 for the settings' pixel size, pixel aspect, "
                                 "principal point, distortion) to the settings' camera, and turn distortion "
                                 "correction on"));
  save_ = wizardButton(tr("Save calibration..."), QStringLiteral("saveIntrinsics"),
                       tr("Write the settings' camera section with the camera found, as imagepro-cli calibrate "
                          "--intrinsics --out does; an existing file is kept as .bak"));
  export_ = wizardButton(tr("Export OpenCV camera..."), QStringLiteral("exportOpenCvCamera"),
                         tr("OpenCV's camera file (camera_matrix, distortion_coefficients, image_width, image_height; "
                            "JSON for a .json name, else YAML) of the camera found, or of the settings' camera "
                            "before a calibration, for OpenCV and ROS tools"));
  auto* import = wizardButton(tr("Import OpenCV camera..."), QStringLiteral("importOpenCvCamera"),
                              tr("Take a camera calibrated elsewhere from OpenCV's camera file into the settings' "
                                 "camera (its distortion fitted to this project's model), and turn distortion "
                                 "correction on"));
  auto* close = new QPushButton(tr("Close"));
  close->setObjectName(QStringLiteral("closeIntrinsics"));

  auto* row = new QWidget;
  auto* layout = new QHBoxLayout(row);
  layout->setContentsMargins(0, 0, 0, 0);
  for (QPushButton* b : {set_and_use_, save_, export_, import}) layout->addWidget(b);
  layout->addStretch(1);
  layout->addWidget(close);

  connect(set_and_use_, &QPushButton::clicked, this, &IntrinsicsPage::setAndUse);
  connect(save_, &QPushButton::clicked, this, [this] {
    const QString name = QStringLiteral("camera-calibration-%1.json")
                             .arg(QDateTime::currentDateTime().toString(QStringLiteral("yyyyMMdd-hhmmss")));
    const QString path = QFileDialog::getSaveFileName(this, tr("Save calibration"), dialogFolderWith(name),
                                                      tr("Settings (*.json);;All files (*)"));
    if (path.isEmpty()) return;
    rememberDialogFolder(path);
    saveCalibration(path);
  });
  connect(export_, &QPushButton::clicked, this, [this] {
    const QString path = QFileDialog::getSaveFileName(this, tr("Export OpenCV camera"),
                                                      dialogFolderWith(QStringLiteral("camera.yaml")),
                                                      tr("OpenCV camera (*.yaml *.yml *.json);;All files (*)"));
    if (path.isEmpty()) return;
    rememberDialogFolder(path);
    exportOpenCvCamera(path);
  });
  connect(import, &QPushButton::clicked, this, [this] {
    const QString path = QFileDialog::getOpenFileName(this, tr("Import OpenCV camera"), dialogFolder(),
                                                      tr("OpenCV camera (*.yaml *.yml *.json);;All files (*)"));
    if (path.isEmpty()) return;
    rememberDialogFolder(path);
    importOpenCvCamera(path);
  });
  connect(close, &QPushButton::clicked, this, &IntrinsicsPage::closeRequested);
  return row;
}

void IntrinsicsPage::calibrate() {
  if (isCalibrating()) return;
  const DotGridSpec s = spec();
  if (const std::string e = dotGridSpecError(s); !e.empty()) {
    setRunStatus(tr("Not calibrated: InvalidPattern: %1.").arg(QString::fromStdString(e)), true);
    return;
  }
  if (imageCount() < kMinIntrinsicViews) {
    setRunStatus(tr("Not calibrated: TooFewViews: %n image(s) set; at least %1 are needed, 4 to 10 best, tilted "
                    "differently.",
                    nullptr, imageCount())
                     .arg(kMinIntrinsicViews),
                 true);
    return;
  }
  std::vector<cv::Mat> images;
  run_ids_.clear();
  run_names_.clear();
  for (const Image& im : images_) {
    images.push_back(im.grey);
    run_ids_.push_back(im.id);
    run_names_ << im.origin;
  }
  result_.reset();
  report_->setResult(nullptr, {});
  refreshImages();
  const int n = imageCount();
  progress_->setRange(0, n + 1);  // each grid search, then the fit
  progress_->setValue(0);
  progress_->setFormat(tr("finding the grids"));
  setRunStatus(tr("Finding the grid in %n image(s)...", nullptr, n), false);

  IntrinsicsOptions options;
  options.fit_k3 = fit_k3_->isChecked();
  run_cancelled_ = std::make_shared<std::atomic<bool>>(false);
  run_ = startPoolRun<IntrinsicsRunUpdate>(
      this,
      [cancelled = run_cancelled_, images, s, options](QPromise<IntrinsicsRunUpdate>& promise) {
        auto result = std::make_shared<IntrinsicsResult>();
        calibrateIntrinsics(images, s, options, *result, [&](int searched, int total) {
          if (cancelled->load()) return false;
          promise.addResult(IntrinsicsRunUpdate{searched, total, nullptr});
          return true;
        });
        promise.addResult(IntrinsicsRunUpdate{0, 0, std::move(result)});
      },
      [this](const IntrinsicsRunUpdate& update) { onRunUpdate(update); });
  updateButtons();
}

void IntrinsicsPage::cancelCalibration() {
  if (!run_) return;
  run_cancelled_->store(true);
  releaseRun(run_, this);
  resetProgress(progress_);
  setRunStatus(tr("Cancelled: the calibration stops at its next image and its result is dropped."), false);
  updateButtons();
}

void IntrinsicsPage::onRunUpdate(const IntrinsicsRunUpdate& update) {
  if (!update.result) {
    progress_->setValue(update.searched);
    if (update.searched < update.images) {
      setRunStatus(tr("Finding the grid in image %1 of %2...").arg(update.searched + 1).arg(update.images), false);
    } else {
      progress_->setRange(0, 0);  // busy: the fit says nothing until it ends
      setRunStatus(tr("Fitting the intrinsics to the grids found (OpenCV's calibrateCamera, each dot's centre "
                      "corrected for perspective)..."),
                   false);
    }
    return;
  }
  result_ = update.result;
  releaseRun(run_, this);
  const IntrinsicsResult& r = *result_;
  const int steps = static_cast<int>(run_ids_.size()) + 1;
  progress_->setRange(0, steps);
  progress_->setValue(steps);
  progress_->setFormat(ok(r.status) ? tr("done") : tr("failed"));
  report_->setResult(&r, run_names_);
  refreshImages();
  if (ok(r.status)) {
    setRunStatus(tr("Calibrated from %1 of %2 images: fx %3 px, fy %4 px, principal point (%5, %6) px, reprojection "
                    "%7 px RMS; %n warning(s). The quality report is on its tab; Set and Use gives the camera to the "
                    "settings.",
                    nullptr, static_cast<int>(report_->warnings().size()))
                     .arg(r.views_used)
                     .arg(r.views.size())
                     .arg(r.fx, 0, 'f', 2)
                     .arg(r.fy, 0, 'f', 2)
                     .arg(r.cx, 0, 'f', 2)
                     .arg(r.cy, 0, 'f', 2)
                     .arg(r.rms_px, 0, 'f', 4),
                 false);
    tabs_->setCurrentWidget(report_);
  } else {
    int found = 0;
    for (const IntrinsicsView& v : r.views) found += v.found.empty() ? 0 : 1;
    setRunStatus(tr("Calibration failed: %1. The grid was found in %2 of %3 images: check that the description "
                    "(kind, columns x rows) is the printed sheet's and see each image's message.")
                     .arg(statusInWords(r.status))
                     .arg(found)
                     .arg(r.views.size()),
                 true);
  }
  updateButtons();
  emit calibrationFinished(ok(r.status));
}

void IntrinsicsPage::setAndUse() {
  if (!result_ || !ok(result_->status)) return;
  Settings next = window_.settings();
  applyIntrinsics(*result_, next.camera());
  next.pipeline.reconstruction.distortion_correction = true;
  window_.setSettings(next);
  window_.calibrationInUse();
  setRunStatus(tr("Set and Use: the %1 source's camera is now %2, with its distortion; distortion correction is on.")
                   .arg(sourceKindLabel(next.source), cameraText(next.camera())),
               false);
}

bool IntrinsicsPage::saveCalibration(const QString& path) {
  if (!result_ || !ok(result_->status)) return false;
  Settings calibrated = window_.settings();
  applyIntrinsics(*result_, calibrated.camera());
  QString message;
  const bool saved = saveCameraSection(path, calibrated, message);
  if (saved) window_.calibrationSaved(calibrated);
  setRunStatus(message, !saved);
  return saved;
}

bool IntrinsicsPage::exportOpenCvCamera(const QString& path) {
  const bool found = result_ && ok(result_->status);
  const OpenCvCamera camera = found ? openCvCameraOf(*result_) : openCvCameraOf(window_.settings().camera());
  std::string error;
  if (!writeOpenCvCamera(path.toStdString(), camera, error)) {
    setRunStatus(tr("OpenCV camera not exported: %1").arg(QString::fromStdString(error)), true);
    return false;
  }
  setRunStatus(tr("Exported %1 to %2 (OpenCV's camera file).")
                   .arg(found ? tr("the camera found") : tr("the settings' camera"), path),
               false);
  return true;
}

bool IntrinsicsPage::importOpenCvCamera(const QString& path) {
  OpenCvCamera camera;
  std::string error;
  if (!readOpenCvCamera(path.toStdString(), camera, error)) {
    setRunStatus(tr("Not imported: %1").arg(QString::fromStdString(error)), true);
    return false;
  }
  Settings next = window_.settings();
  double fit_px = 0.0;
  applyOpenCvCamera(camera, next.camera(), &fit_px);
  next.pipeline.reconstruction.distortion_correction = true;
  window_.setSettings(next);
  window_.calibrationInUse();
  setRunStatus(tr("Imported %1: the settings' camera is now %2; its distortion in this project's model within %3 px "
                  "RMS of OpenCV's; distortion correction is on.")
                   .arg(QFileInfo(path).fileName(), cameraText(next.camera()))
                   .arg(fit_px, 0, 'f', 4),
               false);
  return true;
}

void IntrinsicsPage::setRunStatus(const QString& text, bool error) {
  showStatusText(run_status_, text, error);
}

QString IntrinsicsPage::runStatus() const { return run_status_->text(); }

void IntrinsicsPage::updateButtons() {
  calibrate_->setEnabled(!isCalibrating());
  cancel_->setEnabled(isCalibrating());
  remove_->setEnabled(imageCount() > 0);
  clear_->setEnabled(imageCount() > 0);
  const bool found = result_ && ok(result_->status);
  set_and_use_->setEnabled(found);
  save_->setEnabled(found);
}

}  // namespace imagepro::app
