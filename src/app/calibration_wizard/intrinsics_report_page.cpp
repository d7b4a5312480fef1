#include "app/calibration_wizard/intrinsics_report_page.h"

#include <QGridLayout>
#include <QGroupBox>
#include <QHeaderView>
#include <QImage>
#include <QLabel>
#include <QListWidget>
#include <QTableWidget>
#include <QVBoxLayout>

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "app/calibration_wizard/calibration_views.h"
#include "app/calibration_wizard/wizard_widgets.h"
#include "app/main_window/results_text.h"

namespace imagepro::app {

namespace {

QTableWidget* table(const QString& name, const QStringList& headers, const QString& tooltip) {
  auto* t = new QTableWidget(0, static_cast<int>(headers.size()));
  t->setObjectName(name);
  t->setHorizontalHeaderLabels(headers);
  t->setToolTip(tooltip);
  t->verticalHeader()->hide();
  t->setEditTriggers(QAbstractItemView::NoEditTriggers);
  t->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  t->horizontalHeader()->setSectionResizeMode(0, QHeaderView::Stretch);  // the names take what is left
  return t;
}

void appendRow(QTableWidget* t, const QStringList& cells) {
  const int row = t->rowCount();
  t->insertRow(row);
  for (int c = 0; c < cells.size(); ++c) {
    auto* item = new QTableWidgetItem(cells[c]);
    if (c > 0) item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    t->setItem(row, c, item);
  }
}

QImage rgbImage(const cv::Mat& bgr) {
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  return QImage(rgb.data, rgb.cols, rgb.rows, static_cast<qsizetype>(rgb.step), QImage::Format_RGB888).copy();
}

QString number(double v, int decimals) { return QString::number(v, 'f', decimals); }

}  // namespace

IntrinsicsReportPage::IntrinsicsReportPage(QWidget* parent) : QWidget(parent) {
  summary_ = wizardTextLabel(QStringLiteral("intrinsicsSummary"), 3);
  images_ = table(QStringLiteral("intrinsicsImageTable"),
                  {tr("Image"), tr("Status"), tr("Dots"), tr("RMS px"), tr("Tilt deg")},
                  tr("Each image of the run: whether its grid was found and used, its dots, the reprojection error of "
                     "its dots (RMS, px) and how far the sheet was tilted from facing the camera"));
  parameters_ = table(QStringLiteral("intrinsicsParameterTable"), {tr("Parameter"), tr("Value"), tr("Std. dev.")},
                      tr("The intrinsics found, each with one standard deviation from the fit's covariance; the "
                         "distortion in OpenCV's normalised model"));
  coverage_ = new CalibrationImageView;
  coverage_->setObjectName(QStringLiteral("intrinsicsCoverage"));
  coverage_->setToolTip(tr("Where the dots fell in the image: 8 x 6 cells, green by the number of views with dots in "
                           "them, dark red where there were none; every dot used in its view's colour"));
  coverage_caption_ = wizardTextLabel(QStringLiteral("intrinsicsCoverageCaption"), 2);
  warning_list_ = new QListWidget;
  warning_list_->setObjectName(QStringLiteral("intrinsicsWarnings"));
  warning_list_->setWordWrap(true);
  warning_list_->setSpacing(3);
  warning_list_->setToolTip(tr("What the views leave poorly determined, by name, and what to do about it"));

  auto* images_box = new QGroupBox(tr("Reprojection error per image"));
  (new QVBoxLayout(images_box))->addWidget(images_);
  auto* parameters_box = new QGroupBox(tr("Parameters"));
  (new QVBoxLayout(parameters_box))->addWidget(parameters_);
  auto* coverage_box = new QGroupBox(tr("Coverage map"));
  auto* coverage_layout = new QVBoxLayout(coverage_box);
  coverage_layout->addWidget(coverage_, 1);
  coverage_layout->addWidget(coverage_caption_);
  auto* warnings_box = new QGroupBox(tr("Warnings"));
  (new QVBoxLayout(warnings_box))->addWidget(warning_list_);

  auto* grid = new QGridLayout;
  grid->addWidget(images_box, 0, 0);
  grid->addWidget(parameters_box, 0, 1);
  grid->addWidget(coverage_box, 1, 0);
  grid->addWidget(warnings_box, 1, 1);
  grid->setRowStretch(0, 1);
  grid->setRowStretch(1, 1);
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(summary_);
  layout->addLayout(grid, 1);
  setResult(nullptr, {});
}

QString IntrinsicsReportPage::summary() const { return summary_->text(); }

void IntrinsicsReportPage::setResult(const IntrinsicsResult* r, const QStringList& names) {
  images_->setRowCount(0);
  parameters_->setRowCount(0);
  map_ = r ? coverageMap(*r) : CoverageMap{};
  warnings_ = r ? intrinsicsWarnings(*r, map_) : std::vector<CalibrationWarning>{};
  ok_ = r && ok(r->status);
  if (!r) {
    summary_->setText(tr("No calibration yet: describe the pattern, add 3 or more images of it (4 to 10 best) and "
                         "press Calibrate."));
    coverage_->setImage({}, tr("The coverage map appears after a calibration."));
    coverage_caption_->clear();
    fillWarnings();
    return;
  }
  fillImages(*r, names);
  if (ok(r->status)) {
    const IntrinsicsDeviations& d = r->deviation;
    summary_->setText(
        tr("Calibrated from %1 of %2 images: reprojection %3 px RMS over every dot used. fx %4 ± %5 px, fy %6 ± %7 "
           "px, principal point (%8, %9) px. In this project's model (eq. 4.7): k1 %10, k2 %11, p1 %12, p2 %13 "
           "(within %14 px RMS of OpenCV's field).")
            .arg(r->views_used)
            .arg(r->views.size())
            .arg(number(r->rms_px, 4), number(r->fx, 2), number(d.fx, 2), number(r->fy, 2), number(d.fy, 2),
                 number(r->cx, 2), number(r->cy, 2))
            .arg(r->distortion.k1, 0, 'e', 4)
            .arg(r->distortion.k2, 0, 'e', 4)
            .arg(r->distortion.p1, 0, 'e', 4)
            .arg(r->distortion.p2, 0, 'e', 4)
            .arg(number(r->model_fit_rms_px, 4)));
    fillParameters(*r);
    coverage_->setImage(rgbImage(coverageImage(*r, map_)));
    // Whole cells, not percentages: the warnings round theirs on their own.
    constexpr int kCells = kCoverageColumns * kCoverageRows, kBorderCells = 2 * (kCoverageColumns + kCoverageRows) - 4;
    coverage_caption_->setText(tr("Dots in %1 of the %2 x %3 cells and %4 of the %5 border cells (%6 % and %7 % "
                                  "wanted); each view's dots in its own colour.")
                                   .arg(std::lround(map_.covered_fraction * kCells))
                                   .arg(kCoverageColumns)
                                   .arg(kCoverageRows)
                                   .arg(std::lround(map_.border_fraction * kBorderCells))
                                   .arg(kBorderCells)
                                   .arg(number(100.0 * kMinCoveredFraction, 0))
                                   .arg(number(100.0 * kMinBorderFraction, 0)));
  } else {
    summary_->setText(tr("Calibration failed: %1").arg(statusInWords(r->status)));
    coverage_->setImage({}, tr("No coverage map: the calibration failed."));
    coverage_caption_->clear();
  }
  fillWarnings();
}

void IntrinsicsReportPage::fillImages(const IntrinsicsResult& r, const QStringList& names) {
  for (size_t i = 0; i < r.views.size(); ++i) {
    const IntrinsicsView& v = r.views[i];
    const QString name = static_cast<qsizetype>(i) < names.size() ? names[static_cast<qsizetype>(i)]
                                                                     : tr("Image %1").arg(i + 1);
    const QString status = ok(v.status) ? (v.partial ? tr("used (part of the grid)") : tr("used"))
                                        : QString::fromUtf8(statusName(v.status).data());
    const bool used = ok(v.status);
    appendRow(images_, {name, status, QString::number(v.dots), used ? number(v.rms_px, 4) : QStringLiteral("-"),
                        used ? number(v.tilt_deg, 1) : QStringLiteral("-")});
    if (!used) images_->item(static_cast<int>(i), 1)->setToolTip(statusInWords(v.status));
  }
  appendRow(images_, {tr("Overall"), tr("%1 of %2 used").arg(r.views_used).arg(r.views.size()), QString(),
                      ok(r.status) ? number(r.rms_px, 4) : QStringLiteral("-"), QString()});
}

void IntrinsicsReportPage::fillParameters(const IntrinsicsResult& r) {
  const IntrinsicsDeviations& d = r.deviation;
  const auto row = [this](const QString& name, double value, double sd, char format, int decimals) {
    appendRow(parameters_, {name, QString::number(value, format, decimals), QString::number(sd, format, decimals)});
  };
  row(tr("fx, px"), r.fx, d.fx, 'f', 3);
  row(tr("fy, px"), r.fy, d.fy, 'f', 3);
  row(tr("cx, px"), r.cx, d.cx, 'f', 3);
  row(tr("cy, px"), r.cy, d.cy, 'f', 3);
  row(tr("k1 (OpenCV)"), r.opencv_dist[0], d.k1, 'f', 5);
  row(tr("k2 (OpenCV)"), r.opencv_dist[1], d.k2, 'f', 5);
  row(tr("p1 (OpenCV)"), r.opencv_dist[2], d.p1, 'f', 6);
  row(tr("p2 (OpenCV)"), r.opencv_dist[3], d.p2, 'f', 6);
  if (d.k3 > 0.0)
    row(tr("k3 (OpenCV)"), r.opencv_dist[4], d.k3, 'f', 5);
  else
    appendRow(parameters_, {tr("k3 (OpenCV)"), number(r.opencv_dist[4], 5), tr("fixed")});
  appendRow(parameters_,
            {tr("pixel aspect fx/fy"), r.fy > 0 ? number(r.fx / r.fy, 5) : QStringLiteral("-"), QString()});
}

void IntrinsicsReportPage::fillWarnings() {
  warning_list_->clear();
  for (const CalibrationWarning& w : warnings_) {
    auto* item = new QListWidgetItem(
        QStringLiteral("%1: %2").arg(QString::fromStdString(w.name), QString::fromStdString(w.advice)));
    item->setForeground(QColor(0xb0, 0x00, 0x20));
    warning_list_->addItem(item);
  }
  if (warnings_.empty() && ok_)
    warning_list_->addItem(tr("None: the views cover the image, are tilted enough and fit the model."));
}

}  // namespace imagepro::app
