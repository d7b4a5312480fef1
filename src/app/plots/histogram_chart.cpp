#include "app/plots/histogram_chart.h"

#include <QAreaSeries>
#include <QChart>
#include <QChartView>
#include <QLineSeries>
#include <QValueAxis>
#include <QVBoxLayout>

#include <algorithm>

#include "app/plots/chart_view.h"
#include "app/plots/round_ticks.h"

namespace imagepro::app {

HistogramChart::HistogramChart(QWidget* parent)
    : QWidget(parent), chart_(new QChart), counts_(new QLineSeries), marker_(new QLineSeries), y_(new QValueAxis) {
  auto* area = new QAreaSeries(counts_);
  counts_->setParent(area);  // an area series does not own its line series, nor does the chart
  area->setName(tr("pixels"));
  area->setBrush(QColor(90, 140, 210, 160));
  area->setPen(QPen(QColor(40, 90, 170), 1.0));
  QPen marker_pen(QColor(220, 40, 40), 2.0);
  marker_->setPen(marker_pen);
  marker_->setName(tr("threshold"));
  chart_->addSeries(area);
  chart_->addSeries(marker_);
  auto* x = new QValueAxis;
  setRoundTicks(x, 0.0, 255.0, 50.0);
  x->setTitleText(tr("grey level"));
  chart_->addAxis(x, Qt::AlignBottom);
  chart_->addAxis(y_, Qt::AlignLeft);
  setRoundTicks(y_, 0.0, 1.0, 1.0);
  for (QAbstractSeries* s : {static_cast<QAbstractSeries*>(area), static_cast<QAbstractSeries*>(marker_)}) {
    s->attachAxis(x);
    s->attachAxis(y_);
  }
  chart_->setTitle(tr("Histogram of the searched region"));
  fillWithChart(this, chart_);
}

void HistogramChart::setHistogram(const Histogram& histogram, int threshold) {
  QList<QPointF> points;
  points.reserve(256);
  std::uint32_t peak = 1;
  for (int g = 0; g < 256; ++g) {
    points.append({double(g), double(histogram[static_cast<std::size_t>(g)])});
    peak = std::max(peak, histogram[static_cast<std::size_t>(g)]);
  }
  counts_->replace(points);
  // The count axis up to a round number above the peak, in round steps.
  const double step = roundStep(peak * 1.05, 4, 1.0);
  const double top = roundOutward(0.0, peak * 1.05, step).hi;
  setRoundTicks(y_, 0.0, top, step);
  threshold_ = threshold;
  if (threshold >= 0) marker_->replace({QPointF(threshold, 0), QPointF(threshold, top)});
  else marker_->clear();
  chart_->setTitle(threshold >= 0 ? tr("Histogram of the searched region, threshold %1").arg(threshold)
                                  : tr("Histogram of the searched region"));
}

}  // namespace imagepro::app
