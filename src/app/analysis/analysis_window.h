#pragma once
// The Analysis window: runs either case study of thesis 5.3 — the pendulum and g
// (5.3.2) or the distance and angle between two targets (5.3.1) — on the virtual
// scene, on a recorded data-out file or on the live stream of the main window, and
// shows the summary numbers and the plots. Long work (rendering and reconstructing a
// virtual scene, reading and analysing a file) runs on a background thread behind a
// progress bar; live frames are collected on the GUI thread from the worker's display
// packets, which carry every frame's pose. The computations are analysis_study.h's.
#include <QWidget>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "app/analysis/analysis_study.h"
#include "app/worker/display_packet.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QRadioButton;
class QSpinBox;
class QStackedWidget;
class QTableWidget;
class QThread;
class QTimer;

namespace imagepro::app {

class LiveTwoTargetAnalyser;
class MainWindow;
class PendulumChart;
class TwoTargetCharts;

enum class AnalysisStudy { Pendulum, TwoTargets };
enum class AnalysisInput { VirtualScene, DataOutFile, LiveStream };

class AnalysisWindow : public QWidget {
  Q_OBJECT

 public:
  explicit AnalysisWindow(MainWindow& main, QWidget* parent = nullptr);
  ~AnalysisWindow() override;

  void setStudy(AnalysisStudy study);
  AnalysisStudy study() const;
  void setInput(AnalysisInput input);
  AnalysisInput input() const;
  void setFilePath(const QString& path);
  // The pendulum's still recording (a pose CSV, a video or images): when given, the
  // length comes from it and the file is the swing (thesis 5.3.2).
  void setStillPath(const QString& path);
  void setPendulumParams(const VirtualPendulumParams& params);
  void setTwoTargetParams(const VirtualTwoTargetParams& params);

  // The Run button: a virtual scene or a file is analysed on a background thread;
  // the live stream starts collecting, or stops collecting and analyses.
  void run();
  void cancel();  // a background run
  bool isBusy() const { return task_ != nullptr; }
  bool isCollecting() const { return collecting_; }
  std::int64_t collectedFrames() const;

  const PendulumStudyResult& pendulumResult() const { return pendulum_; }
  const TwoTargetStudyResult& twoTargetResult() const { return two_targets_; }
  // The status line: what was done, or the error in words.
  QString message() const;
  // The summary table as text, one row per line, cells separated by tabs.
  QString summaryText() const;
  PendulumChart* pendulumChart() const { return pendulum_chart_; }
  TwoTargetCharts* twoTargetCharts() const { return two_target_charts_; }

 signals:
  // A result or an error is shown.
  void finished();

 private:
  QWidget* buildControls();
  QWidget* buildPendulumParams();
  QWidget* buildTwoTargetParams();
  void updateControls();
  void startTask(std::function<void()> work, std::function<void()> done);
  void pollProgress();
  void startCollecting();
  void stopCollecting();
  void onLivePacket(const DisplayPacketPtr& packet);
  void takeLiveTwoTargetFrames(bool redraw);
  void showPendulum();
  void showTwoTargets();
  void setMessage(const QString& text, bool error);
  VirtualPendulumParams pendulumParams() const;
  PendulumAnalysisOptions pendulumOptions() const;
  VirtualTwoTargetParams twoTargetParams() const;

  MainWindow& main_;
  // Controls.
  QComboBox* study_ = nullptr;
  QRadioButton* input_virtual_ = nullptr;
  QRadioButton* input_file_ = nullptr;
  QRadioButton* input_live_ = nullptr;
  QLineEdit* file_ = nullptr;
  QPushButton* browse_ = nullptr;
  QLineEdit* still_file_ = nullptr;
  QPushButton* still_browse_ = nullptr;
  QLabel* note_ = nullptr;
  QStackedWidget* params_ = nullptr;
  QSpinBox* pendulum_frames_ = nullptr;
  QDoubleSpinBox* pendulum_noise_ = nullptr;
  QDoubleSpinBox* rate_ = nullptr;
  QCheckBox* amplitude_correction_ = nullptr;
  QComboBox* period_method_ = nullptr;
  QCheckBox* interlaced_ = nullptr;
  QSpinBox* still_positions_ = nullptr;
  QDoubleSpinBox* spacing_ = nullptr;
  QDoubleSpinBox* angle_ = nullptr;
  QSpinBox* two_frames_ = nullptr;
  QComboBox* position_ = nullptr;
  QDoubleSpinBox* two_noise_ = nullptr;
  QCheckBox* thesis_lens_ = nullptr;
  QPushButton* run_ = nullptr;
  QProgressBar* progress_bar_ = nullptr;
  QLabel* count_ = nullptr;
  QLabel* message_ = nullptr;
  // Results.
  QTableWidget* summary_ = nullptr;
  QStackedWidget* plots_ = nullptr;
  PendulumChart* pendulum_chart_ = nullptr;
  TwoTargetCharts* two_target_charts_ = nullptr;

  // The background run.
  QThread* task_ = nullptr;
  StudyProgress progress_;
  QTimer* poll_ = nullptr;

  // Live collection.
  bool collecting_ = false;
  AnalysisStudy collecting_study_ = AnalysisStudy::Pendulum;
  std::vector<imagepro::PoseSample> live_samples_;
  std::vector<std::int64_t> live_indices_;
  std::int64_t live_last_index_ = -1;
  std::int64_t live_without_image_ = 0;
  std::unique_ptr<LiveTwoTargetAnalyser> live_two_;
  bool live_dirty_ = false;
  int live_polls_ = 0;

  PendulumStudyResult pendulum_;
  TwoTargetStudyResult two_targets_;
};

}  // namespace imagepro::app
