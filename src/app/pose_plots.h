#pragma once
// Live plots of the six parameters over time (Qt Charts), with the ground truth of
// virtual frames beside them; pause freezes the view (recording goes on), export
// writes everything recorded as CSV.
#include <QWidget>

#include <array>
#include <vector>

#include "app/display_packet.h"

class QChart;
class QLineSeries;
class QValueAxis;
class QPushButton;
class QTimer;

namespace imagepro::app {

class PosePlots : public QWidget {
  Q_OBJECT

 public:
  explicit PosePlots(QWidget* parent = nullptr);

  void append(const std::vector<PoseSample>& samples);
  void clear();
  bool isPaused() const;
  void setPaused(bool paused);
  const std::vector<PoseSample>& recorded() const { return recorded_; }
  // Writes the recorded samples as pose CSV (+ timestamp and truth columns).
  bool exportCsv(const QString& path, QString& error) const;

 signals:
  void message(const QString& text);
  void error(const QString& text);

 private:
  void redraw();
  void exportInteractive();

  struct Plot {
    QChart* chart = nullptr;
    QLineSeries* measured = nullptr;
    QLineSeries* truth = nullptr;
    QValueAxis* x = nullptr;
    QValueAxis* y = nullptr;
  };
  std::array<Plot, 6> plots_;
  std::vector<PoseSample> recorded_;
  QPushButton* pause_;
  QTimer* redraw_timer_;
  bool dirty_ = false;
};

}  // namespace imagepro::app
