#include "app/plots/pose_plots.h"

#include <QChart>
#include <QChartView>
#include <QFileDialog>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLineSeries>
#include <QPushButton>
#include <QTimer>
#include <QVBoxLayout>
#include <QValueAxis>

#include <algorithm>
#include <cstdio>
#include <limits>

#include "core/common/atomic_file.h"
#include "core/pipeline/frame_record.h"
#include "core/common/pose_csv.h"

namespace imagepro::app {

namespace {

constexpr std::size_t kShown = 400;           // points on screen per series
constexpr int kRedrawMs = 200;

const char* const kTitles[6] = {"Rx [deg]", "Ry [deg]", "Rz [deg]", "Tx [mm]", "Ty [mm]", "Tz [mm]"};

double component(const Pose& p, int i) {
  const double v[6] = {p.rx_deg, p.ry_deg, p.rz_deg, p.tx_mm, p.ty_mm, p.tz_mm};
  return v[i];
}

}  // namespace

PosePlots::PosePlots(QWidget* parent) : QWidget(parent), pause_(new QPushButton(tr("Pause"))), redraw_timer_(new QTimer(this)) {
  auto* grid = new QGridLayout;
  grid->setSpacing(0);
  for (int i = 0; i < 6; ++i) {
    Plot& p = plots_[static_cast<std::size_t>(i)];
    p.chart = new QChart;
    p.chart->setTitle(QLatin1String(kTitles[i]));
    p.chart->legend()->hide();
    p.chart->setMargins(QMargins(2, 2, 2, 2));
    p.measured = new QLineSeries;
    p.truth = new QLineSeries;
    QPen truth_pen(QColor(120, 120, 120));
    truth_pen.setStyle(Qt::DashLine);
    p.truth->setPen(truth_pen);
    p.measured->setPen(QPen(QColor(30, 110, 220), 1.5));
    p.chart->addSeries(p.truth);
    p.chart->addSeries(p.measured);
    p.x = new QValueAxis;
    p.y = new QValueAxis;
    QFont small = p.chart->font();
    small.setPointSizeF(std::max(6.0, small.pointSizeF() * 0.8));
    p.x->setTickCount(3);
    p.y->setTickCount(3);
    p.y->setLabelFormat(QStringLiteral("%.1f"));
    p.x->setLabelsFont(small);
    p.y->setLabelsFont(small);
    p.chart->setTitleFont(small);
    p.chart->addAxis(p.x, Qt::AlignBottom);
    p.chart->addAxis(p.y, Qt::AlignLeft);
    for (QLineSeries* s : {p.measured, p.truth}) {
      s->setUseOpenGL(false);
      s->attachAxis(p.x);
      s->attachAxis(p.y);
    }
    // No antialiasing: six charts repainted five times a second must stay cheap for the GUI thread.
    auto* view = new QChartView(p.chart);
    view->setMinimumSize(180, 130);
    grid->addWidget(view, i / 3, i % 3);
  }
  pause_->setObjectName(QStringLiteral("plotsPause"));
  pause_->setCheckable(true);
  pause_->setToolTip(tr("Freeze the plots; recording goes on"));
  auto* clear_button = new QPushButton(tr("Clear"));
  clear_button->setObjectName(QStringLiteral("plotsClear"));
  auto* export_button = new QPushButton(tr("Export CSV..."));
  export_button->setObjectName(QStringLiteral("plotsExport"));
  export_button->setToolTip(tr("Write every recorded frame's parameters (and ground truth) to a CSV file"));
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(pause_);
  buttons->addWidget(clear_button);
  buttons->addWidget(export_button);
  buttons->addStretch(1);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(2, 2, 2, 2);
  layout->addLayout(buttons);
  layout->addLayout(grid, 1);

  connect(pause_, &QPushButton::toggled, this, [this](bool on) {
    pause_->setText(on ? tr("Resume") : tr("Pause"));
    if (!on) dirty_ = true;
  });
  connect(clear_button, &QPushButton::clicked, this, &PosePlots::clear);
  connect(export_button, &QPushButton::clicked, this, &PosePlots::exportInteractive);
  // One plot per tick, a round of six every kRedrawMs: redrawing all six at once held the
  // GUI thread for about 40 ms, long enough to feel as a stall.
  connect(redraw_timer_, &QTimer::timeout, this, [this] {
    if (isPaused() || !isVisible()) return;
    if (next_plot_ == 0) {
      if (!dirty_) return;
      dirty_ = false;
    }
    redrawPlot(next_plot_, shownRange());
    next_plot_ = (next_plot_ + 1) % static_cast<int>(plots_.size());
  });
  redraw_timer_->start(kRedrawMs / static_cast<int>(plots_.size()));  // at most five rounds a second
}

bool PosePlots::isPaused() const { return pause_->isChecked(); }
void PosePlots::setPaused(bool paused) { pause_->setChecked(paused); }

void PosePlots::append(const std::vector<PoseSample>& samples) {
  if (samples.empty()) return;
  if (recorded_.size() + samples.size() > kMaxRecorded)
    recorded_.erase(recorded_.begin(), recorded_.begin() + static_cast<std::ptrdiff_t>(
                                                                std::min(recorded_.size(), samples.size() + kMaxRecorded / 10)));
  recorded_.insert(recorded_.end(), samples.begin(), samples.end());
  dirty_ = true;
}

void PosePlots::clear() {
  recorded_.clear();
  dirty_ = true;
  redraw();
}

PosePlots::ShownRange PosePlots::shownRange() const {
  ShownRange r;
  r.first = recorded_.size() > kShown ? recorded_.size() - kShown : 0;
  // Files carry no capture times: their samples are placed by frame number instead.
  for (std::size_t k = r.first; k < recorded_.size() && !r.timed; ++k)
    r.timed = recorded_[k].timestamp_s != recorded_[r.first].timestamp_s;
  const auto x_of = [&r](const PoseSample& s) { return r.timed ? s.timestamp_s : static_cast<double>(s.index); };
  r.x0 = r.first < recorded_.size() ? x_of(recorded_[r.first]) : 0.0;
  r.x1 = recorded_.empty() ? 1.0 : x_of(recorded_.back());
  r.few = recorded_.size() - r.first < 30;
  return r;
}

void PosePlots::redraw() {
  dirty_ = false;
  next_plot_ = 0;
  const ShownRange range = shownRange();
  for (int i = 0; i < static_cast<int>(plots_.size()); ++i) redrawPlot(i, range);
}

void PosePlots::redrawPlot(int i, const ShownRange& r) {
  const auto x_of = [&r](const PoseSample& s) { return r.timed ? s.timestamp_s : static_cast<double>(s.index); };
  Plot& p = plots_[static_cast<std::size_t>(i)];
  QList<QPointF> measured, truth;
  measured.reserve(static_cast<qsizetype>(recorded_.size() - r.first));
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  for (std::size_t k = r.first; k < recorded_.size(); ++k) {
    const PoseSample& s = recorded_[k];
    if (s.pose) {
      const double v = component(*s.pose, i);
      measured.append({x_of(s), v});
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    if (s.truth) {
      const double v = component(*s.truth, i);
      truth.append({x_of(s), v});
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  p.measured->replace(measured);
  p.truth->replace(truth);
  p.measured->setPointsVisible(r.few);  // a lone file's pose is a point, not a line
  if (lo > hi) {
    lo = -1.0;
    hi = 1.0;
  }
  const double pad = std::max(0.5, 0.08 * (hi - lo));
  p.y->setRange(lo - pad, hi + pad);
  p.x->setRange(r.x0 - (r.timed ? 0.0 : 0.5), std::max(r.x1, r.x0 + 1.0) + (r.timed ? 0.0 : 0.5));
  p.x->setLabelFormat(r.timed ? QStringLiteral("%.0f s") : QStringLiteral("#%.0f"));
}

bool PosePlots::exportCsv(const QString& path, QString& error) const {
  std::string text = poseCsvHeader("timestamp_s," + recordCsvHeader(kTruthCsv));  // the truth as reconstruct names it
  text += '\n';
  for (const PoseSample& s : recorded_) {
    char extra[256];
    if (s.truth) {
      const Pose& t = *s.truth;
      std::snprintf(extra, sizeof extra, "%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f", s.timestamp_s, t.rx_deg, t.ry_deg, t.rz_deg,
                    t.tx_mm, t.ty_mm, t.tz_mm);
    } else {
      std::snprintf(extra, sizeof extra, "%.6f,,,,,,", s.timestamp_s);
    }
    text += poseCsvRow(std::to_string(s.index), s.status, s.pose, extra);
    text += '\n';
  }
  std::string why;
  if (!writeFileAtomically(path.toStdString(), text, why)) {
    error = QString::fromStdString(why);
    return false;
  }
  return true;
}

void PosePlots::exportInteractive() {
  const QString path = QFileDialog::getSaveFileName(this, tr("Export plotted parameters"), QStringLiteral("poses.csv"),
                                                    tr("CSV files (*.csv);;All files (*)"));
  if (path.isEmpty()) return;
  QString why;
  if (exportCsv(path, why)) emit message(tr("Exported %1 frames to %2").arg(recorded_.size()).arg(path));
  else emit error(tr("Export failed: %1").arg(why));
}

}  // namespace imagepro::app
