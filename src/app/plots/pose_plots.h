#pragma once
// Live plots of the six parameters over time (Qt Charts), with the ground truth of
// virtual frames beside them; pause freezes the view (recording goes on), export
// writes everything recorded as CSV. The six share one window on one clock: the last
// kWindowS seconds of the source's run, or the images of a list by their number, each
// still a point. A clock that starts again (a camera started anew, another file) or
// samples of another kind start the recording again.
#include <QWidget>

#include <array>
#include <vector>

#include "app/worker/display_packet.h"

class QChart;
class QChartView;
class QLineSeries;
class QScatterSeries;
class QValueAxis;
class QPushButton;
class QTimer;

namespace imagepro::app {

class PosePlots : public QWidget {
  Q_OBJECT

 public:
  explicit PosePlots(QWidget* parent = nullptr);

  // The recording's bound (about two hours at 25 Hz, 27 MB): past it the oldest tenth
  // goes, so a long run's memory levels off there.
  static constexpr std::size_t kMaxRecorded = 200000;
  // The time window of a running source, seconds.
  static constexpr double kWindowS = 20.0;

  void append(const std::vector<PoseSample>& samples);
  void clear();
  bool isPaused() const;
  void setPaused(bool paused);
  const std::vector<PoseSample>& recorded() const { return recorded_; }
  // Writes the recorded samples as pose CSV (+ timestamp and truth columns).
  bool exportCsv(const QString& path, QString& error) const;
  // Every plot at once, ending a round in progress: a picture of the window taken
  // during a round would show the held views blank.
  void redraw();

 signals:
  void message(const QString& text);
  void error(const QString& text);

 private:
  // What one round of redraws shows, the same for all six plots.
  struct Shown {
    std::vector<std::size_t> samples;  // the recorded samples drawn, in x order
    bool still = false;                // images of a list: x is the image's number
    bool markers = false;              // each sample a marker: stills, or too few for a line
    double x0 = 0.0, x1 = kWindowS, step = 5.0;
  };
  Shown whatIsShown() const;
  void redrawPlot(int i, const Shown& shown);
  void exportInteractive();

  struct Plot {
    QChart* chart = nullptr;
    QChartView* view = nullptr;
    QLineSeries* measured = nullptr;
    QScatterSeries* points = nullptr;  // the measured samples as markers
    QLineSeries* truth = nullptr;
    QValueAxis* x = nullptr;
    QValueAxis* y = nullptr;
  };
  static void setXTicks(Plot& p, const Shown& shown);
  std::array<Plot, 6> plots_;
  std::vector<PoseSample> recorded_;
  Shown shown_;  // the current round's
  QPushButton* pause_;
  QTimer* redraw_timer_;
  bool dirty_ = false;
  int next_plot_ = 0;  // the timer redraws one plot per tick
  void holdPainting(bool hold);  // the six views paint together, at the end of a round
};

}  // namespace imagepro::app
