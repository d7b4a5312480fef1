#include "app/calibration_wizard/d0_dialog.h"

#include <QChart>
#include <QChartView>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineSeries>
#include <QPushButton>
#include <QSpinBox>
#include <QTableWidget>
#include <QValueAxis>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>

#include "app/calibration_wizard/calibration_images.h"
#include "app/main_window/main_window.h"
#include "app/main_window/owned_dialog.h"
#include "app/main_window/results_text.h"
#include "app/plots/chart_view.h"
#include "app/worker/worker.h"
#include "app/main_window/dialog_folder.h"
#include "core/source/virtual_renderer.h"

namespace imagepro::app {

namespace {

// The worker answers every listener's capture requests: this dialog's are numbered apart
// from the calibration wizard's.
constexpr quint64 kCaptureBase = quint64(1) << 62;

// A frame rendered for the dialog: the target a little turned, so the two spots and the rim
// are measured as in a real view.
constexpr Pose kVirtualView{10.0, -15.0, 20.0, 0.0, 0.0, 800.0};

enum Column { kFrame, kOrigin, kStatus, kIterations, kD0, kDepth, kKnown, kDepthError, kColumns };

QTableWidgetItem* cell(const QString& text) {
  auto* item = new QTableWidgetItem(text);
  item->setFlags(item->flags() & ~Qt::ItemIsEditable);
  return item;
}

}  // namespace

D0Dialog::D0Dialog(MainWindow& window) : QDialog(&window), window_(window) {
  setObjectName(QStringLiteral("d0Dialog"));
  setWindowTitle(tr("Image Plane Distance d0"));
  const double d0 = window_.settings().camera().image_plane_distance_mm;

  focal_ = new QDoubleSpinBox;
  focal_->setObjectName(QStringLiteral("d0FocalLength"));
  focal_->setRange(0.001, 10000.0);
  focal_->setDecimals(6);
  focal_->setSuffix(QStringLiteral(" mm"));
  focal_->setValue(d0);
  focal_->setToolTip(tr("The lens's focal length f: the iteration of thesis eq. 4.1 starts from d0 = f"));
  epsilon_ = new QDoubleSpinBox;
  epsilon_->setObjectName(QStringLiteral("d0Epsilon"));
  epsilon_->setRange(1e-9, 1.0);
  epsilon_->setDecimals(9);
  epsilon_->setSuffix(QStringLiteral(" mm"));
  epsilon_->setValue(D0Options{}.epsilon_mm);
  epsilon_->setToolTip(tr("Converged when d0 changes by less than this (thesis eq. 4.2)"));
  iterations_ = new QSpinBox;
  iterations_->setObjectName(QStringLiteral("d0MaxIterations"));
  iterations_->setRange(1, 1000);
  iterations_->setValue(D0Options{}.max_iterations);
  iterations_->setToolTip(tr("Give up (Diverged) after this many steps"));
  distance_ = new QDoubleSpinBox;
  distance_->setObjectName(QStringLiteral("d0KnownDistance"));
  distance_->setRange(0.0, 1e6);
  distance_->setDecimals(1);
  distance_->setSuffix(QStringLiteral(" mm"));
  distance_->setSpecialValueText(tr("not known"));
  distance_->setToolTip(tr("The target's measured distance from the camera for the next frame: its reconstructed "
                           "depth with the estimated d0 is compared with it (0: not known)"));
  for (QAbstractSpinBox* box : std::initializer_list<QAbstractSpinBox*>{focal_, epsilon_, iterations_, distance_})
    box->setKeyboardTracking(false);

  auto* options = new QFormLayout;
  options->addRow(tr("Focal length f"), focal_);
  options->addRow(tr("Epsilon"), epsilon_);
  options->addRow(tr("Max. iterations"), iterations_);
  options->addRow(tr("Known distance of the next frame"), distance_);

  auto button = [this](const QString& text, const char* name, const QString& tip) {
    auto* b = new QPushButton(text);
    b->setObjectName(QLatin1String(name));
    b->setToolTip(tip);
    return b;
  };
  auto* capture = button(tr("Capture Frame"), "d0Capture", tr("Take the running source's current frame"));
  auto* open = button(tr("Open Image..."), "d0Open", tr("Add an image of the target from a file"));
  auto* render = button(tr("Render Virtual"), "d0Render",
                        tr("Add the target rendered by the Virtual source at the known distance (800 mm when none) "
                           "with the settings' camera"));
  auto* clear = button(tr("Clear"), "d0Clear", tr("Remove every frame"));
  set_ = button(tr("Set d0"), "d0Set", tr("Give the mean d0 to the settings' camera"));
  auto* buttons = new QHBoxLayout;
  for (QPushButton* b : {capture, open, render, clear, set_}) buttons->addWidget(b);

  table_ = new QTableWidget(0, kColumns);
  table_->setObjectName(QStringLiteral("d0Table"));
  table_->setHorizontalHeaderLabels({tr("Frame"), tr("Origin"), tr("Status"), tr("Iterations"), tr("d0 (mm)"),
                                     tr("Depth (mm)"), tr("Known (mm)"), tr("Depth - known (mm)")});
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->horizontalHeader()->setSectionResizeMode(kOrigin, QHeaderView::Stretch);
  table_->verticalHeader()->hide();
  summary_ = new QLabel;
  summary_->setObjectName(QStringLiteral("d0Summary"));
  summary_->setWordWrap(true);
  summary_->setTextInteractionFlags(Qt::TextSelectableByMouse);

  chart_ = new QChart;
  chart_->setTitle(tr("d0 at each step of eq. 4.1"));
  axis_x_ = new QValueAxis;
  axis_x_->setTitleText(tr("iteration"));
  axis_x_->setLabelFormat(QStringLiteral("%d"));
  axis_y_ = new QValueAxis;
  axis_y_->setTitleText(tr("d0 (mm)"));
  chart_->addAxis(axis_x_, Qt::AlignBottom);
  chart_->addAxis(axis_y_, Qt::AlignLeft);
  chart_->legend()->setAlignment(Qt::AlignBottom);
  auto* chart_box = new QWidget;
  chart_box->setMinimumHeight(260);
  fillWithChart(chart_box, chart_);

  auto* layout = new QVBoxLayout(this);
  auto* note = new QLabel(tr("Thesis 4.1: hold the target still at a measured distance, take a frame, repeat at other "
                             "distances. Each frame's d0 comes from the iteration d0(i+1) = d f / (d - f) from d0(1) = f, "
                             "d being the depth reconstructed with d0(i)."));
  note->setWordWrap(true);
  layout->addWidget(note);
  layout->addLayout(options);
  layout->addLayout(buttons);
  layout->addWidget(table_, 1);
  layout->addWidget(summary_);
  layout->addWidget(chart_box, 2);

  connect(capture, &QPushButton::clicked, this, &D0Dialog::captureFrame);
  connect(open, &QPushButton::clicked, this, [this] {
    const QString path = QFileDialog::getOpenFileName(this, tr("Open an image of the target"), dialogFolder(),
                                                      tr("Images (*.png *.pgm *.bmp *.jpg *.jpeg *.tif *.tiff);;All files (*)"));
    if (path.isEmpty()) return;
    rememberDialogFolder(path);
    openImage(path);
  });
  connect(render, &QPushButton::clicked, this, &D0Dialog::renderVirtual);
  connect(clear, &QPushButton::clicked, this, &D0Dialog::clearFrames);
  connect(set_, &QPushButton::clicked, this, &D0Dialog::setAndUse);
  for (QDoubleSpinBox* box : {focal_, epsilon_})
    connect(box, &QDoubleSpinBox::valueChanged, this, &D0Dialog::estimateAll);
  connect(iterations_, &QSpinBox::valueChanged, this, &D0Dialog::estimateAll);
  connect(window_.worker(), &Worker::frameCaptured, this, &D0Dialog::onFrameCaptured);
  refresh();
  resize(900, 760);
}

void D0Dialog::setFocalLength(double mm) { focal_->setValue(mm); }
void D0Dialog::setKnownDistance(double mm) { distance_->setValue(mm); }

void D0Dialog::addFrame(const cv::Mat& grey, const QString& origin) {
  Entry e;
  e.grey = grey;
  e.origin = origin;
  e.distance_mm = distance_->value();
  entries_.push_back(std::move(e));
  estimateAll();
}

bool D0Dialog::openImage(const QString& path) {
  cv::Mat grey;
  QString error;
  if (!ok(readCalibrationImage(path, grey, error))) {
    summary_->setText(error);
    return false;
  }
  addFrame(grey, QFileInfo(path).fileName());
  return true;
}

void D0Dialog::captureFrame() {
  const quint64 request = kCaptureBase + ++next_capture_;
  pending_captures_[request] = true;
  window_.worker()->captureFrame(request);
}

void D0Dialog::onFrameCaptured(quint64 request, const cv::Mat& grey, const QString& source, bool) {
  if (pending_captures_.erase(request) == 0) return;
  if (grey.empty()) {
    summary_->setText(tr("Nothing to capture: start the Camera or Virtual source with the target in view (or open "
                         "a file) first."));
    return;
  }
  addFrame(grey, tr("Captured from %1").arg(source));
}

void D0Dialog::renderVirtual() {
  const Settings& s = window_.settings();
  Pose pose = kVirtualView;
  if (distance_->value() > 0.0) pose.tz_mm = distance_->value();
  cv::Mat grey;
  renderTarget(s.camera(), s.target, s.virtual_scene, pose, grey, entries_.size() + 1);
  addFrame(grey, tr("Virtual, d0 %1 mm, %2 mm away").arg(s.camera().image_plane_distance_mm).arg(pose.tz_mm));
}

void D0Dialog::clearFrames() {
  entries_.clear();
  refresh();
}

D0Summary D0Dialog::summary() const {
  std::vector<double> d0;
  for (const Entry& e : entries_)
    if (ok(e.estimate.status)) d0.push_back(e.estimate.estimate.d0_mm);
  return summarizeD0(d0);
}

bool D0Dialog::setAndUse() {
  const D0Summary s = summary();
  if (s.count == 0) return false;
  Settings next = window_.settings();
  next.camera().image_plane_distance_mm = s.mean_mm;
  window_.setSettings(next);
  window_.calibrationInUse();
  summary_->setText(summaryText() + QLatin1Char(' ') + tr("The settings' camera now has d0 = %1 mm.").arg(s.mean_mm, 0, 'f', 6));
  return true;
}

void D0Dialog::estimateAll() {
  const D0Options options{focal_->value(), epsilon_->value(), iterations_->value()};
  D0Estimator estimator(window_.settings(), options);
  FrameResult result;
  for (Entry& e : entries_) {
    Frame frame;
    frame.image = e.grey;
    estimator.process(frame, result, e.estimate);
  }
  refresh();
}

QString D0Dialog::summaryText() const {
  const D0Summary s = summary();
  if (entries_.empty()) return tr("No frames yet.");
  if (s.count == 0) return tr("No frame gave an estimate of d0.");
  return tr("d0 = %1 mm, mean of %2 of %3 frames, standard deviation %4 mm.")
      .arg(s.mean_mm, 0, 'f', 6)
      .arg(s.count)
      .arg(entries_.size())
      .arg(s.sd_mm, 0, 'f', 6);
}

void D0Dialog::refresh() {
  table_->setRowCount(static_cast<int>(entries_.size()));
  chart_->removeAllSeries();
  double lo = 1e300, hi = -1e300;
  int steps = 1;
  for (size_t i = 0; i < entries_.size(); ++i) {
    const Entry& e = entries_[i];
    const int row = static_cast<int>(i);
    const ImagePlaneDistanceEstimate& est = e.estimate.estimate;
    const bool good = ok(e.estimate.status);
    table_->setItem(row, kFrame, cell(QString::number(i + 1)));
    table_->setItem(row, kOrigin, cell(e.origin));
    table_->setItem(row, kStatus, cell(statusInWords(e.estimate.status)));
    table_->setItem(row, kIterations, cell(good ? QString::number(est.iterations) : QString()));
    table_->setItem(row, kD0, cell(good ? QString::number(est.d0_mm, 'f', 6) : QString()));
    table_->setItem(row, kDepth, cell(good ? QString::number(est.depth_mm, 'f', 2) : QString()));
    table_->setItem(row, kKnown, cell(e.distance_mm > 0.0 ? QString::number(e.distance_mm, 'f', 1) : QString()));
    table_->setItem(row, kDepthError,
                    cell(good && e.distance_mm > 0.0 ? QString::number(est.depth_mm - e.distance_mm, 'f', 2) : QString()));
    // The steps of the iteration, also of one that did not converge (Diverged shows why).
    if (est.history_mm.empty()) continue;
    auto* series = new QLineSeries;
    series->setName(tr("frame %1").arg(i + 1));
    for (size_t k = 0; k < est.history_mm.size(); ++k) {
      series->append(static_cast<double>(k + 1), est.history_mm[k]);
      lo = std::min(lo, est.history_mm[k]);
      hi = std::max(hi, est.history_mm[k]);
    }
    steps = std::max(steps, static_cast<int>(est.history_mm.size()));
    series->setPointsVisible(true);
    chart_->addSeries(series);
    series->attachAxis(axis_x_);
    series->attachAxis(axis_y_);
  }
  axis_x_->setRange(1, std::max(2, steps));
  axis_x_->setTickCount(std::min(std::max(2, steps), 11));
  if (lo <= hi) {
    const double pad = std::max(1e-6, 0.05 * (hi - lo));
    axis_y_->setRange(lo - pad, hi + pad);
  }
  summary_->setText(summaryText());
  set_->setEnabled(summary().count > 0);
  emit framesChanged();
}

D0Dialog& showD0Dialog(MainWindow& window) { return showOwnedDialog<D0Dialog>(window); }

}  // namespace imagepro::app
