#include "app/plots/analysis_plots.h"

#include <QChart>
#include <QChartView>
#include <QHBoxLayout>
#include <QLineSeries>
#include <QStringList>
#include <QVBoxLayout>
#include <QValueAxis>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace imagepro::app {

namespace {

const QColor kAxisColours[3] = {QColor(200, 80, 0), QColor(0, 140, 0), QColor(0, 90, 220)};
const QColor kCorrected(30, 110, 220), kUncorrected(230, 120, 20), kKnown(110, 110, 110);

// Range of the values with a margin; [-1, 1] when there are none.
struct Range {
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  void applyTo(QValueAxis* axis, double min_pad) const {
    if (lo > hi) {
      axis->setRange(-1.0, 1.0);
      return;
    }
    const double pad = std::max(min_pad, 0.05 * (hi - lo));
    axis->setRange(lo - pad, hi + pad);
    axis->applyNiceNumbers();  // round ticks
  }
};

QChart* makeChart(const QString& title, const QString& x_title, const QString& y_title, QValueAxis*& x,
                  QValueAxis*& y) {
  auto* chart = new QChart;
  chart->setTitle(title);
  chart->setMargins(QMargins(4, 4, 4, 4));
  chart->legend()->setAlignment(Qt::AlignBottom);
  x = new QValueAxis;
  y = new QValueAxis;
  x->setTitleText(x_title);
  y->setTitleText(y_title);
  chart->addAxis(x, Qt::AlignBottom);
  chart->addAxis(y, Qt::AlignLeft);
  return chart;
}

QLineSeries* addSeries(QChart* chart, const QString& name, const QColor& colour, Qt::PenStyle style, double width) {
  auto* series = new QLineSeries;
  series->setName(name);
  QPen pen(colour, width);
  pen.setStyle(style);
  series->setPen(pen);
  chart->addSeries(series);
  for (QAbstractAxis* axis : chart->axes()) series->attachAxis(axis);
  return series;
}

QValueAxis* axisOf(QChart* chart, Qt::Orientation orientation) {
  const QList<QAbstractAxis*> axes = chart->axes(orientation);
  return axes.isEmpty() ? nullptr : static_cast<QValueAxis*>(axes.front());
}

QChartView* viewOf(QChart* chart) {
  auto* view = new QChartView(chart);
  view->setRenderHint(QPainter::Antialiasing);  // drawn once per result, not per frame
  view->setMinimumSize(360, 260);
  return view;
}

}  // namespace

Eigen::VectorXd fitHarmonics(std::span<const double> t_s, std::span<const double> values, double period_s,
                             int harmonics) {
  const Eigen::Index unknowns = 1 + 2 * harmonics;
  const Eigen::Index n = static_cast<Eigen::Index>(std::min(t_s.size(), values.size()));
  if (!(period_s > 0.0) || harmonics < 0 || n < unknowns + 1) return {};
  const double w = 2.0 * M_PI / period_s;
  Eigen::MatrixXd A(n, unknowns);
  Eigen::VectorXd b(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = t_s[static_cast<std::size_t>(i)];
    A(i, 0) = 1.0;
    for (int k = 1; k <= harmonics; ++k) {
      A(i, 2 * k - 1) = std::cos(k * w * t);
      A(i, 2 * k) = std::sin(k * w * t);
    }
    b(i) = values[static_cast<std::size_t>(i)];
  }
  return A.colPivHouseholderQr().solve(b);
}

double evaluateHarmonics(const Eigen::VectorXd& c, double period_s, double t_s) {
  if (c.size() == 0) return 0.0;
  const double w = 2.0 * M_PI / period_s;
  double v = c(0);
  for (Eigen::Index k = 1; 2 * k < c.size() + 1; ++k)
    v += c(2 * k - 1) * std::cos(static_cast<double>(k) * w * t_s) + c(2 * k) * std::sin(static_cast<double>(k) * w * t_s);
  return v;
}

// ---- Pendulum -------------------------------------------------------------------

PendulumChart::PendulumChart(QWidget* parent) : QWidget(parent) {
  QValueAxis *x = nullptr, *y = nullptr;
  chart_ = makeChart(tr("Reconstructed translations about their means (thesis fig. 5.10)"), tr("time [s]"),
                     tr("T - mean [mm]"), x, y);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(viewOf(chart_));
}

void PendulumChart::clear() {
  chart_->removeAllSeries();
  axisOf(chart_, Qt::Horizontal)->setRange(0.0, 1.0);
  axisOf(chart_, Qt::Vertical)->setRange(-1.0, 1.0);
}

