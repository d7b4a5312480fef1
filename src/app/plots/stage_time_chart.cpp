#include "app/plots/stage_time_chart.h"

#include <QBarCategoryAxis>
#include <QBarSet>
#include <QChart>
#include <QChartView>
#include <QHorizontalStackedBarSeries>
#include <QValueAxis>
#include <QVBoxLayout>

#include <algorithm>

#include "app/plots/chart_view.h"
#include "app/plots/round_ticks.h"

namespace imagepro::app {

StageTimeChart::StageTimeChart(QWidget* parent) : QWidget(parent), chart_(new QChart), axis_(new QValueAxis) {
  auto* series = new QHorizontalStackedBarSeries;
  for (std::size_t s = 0; s < kStageCount; ++s) {
    sets_[s] = new QBarSet(QLatin1String(stageName(static_cast<Stage>(s))));
    *sets_[s] << 0.0;
    series->append(sets_[s]);
  }
  series->setBarWidth(0.6);
  chart_->addSeries(series);
  auto* category = new QBarCategoryAxis;
  category->append(tr("frame"));
  chart_->addAxis(category, Qt::AlignLeft);
  series->attachAxis(category);
  axis_->setTitleText(tr("microseconds"));
  showRange();
  chart_->addAxis(axis_, Qt::AlignBottom);
  series->attachAxis(axis_);
  chart_->legend()->setAlignment(Qt::AlignBottom);
  chart_->setTitle(tr("Time per stage"));
  fillWithChart(this, chart_);
}

void StageTimeChart::setTimes(const StageTimes& times) {
  for (std::size_t s = 0; s < kStageCount; ++s) sets_[s]->replace(0, times.us[s]);
  total_ = times.total();
  // Grow at once, shrink slowly, so the bar does not jump about.
  if (total_ > range_) range_ = total_ * 1.2;
  else if (total_ < range_ * 0.4) range_ = std::max(10.0, range_ * 0.9);
  showRange();
  chart_->setTitle(tr("Time per stage: %1 us total").arg(total_, 0, 'f', 0));
}

void StageTimeChart::showRange() {
  const double step = roundStep(range_, 5, 1.0);
  setRoundTicks(axis_, 0.0, roundOutward(0.0, range_, step).hi, step);
}

}  // namespace imagepro::app
