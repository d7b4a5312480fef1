#pragma once
// One stacked bar of the last frame's per-stage times (thesis figure 5.1 stages).
#include <QWidget>

#include <array>

#include "core/pipeline/frame_result.h"

class QBarSet;
class QChart;
class QValueAxis;

namespace imagepro::app {

class StageTimeChart : public QWidget {
  Q_OBJECT

 public:
  explicit StageTimeChart(QWidget* parent = nullptr);
  void setTimes(const StageTimes& times);
  double shownTotalUs() const { return total_; }

 private:
  void showRange();  // the axis to range_ rounded up, in round steps
  QChart* chart_;
  std::array<QBarSet*, kStageCount> sets_{};
  QValueAxis* axis_;
  double total_ = 0.0;
  double range_ = 1000.0;
};

}  // namespace imagepro::app
