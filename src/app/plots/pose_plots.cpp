#include "app/plots/pose_plots.h"

#include <QChart>
#include <QChartView>
#include <QFileDialog>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLineSeries>
#include <QPushButton>
#include <QScatterSeries>
#include <QTimer>
#include <QVBoxLayout>
#include <QValueAxis>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "app/plots/round_ticks.h"
#include "app/main_window/dialog_folder.h"
#include "core/common/atomic_file.h"
#include "core/pipeline/frame_record.h"
#include "core/common/pose_csv.h"

namespace imagepro::app {

namespace {

constexpr std::size_t kShown = 400;  // points on screen per series at most
constexpr std::size_t kFewForLine = 30;  // below this many samples each is a marker too
constexpr int kRedrawMs = 200;
const QColor kMeasured(30, 110, 220);

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
    p.points = new QScatterSeries;
    p.truth = new QLineSeries;
    QPen truth_pen(QColor(120, 120, 120));
    truth_pen.setStyle(Qt::DashLine);
    p.truth->setPen(truth_pen);
    p.measured->setPen(QPen(kMeasured, 1.5));
    p.points->setMarkerSize(7.0);
    p.points->setColor(kMeasured);
    p.points->setBorderColor(kMeasured);
    p.chart->addSeries(p.truth);
    p.chart->addSeries(p.measured);
    p.chart->addSeries(p.points);
    p.x = new QValueAxis;
    p.y = new QValueAxis;
    QFont small = p.chart->font();
    small.setPointSizeF(std::max(6.0, small.pointSizeF() * 0.8));
    p.x->setLabelsFont(small);
    p.y->setLabelsFont(small);
    p.chart->setTitleFont(small);
    p.chart->addAxis(p.x, Qt::AlignBottom);
    p.chart->addAxis(p.y, Qt::AlignLeft);
    for (QXYSeries* s : std::initializer_list<QXYSeries*>{p.measured, p.points, p.truth}) {
      s->setUseOpenGL(false);
      s->attachAxis(p.x);
      s->attachAxis(p.y);
    }
    // No antialiasing: six charts repainted five times a second must stay cheap for the GUI thread.
    p.view = new QChartView(p.chart);
    p.view->setMinimumSize(180, 130);
    grid->addWidget(p.view, i / 3, i % 3);
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
  // One plot's series per tick, a round of six every kRedrawMs: replacing all six at once
  // held the GUI thread for about 40 ms, long enough to feel as a stall. The views are
  // painted together when the round is done, so the six show one window and one last
  // sample at every moment.
  connect(redraw_timer_, &QTimer::timeout, this, [this] {
    if (next_plot_ == 0) {
      if (isPaused() || !isVisible() || !dirty_) return;
      dirty_ = false;
      shown_ = whatIsShown();
      holdPainting(true);
    }
    setXTicks(plots_[static_cast<std::size_t>(next_plot_)], shown_);
    redrawPlot(next_plot_, shown_);
    next_plot_ = (next_plot_ + 1) % static_cast<int>(plots_.size());
    if (next_plot_ == 0) holdPainting(false);
  });
  redraw_timer_->start(kRedrawMs / static_cast<int>(plots_.size()));  // at most five rounds a second
  redraw();
}

bool PosePlots::isPaused() const { return pause_->isChecked(); }
void PosePlots::setPaused(bool paused) { pause_->setChecked(paused); }

void PosePlots::append(const std::vector<PoseSample>& samples) {
  if (samples.empty()) return;
  for (const PoseSample& s : samples) {
    // One clock per run: time running backwards (a camera started anew, a video played
    // again) or stills after timed frames, or the other way, begin another run.
    if (!recorded_.empty() && (s.still != recorded_.back().still ||
                               (!s.still && s.timestamp_s < recorded_.back().timestamp_s)))
      recorded_.clear();
    if (recorded_.size() >= kMaxRecorded)
      recorded_.erase(recorded_.begin(), recorded_.begin() + static_cast<std::ptrdiff_t>(kMaxRecorded / 10));
    recorded_.push_back(s);
  }
  dirty_ = true;
}

void PosePlots::clear() {
  recorded_.clear();
  dirty_ = true;
  redraw();
}

PosePlots::Shown PosePlots::whatIsShown() const {
  Shown shown;
  if (recorded_.empty()) {
    shown.step = roundStep(kWindowS, 4);
    return shown;
  }
  if (recorded_.back().still) {
    // Images by number (1 for the first, as the title counts them), the latest result
    // of each: an image processed again with other options replaces its point.
    shown.still = shown.markers = true;
    std::map<std::int64_t, std::size_t> latest;
    const std::size_t from = recorded_.size() > kShown ? recorded_.size() - kShown : 0;
    for (std::size_t k = from; k < recorded_.size(); ++k) latest[recorded_[k].index] = k;
    for (const auto& [index, k] : latest) shown.samples.push_back(k);
    shown.x0 = static_cast<double>(latest.begin()->first) + 0.5;
    shown.x1 = static_cast<double>(latest.rbegin()->first) + 1.5;
    shown.step = roundStep(shown.x1 - shown.x0, 5, 1.0);
    return shown;
  }
  // The run's first kWindowS seconds, then the last kWindowS seconds.
  const double t_first = recorded_.front().timestamp_s, t_last = recorded_.back().timestamp_s;
  shown.x0 = std::max(t_first, t_last - kWindowS);
  shown.x1 = shown.x0 + kWindowS;
  shown.step = roundStep(kWindowS, 4);
  const auto first = std::lower_bound(recorded_.begin(), recorded_.end(), shown.x0,
                                      [](const PoseSample& s, double t) { return s.timestamp_s < t; });
  const auto begin = static_cast<std::size_t>(first - recorded_.begin());
  const std::size_t count = recorded_.size() - begin;
  // Thinned by frame number, so that the same frames stay on screen as the window moves.
  const auto stride = static_cast<std::int64_t>((count + kShown - 1) / kShown);
  for (std::size_t k = begin; k < recorded_.size(); ++k)
    if (recorded_[k].index % stride == 0 || k + 1 == recorded_.size()) shown.samples.push_back(k);
  shown.markers = count < kFewForLine;
  return shown;
}

void PosePlots::holdPainting(bool hold) {
  for (Plot& p : plots_) p.view->setUpdatesEnabled(!hold);
}

void PosePlots::redraw() {
  dirty_ = false;
  next_plot_ = 0;
  holdPainting(false);
  shown_ = whatIsShown();
  for (Plot& p : plots_) setXTicks(p, shown_);
  for (int i = 0; i < static_cast<int>(plots_.size()); ++i) redrawPlot(i, shown_);
}

void PosePlots::redrawPlot(int i, const Shown& shown) {
  Plot& p = plots_[static_cast<std::size_t>(i)];
  QList<QPointF> measured, truth;
  measured.reserve(static_cast<qsizetype>(shown.samples.size()));
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  for (std::size_t k : shown.samples) {
    const PoseSample& s = recorded_[k];
    const double x = shown.still ? static_cast<double>(s.index + 1) : s.timestamp_s;
    if (s.pose) {
      const double v = component(*s.pose, i);
      measured.append({x, v});
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    if (s.truth) {
      const double v = component(*s.truth, i);
      truth.append({x, v});
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  // Stills are points, not a line through the images; a run's first frames are both.
  p.measured->replace(shown.still ? QList<QPointF>{} : measured);
  p.points->replace(shown.markers ? measured : QList<QPointF>{});
  p.truth->replace(truth);
  if (lo > hi) {
    lo = -1.0;
    hi = 1.0;
  }
  const double pad = std::max(0.5, 0.08 * (hi - lo));
  const double y_step = roundStep(hi - lo + 2.0 * pad, 4);
  const AxisRange y = roundOutward(lo - pad, hi + pad, y_step);
  setRoundTicks(p.y, y.lo, y.hi, y_step);
}

void PosePlots::setXTicks(Plot& p, const Shown& shown) {
  if (shown.still) setRoundTicks(p.x, shown.x0, shown.x1, shown.step, QStringLiteral("#"));
  else setRoundTicks(p.x, shown.x0, shown.x1, shown.step, {}, QStringLiteral(" s"));
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
  const QString path = QFileDialog::getSaveFileName(this, tr("Export plotted parameters"), dialogFolderWith(QStringLiteral("poses.csv")),
                                                    tr("CSV files (*.csv);;All files (*)"));
  if (path.isEmpty()) return;
  rememberDialogFolder(path);
  QString why;
  if (exportCsv(path, why)) emit message(tr("Exported %1 frames to %2").arg(recorded_.size()).arg(path));
  else emit error(tr("Export failed: %1").arg(why));
}

}  // namespace imagepro::app
