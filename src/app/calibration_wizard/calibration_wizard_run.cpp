// CalibrationWizard: the calibration run (off the GUI thread), its iterations, the
// distortion field found, Set and Use, and the calibration file.
#include <QDateTime>
#include <QFileDialog>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>

#include "app/calibration_wizard/calibration_views.h"
#include "app/calibration_wizard/calibration_wizard.h"
#include "app/calibration_wizard/wizard_widgets.h"
#include "app/main_window/main_window.h"
#include "app/main_window/results_text.h"
#include "app/main_window/dialog_folder.h"

namespace imagepro::app {

namespace {

QString distortionText(const Distortion& d) {
  return QObject::tr("k1 %1 px^-2, k2 %2 px^-4, p1 %3 px^-1, p2 %4 px^-1")
      .arg(d.k1, 0, 'e', 4)
      .arg(d.k2, 0, 'e', 4)
      .arg(d.p1, 0, 'e', 4)
      .arg(d.p2, 0, 'e', 4);
}

// What to do about a failed run.
QString runRemedy(Status status) {
  switch (status) {
    case Status::Diverged:
      return QObject::tr("The estimate stopped being a plausible lens, or did not settle within the iterations "
                         "allowed: check each image's matches.");
    case Status::PoorCoverage:
      return QObject::tr("The matched spots reach only %1 of the way to the image's corners (at least 0.6 is needed "
                         "to calibrate the corners): move the pattern closer or print it larger.");
    case Status::DegenerateFit:
      return QObject::tr("The matched spots do not determine k1, k2, p1 and p2: use more images, with the pattern "
                         "filling each one.");
    default:
      return QObject::tr("No image was usable: see each image's message.");
  }
}

}  // namespace

QWidget* CalibrationWizard::buildRunColumn() {
  calibrate_ = wizardButton(
      tr("Calibrate"), QStringLiteral("calibrate"),
      tr("Lens distortion calibration (thesis 4.6): from zero distortion, reconstruct each image's pattern pose from "
         "its target, match the spots' ideal and seen positions, and fit k1, k2, p1, p2 by least squares (eqs. "
         "4.8-4.9), until every parameter changes by less than the relative change limit"));
  cancel_ = wizardButton(tr("Cancel"), QStringLiteral("cancelCalibration"),
                         tr("Stop waiting for the calibration (thesis 4.6); it ends in the background and its result "
                            "is dropped"));
  progress_ = wizardProgressBar(QStringLiteral("calibrationProgress"));
  run_status_ = wizardTextLabel(QStringLiteral("calibrationRunStatus"), 3);

  table_ = new QTableWidget(0, 9);
  table_->setObjectName(QStringLiteral("calibrationIterations"));
  const QStringList headers{tr("It."), tr("k1"), tr("k2"), tr("p1"), tr("p2"), tr("Change"), tr("RMS px"),
                            tr("Spots"), tr("Images")};
  const QStringList header_tips{tr("Iteration"),
                                tr("Radial distortion k1, px^-2"),
                                tr("Radial distortion k2, px^-4"),
                                tr("Tangential distortion p1, px^-1"),
                                tr("Tangential distortion p2, px^-1"),
                                tr("Largest relative change of a parameter against the iteration before (step 8)"),
                                tr("RMS residual of the fit over the matched spots, px"),
                                tr("Spots matched over every image used"),
                                tr("Images used")};
  for (int c = 0; c < headers.size(); ++c) {
    auto* item = new QTableWidgetItem(headers[c]);
    item->setToolTip(header_tips[c]);
    table_->setHorizontalHeaderItem(c, item);
  }
  table_->setToolTip(tr("Every iteration of thesis 4.6 steps 3-7 as it ends: the parameters found (eq. 4.7), their "
                        "largest relative change (step 8), the RMS residual of the fit, the spots matched and the "
                        "images used"));
  table_->verticalHeader()->hide();
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->setMinimumHeight(150);

  QGroupBox* run_box = wizardRunBox(tr("Calibration (thesis 4.6)"), calibrate_, cancel_, progress_, run_status_);
  static_cast<QVBoxLayout*>(run_box->layout())->addWidget(table_, 1);

  field_ = new DistortionFieldView;
  field_->setObjectName(QStringLiteral("distortionField"));
  field_->setToolTip(tr("Where the lens moves each point of the image (thesis eq. 4.7): arrows from the undistorted "
                        "position, lengthened by the factor shown; + is the principal point"));
  field_caption_ = wizardTextLabel(QStringLiteral("distortionFieldCaption"), 3);
  set_and_use_ = wizardButton(tr("Set and Use"), QStringLiteral("setAndUse"),
                              tr("Give the distortion found by the calibration (thesis 4.6) to the settings' camera, "
                                 "which every source uses, and turn distortion correction (thesis 4.5) on"));
  save_ = wizardButton(tr("Save calibration..."), QStringLiteral("saveCalibration"),
                       tr("Write the camera with the distortion found (thesis 4.6) as a settings file of its camera "
                          "section alone, as imagepro-cli calibrate does; an existing file is kept as .bak"));
  auto* close = new QPushButton(tr("Close"));
  close->setObjectName(QStringLiteral("closeCalibration"));
  auto* field_box = new QGroupBox(tr("Distortion field (thesis eq. 4.7)"));
  auto* field_layout = new QVBoxLayout(field_box);
  field_layout->addWidget(field_, 1);
  field_layout->addWidget(field_caption_);

  auto* buttons = new QHBoxLayout;
  buttons->addWidget(set_and_use_);
  buttons->addWidget(save_);
  buttons->addStretch(1);
  buttons->addWidget(close);

  auto* column = new QWidget;
  auto* layout = new QVBoxLayout(column);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(run_box, 1);
  layout->addWidget(field_box, 1);
  layout->addLayout(buttons);

  connect(calibrate_, &QPushButton::clicked, this, &CalibrationWizard::calibrate);
  connect(cancel_, &QPushButton::clicked, this, &CalibrationWizard::cancelCalibration);
  connect(set_and_use_, &QPushButton::clicked, this, &CalibrationWizard::setAndUse);
  connect(save_, &QPushButton::clicked, this, [this] {
    const QString name = QStringLiteral("camera-calibration-%1.json")
                             .arg(QDateTime::currentDateTime().toString(QStringLiteral("yyyyMMdd-hhmmss")));
    const QString path = QFileDialog::getSaveFileName(this, tr("Save calibration"), dialogFolderWith(name),
                                                      tr("Settings (*.json);;All files (*)"));
    if (path.isEmpty()) return;
    rememberDialogFolder(path);
    saveCalibration(path);
  });
  connect(close, &QPushButton::clicked, this, &QDialog::close);
  setRunStatus(tr("Set up one to four images of the pattern, best four turned about +-45 deg about x and y with "
                  "the target near the image centre (thesis 4.6 step 1), then Calibrate."),
               false);
  return column;
}

void CalibrationWizard::calibrate() {
  if (isCalibrating()) return;
  std::vector<cv::Mat> images;
  run_slots_.clear();
  run_generations_.clear();
  for (int i = 0; i < kCalibrationSlots; ++i) {
    const Slot& s = slots_[static_cast<size_t>(i)];
    if (s.image.grey.empty()) continue;
    images.push_back(s.image.grey);
    run_slots_.push_back(i);
    run_generations_.push_back(s.generation);
  }
  if (images.empty()) {
    setRunStatus(tr("No images to calibrate from: set up at least one image of the pattern."), true);
    return;
  }
  const Settings settings = window_.settings();
  run_options_ = settings.pipeline.calibration;
  result_.reset();
  table_->setRowCount(0);
  for (int i = 0; i < kCalibrationSlots; ++i) refreshSlot(i);
  progress_->setRange(0, 0);  // busy until the first iteration ends (it finds every spot)
  progress_->setFormat(QString());
  setRunStatus(tr("Calibrating from %n image(s): finding the spots and each pattern's pose...", nullptr,
                  static_cast<int>(images.size())),
               false);

  // The task owns copies of everything it reads and writes only to the promise, so the
  // wizard may be cancelled, closed or deleted while it runs.
  run_ = startPoolRun<CalibrationRunUpdate>(
      this,
      [settings, images](QPromise<CalibrationRunUpdate>& promise) {
        auto result = std::make_shared<CalibrationResult>();
        calibrateDistortion(settings, images, *result, [&promise](const CalibrationIteration& it) {
          promise.addResult(CalibrationRunUpdate{it, nullptr});
        });
        promise.addResult(CalibrationRunUpdate{std::nullopt, std::move(result)});
      },
      [this](const CalibrationRunUpdate& update) { onRunUpdate(update); });
  updateButtons();
}

void CalibrationWizard::cancelCalibration() {
  if (!run_) return;
  releaseRun(run_, this);
  resetProgress(progress_);
  setRunStatus(tr("Cancelled: the calibration ends in the background and its result is dropped."), false);
  updateButtons();
}

void CalibrationWizard::onRunUpdate(const CalibrationRunUpdate& update) {
  if (update.iteration) {
    const CalibrationIteration& it = *update.iteration;
    addIterationRow(it);
    progress_->setRange(0, run_options_.max_iterations);
    progress_->setValue(std::min(it.iteration, run_options_.max_iterations));
    progress_->setFormat(tr("iteration %v of at most %m"));
    setRunStatus(tr("Iteration %1: relative change %2 (converged below %3), RMS residual %4 px.")
                     .arg(it.iteration)
                     .arg(it.relative_change, 0, 'f', 4)
                     .arg(run_options_.relative_change)
                     .arg(it.rms_residual_px, 0, 'f', 4),
                 false);
    return;
  }
  if (!update.result) return;
  result_ = update.result;
  releaseRun(run_, this);
  const CalibrationResult& r = *result_;
  progress_->setRange(0, std::max(1, run_options_.max_iterations));
  progress_->setValue(ok(r.status) ? progress_->maximum() : r.iterations);
  progress_->setFormat(ok(r.status) ? tr("converged") : tr("failed"));
  int used = 0;
  for (const CalibrationImageReport& im : r.images) used += ok(im.status) ? 1 : 0;
  if (ok(r.status)) {
    setRunStatus(tr("Converged after %1 iterations: RMS residual %2 px over %3 spots in %4 of %5 images. "
                    "Set and Use gives the distortion to the settings' camera.")
                     .arg(r.iterations)
                     .arg(r.rms_residual_px, 0, 'f', 4)
                     .arg(r.history.empty() ? 0 : r.history.back().matches)
                     .arg(used)
                     .arg(r.images.size()),
                 false);
  } else {
    QString remedy = runRemedy(r.status);
    if (r.status == Status::PoorCoverage) remedy = remedy.arg(r.coverage_radius_fraction, 0, 'f', 2);
    setRunStatus(tr("Calibration failed: %1. %2").arg(statusInWords(r.status), remedy), true);
  }
  for (int i = 0; i < kCalibrationSlots; ++i) refreshSlot(i);
  showField();
  updateButtons();
  emit calibrationFinished(ok(r.status));
}

void CalibrationWizard::addIterationRow(const CalibrationIteration& it) {
  const int row = table_->rowCount();
  table_->insertRow(row);
  const QStringList cells{QString::number(it.iteration),
                          QString::number(it.distortion.k1, 'e', 4),
                          QString::number(it.distortion.k2, 'e', 4),
                          QString::number(it.distortion.p1, 'e', 4),
                          QString::number(it.distortion.p2, 'e', 4),
                          QString::number(it.relative_change, 'f', 4),
                          QString::number(it.rms_residual_px, 'f', 4),
                          QString::number(it.matches),
                          QString::number(it.images_used)};
  for (int c = 0; c < cells.size(); ++c) {
    auto* item = new QTableWidgetItem(cells[c]);
    item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    table_->setItem(row, c, item);
  }
  table_->scrollToBottom();
}

void CalibrationWizard::showField() {
  const CameraModel& camera = window_.settings().camera();
  const Distortion d = result_ ? result_->distortion : camera.distortion;
  field_->setField(camera, d);
  const QString what = !result_                ? tr("In the settings now (not calibrated here yet)")
                       : ok(result_->status) ? tr("Found")
                                             : tr("Last estimate of the failed run");
  QString caption = tr("%1: %2.").arg(what, distortionText(d));
  if (field_->arrowScale() > 0.0)
    caption += tr(" Largest displacement %1 px over the %2 x %3 image; arrows drawn %4 times their length.")
                   .arg(field_->largestDisplacementPx(), 0, 'f', 2)
                   .arg(camera.width)
                   .arg(camera.height)
                   .arg(field_->arrowScale());
  else if (field_->largestDisplacementPx() > 0.0)
    caption += tr(" Largest displacement %1 px: no distortion to speak of (below %2 px), so no arrows are drawn.")
                   .arg(field_->largestDisplacementPx(), 0, 'g', 2)
                   .arg(DistortionFieldView::kNegligiblePx);
  else
    caption += tr(" No displacement.");
  field_caption_->setText(caption);
}

void CalibrationWizard::setAndUse() {
  if (!result_ || !ok(result_->status)) return;
  Settings next = window_.settings();
  next.camera().distortion = result_->distortion;
  next.pipeline.reconstruction.distortion_correction = true;
  window_.setSettings(next);
  window_.calibrationInUse();
  setRunStatus(tr("Set and Use: the %1 source's camera now has %2, and distortion correction is on.")
                   .arg(sourceKindLabel(next.source), distortionText(result_->distortion)),
               false);
}

bool CalibrationWizard::saveCalibration(const QString& path) {
  if (!result_ || !ok(result_->status)) return false;
  Settings calibrated = window_.settings();
  calibrated.camera().distortion = result_->distortion;
  QString message;
  const bool saved = saveCameraSection(path, calibrated, message);
  if (saved) window_.calibrationSaved(calibrated);
  setRunStatus(message, !saved);
  return saved;
}

void CalibrationWizard::setRunStatus(const QString& text, bool error) {
  showStatusText(run_status_, text, error);
}

QString CalibrationWizard::runStatus() const { return run_status_->text(); }

void CalibrationWizard::updateButtons() {
  bool any = false;
  for (const Slot& s : slots_) any = any || !s.image.grey.empty();
  calibrate_->setEnabled(any && !isCalibrating());
  cancel_->setEnabled(isCalibrating());
  const bool found = result_ && ok(result_->status);
  set_and_use_->setEnabled(found);
  save_->setEnabled(found);
}

void CalibrationWizard::showEvent(QShowEvent* event) {
  if (!result_) showField();  // the settings may have changed while the window was closed
  QDialog::showEvent(event);
}

}  // namespace imagepro::app