void PendulumChart::setResult(const PendulumStudyResult& result) {
  clear();
  std::vector<double> t;
  std::vector<double> v[3];
  for (const imagepro::PoseSample& s : result.samples) {
    if (!s.valid) continue;
    t.push_back(s.t_s);
    v[0].push_back(s.pose.tx_mm);
    v[1].push_back(s.pose.ty_mm);
    v[2].push_back(s.pose.tz_mm);
  }
  if (t.empty()) return;
  const double period = ok(result.status) ? result.analysis.period_s : 0.0;
  const char* names[3] = {"Tx", "Ty", "Tz"};
  Range range;
  for (int k = 0; k < 3; ++k) {
    double mean = 0.0;
    for (double value : v[k]) mean += value;
    mean /= static_cast<double>(v[k].size());
    QList<QPointF> points;
    points.reserve(static_cast<qsizetype>(t.size()));
    for (std::size_t i = 0; i < t.size(); ++i) {
      points.append({t[i], v[k][i] - mean});
      range.add(v[k][i] - mean);
    }
    QLineSeries* measured = addSeries(chart_, tr("%1 (mean %2 mm)").arg(QLatin1String(names[k])).arg(mean, 0, 'f', 1),
                                      kAxisColours[k], Qt::SolidLine, 1.5);
    measured->replace(points);
    const Eigen::VectorXd c = fitHarmonics(t, v[k], period, 2);
    if (c.size() == 0) continue;
    // The fit, drawn finely enough to be smooth between the frames.
    QList<QPointF> fitted;
    const int steps = static_cast<int>(std::clamp((t.back() - t.front()) / period * 40.0, 2.0, 4000.0));
    for (int i = 0; i <= steps; ++i) {
      const double ti = t.front() + (t.back() - t.front()) * i / steps;
      fitted.append({ti, evaluateHarmonics(c, period, ti) - mean});
    }
    QLineSeries* fit = addSeries(chart_, tr("%1 fit").arg(QLatin1String(names[k])), kAxisColours[k].darker(150),
                                 Qt::DashLine, 1.0);
    fit->replace(fitted);
  }
  axisOf(chart_, Qt::Horizontal)->setRange(t.front(), std::max(t.back(), t.front() + 1e-3));
  range.applyTo(axisOf(chart_, Qt::Vertical), 0.5);
  chart_->setTitle(period > 0.0 ? tr("Reconstructed translations about their means, with the fit at the measured "
                                     "period %1 s (thesis fig. 5.10)").arg(period, 0, 'f', 4)
                                : tr("Reconstructed translations about their means (thesis fig. 5.10)"));
}

// ---- Two targets ------------------------------------------------------------------

TwoTargetCharts::TwoTargetCharts(QWidget* parent) : QWidget(parent) {
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  for (int q = 0; q < 2; ++q) {
    QValueAxis *x = nullptr, *y = nullptr;
    charts_[q] = makeChart(q == 0 ? tr("Distance between the target centres") : tr("Angle between the target normals"),
                           tr("frame"), q == 0 ? tr("distance [mm]") : tr("angle [deg]"), x, y);
    x->setLabelFormat(QStringLiteral("%.0f"));
    layout->addWidget(viewOf(charts_[q]));
  }
}

void TwoTargetCharts::clear() {
  for (QChart* chart : charts_) {
    chart->removeAllSeries();
    axisOf(chart, Qt::Horizontal)->setRange(0.0, 1.0);
    axisOf(chart, Qt::Vertical)->setRange(-1.0, 1.0);
  }
}

void TwoTargetCharts::setResult(const TwoTargetStudyResult& result) {
  clear();
  const double known[2] = {result.object.spacing_mm, result.object.angle_deg};
  const int n = static_cast<int>(result.frames.size());
  // Which frames show which object position (virtual scene).
  QStringList positions, starts;
  for (int i = 0; i < n;) {
    const int position = result.frames[static_cast<std::size_t>(i)].position;
    int end = i;
    while (end < n && result.frames[static_cast<std::size_t>(end)].position == position) ++end;
    if (position > 0) {
      positions << QString::number(position);
      starts << QString::number(i);
    }
    i = end;
  }
  const QString x_title = positions.isEmpty() ? tr("frame")
                          : positions.size() == 1
                              ? tr("frame (position %1)").arg(positions.front())
                              : tr("frame (pos. %1 from %2)").arg(positions.join(QStringLiteral(", ")),
                                                                 starts.join(QStringLiteral(", ")));
  for (int q = 0; q < 2; ++q) {
    QChart* chart = charts_[q];
    Range range;
    range.add(known[q]);
    for (int c = 0; c < kCorrections; ++c) {
      QList<QPointF> points;
      for (int i = 0; i < n; ++i) {
        const TwoTargetFrame& f = result.frames[static_cast<std::size_t>(i)];
        if (!ok(f.status[c])) continue;
        const double v = q == 0 ? f.measurement[c].distance_mm : f.measurement[c].angle_deg;
        points.append({static_cast<double>(i), v});
        range.add(v);
      }
      QLineSeries* s = addSeries(chart, kCorrectionOn[c] ? tr("distortion corrected") : tr("not corrected"),
                                 kCorrectionOn[c] ? kCorrected : kUncorrected, Qt::SolidLine, 1.5);
      s->setPointsVisible(n < 60);
      s->replace(points);
    }
    QLineSeries* k = addSeries(chart, q == 0 ? tr("known %1 mm").arg(known[q], 0, 'f', 1)
                                             : tr("known %1 deg").arg(known[q], 0, 'f', 1),
                               kKnown, Qt::DashLine, 1.2);
    k->replace({QPointF(0.0, known[q]), QPointF(std::max(1, n - 1), known[q])});
    QValueAxis* x = axisOf(chart, Qt::Horizontal);
    x->setRange(0.0, std::max(1, n - 1));
    x->applyNiceNumbers();
    x->setTitleText(x_title);
    range.applyTo(axisOf(chart, Qt::Vertical), q == 0 ? 0.1 : 0.05);
  }
}

}  // namespace imagepro::app
