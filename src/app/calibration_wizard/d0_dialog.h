#pragma once
// The image plane distance dialog (thesis 4.1): frames of the target at known distances
// (captured from the running source, opened from files, or rendered by the Virtual
// source), each run through the iteration of eq. 4.1 from the lens's focal length
// (core/calibration/d0_estimation.h, the same as imagepro-cli estimate-d0). A table gives
// each frame's d0, its iterations, the depth reconstructed with it and, where the distance
// was measured, how far that depth is from it; a chart shows d0 at every step of each
// frame's iteration, converging. Set d0 gives the mean to the settings' camera.
#include <QDialog>

#include <map>
#include <vector>

#include <opencv2/core.hpp>

#include "core/calibration/d0_estimation.h"

class QChart;
class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QSpinBox;
class QTableWidget;
class QValueAxis;

namespace imagepro::app {

class MainWindow;

class D0Dialog : public QDialog {
  Q_OBJECT

 public:
  explicit D0Dialog(MainWindow& window);

  struct Entry {
    cv::Mat grey;
    QString origin;
    double distance_mm = 0.0;  // measured distance of the target, 0: not known
    D0FrameEstimate estimate;
  };

  // The buttons' actions, without their file dialogs. Each frame takes the known distance
  // the dialog shows when it is added.
  void addFrame(const cv::Mat& grey, const QString& origin);
  bool openImage(const QString& path);
  void captureFrame();   // the running source's frame, when the worker answers
  void renderVirtual();  // the target at the known distance (800 mm when none), through the settings' camera
  void clearFrames();
  bool setAndUse();      // the mean d0 into the settings' camera; false without an estimate

  void setFocalLength(double mm);
  void setKnownDistance(double mm);
  const std::vector<Entry>& entries() const { return entries_; }
  D0Summary summary() const;
  QString summaryText() const;
  QTableWidget* table() const { return table_; }
  QChart* chart() const { return chart_; }

 signals:
  void framesChanged();

 private:
  void onFrameCaptured(quint64 request, const cv::Mat& grey, const QString& source, bool running);
  void estimateAll();  // every frame again, with the dialog's options and the window's settings
  void refresh();

  MainWindow& window_;
  std::vector<Entry> entries_;
  std::map<quint64, bool> pending_captures_;
  quint64 next_capture_ = 0;
  QDoubleSpinBox* focal_ = nullptr;
  QDoubleSpinBox* epsilon_ = nullptr;
  QSpinBox* iterations_ = nullptr;
  QDoubleSpinBox* distance_ = nullptr;
  QPushButton* set_ = nullptr;
  QTableWidget* table_ = nullptr;
  QLabel* summary_ = nullptr;
  QChart* chart_ = nullptr;
  QValueAxis* axis_x_ = nullptr;
  QValueAxis* axis_y_ = nullptr;
};

// The window's one d0 dialog (made on first use), shown and raised.
D0Dialog& showD0Dialog(MainWindow& window);

}  // namespace imagepro::app
