#pragma once
// The searched region's grey-level histogram (thesis figure 2.7) with the chosen
// threshold marked.
#include <QWidget>

#include "core/segmentation/histogram.h"

class QChart;
class QLineSeries;
class QValueAxis;

namespace imagepro::app {

class HistogramChart : public QWidget {
  Q_OBJECT

 public:
  explicit HistogramChart(QWidget* parent = nullptr);
  // threshold < 0: none marked.
  void setHistogram(const Histogram& histogram, int threshold);
  int threshold() const { return threshold_; }

 private:
  QChart* chart_;
  QLineSeries* counts_;
  QLineSeries* marker_;
  QValueAxis* y_;
  int threshold_ = -1;
};

}  // namespace imagepro::app
