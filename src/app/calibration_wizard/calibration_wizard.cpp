// CalibrationWizard: the window and its four image slots (open, capture, render, analyse).
#include "app/calibration_wizard/calibration_wizard.h"

#include <QFileDialog>
#include <QFileInfo>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPromise>
#include <QPushButton>
#include <QRadioButton>
#include <QSpinBox>
#include <QStackedWidget>
#include <QThreadPool>
#include <QVBoxLayout>

#include "app/calibration_wizard/calibration_views.h"
#include "app/calibration_wizard/intrinsics_page.h"
#include "app/calibration_wizard/wizard_widgets.h"
#include "app/main_window/main_window.h"
#include "app/main_window/owned_dialog.h"
#include "app/worker/packet_builder.h"
#include "app/worker/worker.h"
#include "app/main_window/dialog_folder.h"

namespace imagepro::app {

namespace {

QString viewName(int slot) {
  const Pose v = virtualCalibrationView(slot);
  return v.rx_deg != 0.0 ? QObject::tr("Rx %1%2 deg").arg(v.rx_deg > 0 ? "+" : "").arg(v.rx_deg)
                         : QObject::tr("Ry %1%2 deg").arg(v.ry_deg > 0 ? "+" : "").arg(v.ry_deg);
}

CalibrationOverlay overlayOf(const CalibrationImage& image, const CalibrationImageReport& report) {
  CalibrationOverlay o;
  o.target = image.target;
  o.spots.reserve(image.spots.size());
  for (const ObservedSpot& s : image.spots) o.spots.emplace_back(s.centre.x(), s.centre.y());
  for (const SpotCorrespondence& c : report.correspondences) {
    o.ideal.emplace_back(c.ideal_px.x(), c.ideal_px.y());
    o.seen.emplace_back(c.seen_px.x(), c.seen_px.y());
  }
  return o;
}

}  // namespace

CalibrationWizard::CalibrationWizard(MainWindow& window) : QDialog(&window), window_(window) {
  setObjectName(QStringLiteral("calibrationWizard"));
  setWindowTitle(tr("Internal Camera Calibration"));
  setToolTip(QString());
  intrinsics_ = new IntrinsicsPage(window_);
  pages_ = new QStackedWidget;
  pages_->setObjectName(QStringLiteral("calibrationModePages"));
  pages_->addWidget(buildDistortionPage());
  pages_->addWidget(intrinsics_);
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(buildModeChoice());
  layout->addWidget(pages_, 1);

  connect(window_.worker(), &Worker::frameCaptured, this, &CalibrationWizard::onFrameCaptured);
  connect(intrinsics_, &IntrinsicsPage::captureRequested, this, [this] {
    const quint64 request = ++next_capture_;
    pending_captures_[request] = kIntrinsicsCapture;
    window_.worker()->captureFrame(request);
  });
  connect(intrinsics_, &IntrinsicsPage::closeRequested, this, &QDialog::close);
  for (int i = 0; i < kCalibrationSlots; ++i) refreshSlot(i);
  showField();
  updateButtons();
  resize(1400, 900);
}

QWidget* CalibrationWizard::buildModeChoice() {
  distortion_mode_ = new QRadioButton(tr("Distortion only (thesis 4.6)"));
  distortion_mode_->setObjectName(QStringLiteral("distortionMode"));
  distortion_mode_->setToolTip(tr("The thesis's procedure: k1, k2, p1, p2 from up to four images of the thesis "
                                  "pattern, with d0, the pixel size and the principal point known"));
  intrinsics_mode_ = new QRadioButton(tr("Full intrinsics (focal length, principal point, distortion)"));
  intrinsics_mode_->setObjectName(QStringLiteral("intrinsicsMode"));
  intrinsics_mode_->setToolTip(tr("A camera nothing is known about (a webcam): fx, fy, the principal point and the "
                                  "distortion from 3 or more images of a printed dot grid"));
  distortion_mode_->setChecked(true);
  auto* box = new QGroupBox(tr("What to calibrate"));
  auto* row = new QHBoxLayout(box);
  row->addWidget(distortion_mode_);
  row->addWidget(intrinsics_mode_);
  row->addStretch(1);
  connect(intrinsics_mode_, &QRadioButton::toggled, this, [this](bool on) {
    setMode(on ? CalibrationMode::Intrinsics : CalibrationMode::Distortion);
  });
  return box;
}

void CalibrationWizard::setMode(CalibrationMode mode) {
  const bool intrinsics = mode == CalibrationMode::Intrinsics;
  (intrinsics ? intrinsics_mode_ : distortion_mode_)->setChecked(true);
  pages_->setCurrentIndex(intrinsics ? 1 : 0);
}

CalibrationMode CalibrationWizard::mode() const {
  return pages_->currentIndex() == 1 ? CalibrationMode::Intrinsics : CalibrationMode::Distortion;
}

QWidget* CalibrationWizard::buildDistortionPage() {
  auto* images = new QGridLayout;
  for (int i = 0; i < kCalibrationSlots; ++i) images->addWidget(buildSlot(i), i / 2, i % 2);

  match_scale_ = new QSpinBox;
  match_scale_->setObjectName(QStringLiteral("matchLineScale"));
  match_scale_->setRange(1, 50);
  match_scale_->setPrefix(QStringLiteral("x"));
  match_scale_->setToolTip(tr("Match lines drawn this many times their length (x1: as measured, as in thesis fig. 4.6)"));
  auto* legend = new QLabel(tr("<span style='color:#28dc3c'>&#9711;</span> target found &nbsp; "
                               "<span style='color:#00c8ff'>&#9675;</span> spots found (step 5) &nbsp; "
                               "<span style='color:#ff2828'>&#9679;</span> ideal positions (step 4) &nbsp; "
                               "<span style='color:#c8b400'>&#9472;</span> matches (step 6), drawn at length"));
  legend->setObjectName(QStringLiteral("calibrationLegend"));
  auto* legend_row = new QHBoxLayout;
  legend_row->addWidget(legend, 1);
  legend_row->addWidget(match_scale_);
  connect(match_scale_, &QSpinBox::valueChanged, this, [this](int factor) {
    for (Slot& s : slots_) s.view->setMatchScale(factor);
  });

  auto* left = new QVBoxLayout;
  left->addLayout(images, 1);
  left->addLayout(legend_row);
  auto* page = new QWidget;
  auto* layout = new QHBoxLayout(page);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addLayout(left, 5);
  layout->addWidget(buildRunColumn(), 4);
  return page;
}

CalibrationWizard::~CalibrationWizard() = default;

CalibrationWizard& showCalibrationWizard(MainWindow& window) { return showOwnedDialog<CalibrationWizard>(window); }

QWidget* CalibrationWizard::buildSlot(int i) {
  Slot& s = slots_[static_cast<size_t>(i)];
  auto* box = new QGroupBox(tr("Image %1").arg(i + 1));
  box->setObjectName(QStringLiteral("calibrationSlot%1").arg(i + 1));
  auto* open = wizardButton(tr("Open image..."), QStringLiteral("openImage%1").arg(i + 1),
                      tr("An image of the calibration pattern from a file (thesis 4.6 step 1)"));
  auto* capture = wizardButton(tr("Capture"), QStringLiteral("captureImage%1").arg(i + 1),
                         tr("The current frame of the running source, as in thesis appendix A.2.2 "
                            "(\"Set as Calibration Image\")"));
  auto* render = wizardButton(tr("Render virtual"), QStringLiteral("renderImage%1").arg(i + 1),
                        tr("The calibration pattern (thesis 4.3) drawn by the Virtual source through the settings' "
                           "lens, turned %1 as thesis 4.6 step 1 asks, its target %2 mm away on the optical axis")
                            .arg(viewName(i))
                            .arg(kVirtualCalibrationDistanceMm));
  s.clear = wizardButton(tr("Clear"), QStringLiteral("clearImage%1").arg(i + 1),
                   tr("Remove this image from the calibration (thesis appendix A: the check boxes)"));
  s.view = new CalibrationImageView;
  s.view->setObjectName(QStringLiteral("calibrationView%1").arg(i + 1));
  s.status = wizardTextLabel(QStringLiteral("slotStatus%1").arg(i + 1), 3);

  auto* buttons = new QHBoxLayout;
  for (QPushButton* b : {open, capture, render, s.clear}) buttons->addWidget(b);
  auto* layout = new QVBoxLayout(box);
  layout->addLayout(buttons);
  layout->addWidget(s.view, 1);
  layout->addWidget(s.status);

  connect(open, &QPushButton::clicked, this, [this, i] { chooseImageFile(i); });
  connect(capture, &QPushButton::clicked, this, [this, i] { captureFrame(i); });
  connect(render, &QPushButton::clicked, this, [this, i] { renderVirtual(i); });
  connect(s.clear, &QPushButton::clicked, this, [this, i] { clearImage(i); });
  return box;
}

CalibrationImageView* CalibrationWizard::imageView(int slot) const {
  return slot >= 0 && slot < kCalibrationSlots ? slots_[static_cast<size_t>(slot)].view : nullptr;
}

bool CalibrationWizard::hasImage(int slot) const {
  return slot >= 0 && slot < kCalibrationSlots && !slots_[static_cast<size_t>(slot)].image.grey.empty();
}

bool CalibrationWizard::isAnalysing() const {
  for (const Slot& s : slots_)
    if (s.busy) return true;
  return false;
}

QString CalibrationWizard::slotStatus(int slot) const {
  return slot >= 0 && slot < kCalibrationSlots ? slots_[static_cast<size_t>(slot)].status->text() : QString();
}

void CalibrationWizard::chooseImageFile(int slot) {
  const QString path = QFileDialog::getOpenFileName(
      this, tr("Calibration image %1").arg(slot + 1), dialogFolder(),
      tr("Images (*.png *.pgm *.ppm *.pnm *.bmp *.jpg *.jpeg *.tif *.tiff);;All files (*)"));
  if (path.isEmpty()) return;
  rememberDialogFolder(path);
  openImage(slot, path);
}

void CalibrationWizard::openImage(int slot, const QString& path) {
  if (slot < 0 || slot >= kCalibrationSlots) return;
  cv::Mat grey;
  QString error;
  const Status status = readCalibrationImage(path, grey, error);
  if (!ok(status)) {
    Slot& s = slots_[static_cast<size_t>(slot)];
    ++s.generation;  // whatever was on its way to the slot is not wanted any more
    s.busy = false;
    s.image = {};
    setSlotNote(slot, tr("Not read (%1): %2").arg(QString::fromUtf8(statusName(status).data()), error), true);
    emit imageReady(slot);
    return;
  }
  startAnalysis(slot, [grey](cv::Mat& out) { out = grey; }, QFileInfo(path).fileName());
}

void CalibrationWizard::renderVirtual(int slot) {
  if (slot < 0 || slot >= kCalibrationSlots) return;
  const Settings settings = window_.settings();
  startAnalysis(slot, [settings, slot](cv::Mat& out) { renderVirtualCalibrationImage(settings, slot, out); },
                tr("Virtual pattern, %1").arg(viewName(slot)));
}

void CalibrationWizard::captureFrame(int slot) {
  if (slot < 0 || slot >= kCalibrationSlots) return;
  const quint64 request = ++next_capture_;
  pending_captures_[request] = slot;
  setSlotNote(slot, tr("Asking the source for its frame..."), false);
  window_.worker()->captureFrame(request);
}

void CalibrationWizard::onFrameCaptured(quint64 request, const cv::Mat& grey, const QString& source, bool running) {
  const auto it = pending_captures_.find(request);
  if (it == pending_captures_.end()) return;
  const int slot = it->second;
  pending_captures_.erase(it);
  const QString origin = running ? tr("Captured from %1").arg(source)
                                 : tr("Captured from %1 (stopped: its last frame)").arg(source);
  if (slot == kIntrinsicsCapture) {
    intrinsics_->takeCapture(grey, origin);
    return;
  }
  if (grey.empty()) {
    setSlotNote(slot, tr("Nothing to capture: no source is running and no image is open. Start the Camera or "
                         "Virtual source with the pattern in view (or open a file) first."),
                true);
    emit imageReady(slot);
    return;
  }
  startAnalysis(slot, [grey](cv::Mat& out) { out = grey; }, origin);
}

void CalibrationWizard::clearImage(int slot) {
  if (slot < 0 || slot >= kCalibrationSlots) return;
  Slot& s = slots_[static_cast<size_t>(slot)];
  ++s.generation;
  s.busy = false;
  s.image = {};
  s.note.clear();
  refreshSlot(slot);
  updateButtons();
}

void CalibrationWizard::startAnalysis(int slot, std::function<void(cv::Mat&)> produce, const QString& origin) {
  Slot& s = slots_[static_cast<size_t>(slot)];
  const quint64 generation = ++s.generation;
  s.busy = true;
  setSlotNote(slot, tr("%1: finding the target and the spots...").arg(origin), false);

  const Settings settings = window_.settings();
  auto promise = std::make_shared<QPromise<CalibrationImage>>();
  auto* watcher = new QFutureWatcher<CalibrationImage>(this);
  connect(watcher, &QFutureWatcherBase::finished, this, [this, slot, generation, watcher] {
    watcher->deleteLater();
    Slot& s = slots_[static_cast<size_t>(slot)];
    if (s.generation != generation) return;  // replaced meanwhile
    s.busy = false;
    if (watcher->future().resultCount() == 0) {
      setSlotNote(slot, tr("The image could not be analysed."), true);
    } else {
      s.image = watcher->future().result();
      s.note.clear();
    }
    refreshSlot(slot);
    updateButtons();
    emit imageReady(slot);
  });
  watcher->setFuture(promise->future());
  promise->start();
  // The task owns copies of everything it reads: the window may be gone when it ends.
  QThreadPool::globalInstance()->start([promise, produce, settings, origin] {
    CalibrationImage image;
    image.origin = origin;
    produce(image.grey);
    analyseCalibrationImage(settings, image);
    promise->addResult(std::move(image));
    promise->finish();
  });
}

void CalibrationWizard::setSlotNote(int slot, const QString& text, bool error) {
  Slot& s = slots_[static_cast<size_t>(slot)];
  s.note = text;
  s.note_is_error = error;
  refreshSlot(slot);
}

const CalibrationImageReport* CalibrationWizard::runReport(int slot) const {
  if (!result_) return nullptr;
  for (size_t k = 0; k < run_slots_.size() && k < result_->images.size(); ++k)
    if (run_slots_[k] == slot && run_generations_[k] == slots_[static_cast<size_t>(slot)].generation)
      return &result_->images[k];
  return nullptr;
}

void CalibrationWizard::refreshSlot(int slot) {
  Slot& s = slots_[static_cast<size_t>(slot)];
  const CalibrationImage& image = s.image;
  const CalibrationImageReport* run = runReport(slot);
  if (image.grey.empty()) {
    s.view->setImage({}, tr("No image"));
  } else {
    s.view->setImage(displayImage(image.grey));
    s.view->setOverlay(overlayOf(image, run ? *run : image.first));
  }
  s.clear->setEnabled(!image.grey.empty());
  QString text = s.note;
  bool error = s.note_is_error;
  if (text.isEmpty()) {
    text = calibrationImageSummary(image, run);
    if (!image.grey.empty()) text = image.origin + QStringLiteral(". ") + text;
    error = !image.grey.empty() && !ok(run ? run->status : image.first.status);
  }
  showStatusText(s.status, text, error);
}

}  // namespace imagepro::app
