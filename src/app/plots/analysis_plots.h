#pragma once
// The Analysis window's charts (Qt Charts): the pendulum's translations over time
// about their means with the fit at the measured period (thesis fig. 5.10), and the
// two targets' distance and angle per frame, with and without distortion correction,
// beside the known values (thesis figs. 5.3-5.8).
#include <QWidget>

#include <Eigen/Core>

#include <span>
#include <vector>

#include "app/analysis/analysis_study.h"

class QChart;

namespace imagepro::app {

// Least-squares fit of  c0 + sum_k (a_k cos(k w t) + b_k sin(k w t)),  k = 1..harmonics,
// w = 2 pi / period_s: the coefficients [c0, a1, b1, a2, b2, ...], or empty when the
// times are too few or the period is not positive. Two harmonics follow all three
// translations of a pendulum: the height rises at both ends of the swing.
Eigen::VectorXd fitHarmonics(std::span<const double> t_s, std::span<const double> values, double period_s,
                             int harmonics);
double evaluateHarmonics(const Eigen::VectorXd& coefficients, double period_s, double t_s);

class PendulumChart : public QWidget {
  Q_OBJECT

 public:
  explicit PendulumChart(QWidget* parent = nullptr);
  // The translations of the valid samples; with the fit when the analysis succeeded.
  void setResult(const PendulumStudyResult& result);
  void clear();
  QChart* chart() const { return chart_; }

 private:
  QChart* chart_;
};

class TwoTargetCharts : public QWidget {
  Q_OBJECT

 public:
  explicit TwoTargetCharts(QWidget* parent = nullptr);
  void setResult(const TwoTargetStudyResult& result);
  void clear();
  QChart* distanceChart() const { return charts_[0]; }
  QChart* angleChart() const { return charts_[1]; }

 private:
  QChart* charts_[2];
};

}  // namespace imagepro::app
