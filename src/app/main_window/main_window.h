#pragma once
// The ImagePro window (thesis appendix A): the control panel dock, the results area
// (frame view and results text), the plots dock and the status bar. It holds the
// one Settings model the panels edit and hands copies to the worker thread; it
// draws what the worker sends and holds no algorithm itself.
#include <QElapsedTimer>
#include <QMainWindow>
#include <QThread>

#include <optional>
#include <utility>

#include "app/worker/display_packet.h"
#include "app/worker/source_kind.h"
#include "core/pipeline/data_out.h"
#include "core/settings/settings.h"

class QAction;
class QLabel;
class QMenu;
class QTimer;

namespace imagepro::app {

class ControlPanel;
class FrameView;
class HistogramChart;
class MessageBanner;
class PosePlots;
class RecentFiles;
class SettingsBinder;
class StageTimeChart;
class Worker;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  // Actions, also used by the command line and the tests.
  bool loadSettingsFile(const QString& path);   // false: the error (naming the key) is shown
  bool saveSettingsFile(const QString& path);
  void restoreDefaults();
  void setSettings(const Settings& settings);   // replaces the model, refreshes the panels
  const Settings& settings() const { return settings_; }
  void selectSource(SourceKind kind);
  // The selected source: a live one, or a list of images or a video open on File (with
  // nothing to play, File asks for files instead).
  void startSource();
  void stopSource();
  void openPaths(const QStringList& paths);      // files or folders: switches to File input
  void stepFile(FileStep step);                  // another image of the open list
  void openSamples();                            // the shipped sample frames (data_directory.h)
  bool saveScreenshot(const QString& path);
  // The screenshot option (thesis A.1.1): Screenshot stops a running live source while its
  // file is chosen and starts it again after. Remembered between runs.
  void setFreezeOnScreenshot(bool on);
  bool freezeOnScreenshot() const;
  bool frozenForScreenshot() const { return frozen_for_screenshot_; }
  // False (the reason shown) for a name that is no CSV text file's: Data Out writes CSV,
  // to a name ending in .csv or .txt; a name without an extension gets .csv.
  // A calibration set and in use (the wizard's Set and Use, an imported camera, Set d0):
  // quitting asks to save the settings while the source in use's camera still has it and
  // it has not been saved since (in a settings file, or as the wizard's calibration file).
  void calibrationInUse();
  void calibrationSaved(const Settings& saved);  // clears it when `saved` holds that camera
  bool hasUnsavedCalibration() const;

  bool startDataOut(const QString& path, ExistingFile existing, bool replace);
  void stopDataOut();
  // Ctrl+D: Data Out off while it writes, else the file dialog that switches it on.
  void toggleDataOut();

  Worker* worker() const { return worker_; }
  ControlPanel* controlPanel() const { return control_panel_; }
  FrameView* frameView() const { return view_; }
  PosePlots* posePlots() const { return plots_; }
  HistogramChart* histogramChart() const { return histogram_; }
  StageTimeChart* stageTimeChart() const { return stage_times_; }
  QWidget* resultsArea() const { return results_area_; }
  QString resultsText() const;
  QString lastError() const { return last_error_; }
  QString bannerText() const;  // the error banner's text while it shows, else empty
  // Where the file dialogs start (dialog_folder.h).
  QString dialogDirectory() const;
  QString dataOutPath() const { return data_out_path_; }
  QStringList recentPaths() const;
  std::int64_t packetsShown() const { return packets_shown_; }

 signals:
  void packetShown();

 protected:
  void closeEvent(QCloseEvent* event) override;
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  void buildResultsArea();
  void buildDocks();
  void buildMenus();
  // Tools > Targets of the Set: the shown target, the reference target and the measured
  // pair (settings frames) offered from the settings' set each time the menu opens.
  void fillTargetSetMenu(QMenu& menu);
  void buildStatusBar();
  void connectWorker();
  void restoreLayout();
  void onPacket(const DisplayPacketPtr& packet);
  void refreshReadouts();  // results text, status bar, histogram and stage times
  void onSettingsEdited();
  void showError(const QString& message);
  void showInfo(const QString& message);
  // What the selected source is and what is on (Data Out, the stream): window title,
  // status bar and the Input Source panel.
  void showSource(const QString& description);
  void updateTitle();
  // The selected source has no frame yet: the last source's frame, numbers, status and
  // plots go, and the frame view says `why`.
  void clearShownResults(const QString& why);
  // Interactive versions with dialogs.
  void openDialog(bool folder);
  void saveSettingsDialog();
  void loadSettingsDialog();
  void screenshotDialog();
  void dataOutDialog(bool on);
  void settingsDialog();
  void showKeys();
  // Asks whether to save a calibration in use and not saved before `action` loses it
  // (quitting, the defaults, a settings file): true to go on. Asks nothing, and is true,
  // when there is none or `next` keeps the same camera.
  bool mayLoseCalibration(const QString& action, const Settings* next = nullptr);

  Settings settings_;
  SettingsBinder* binder_;
  QThread thread_;
  Worker* worker_;
  ControlPanel* control_panel_ = nullptr;
  FrameView* view_ = nullptr;
  QLabel* results_text_ = nullptr;
  QWidget* results_area_ = nullptr;
  MessageBanner* banner_ = nullptr;
  PosePlots* plots_ = nullptr;
  HistogramChart* histogram_ = nullptr;
  StageTimeChart* stage_times_ = nullptr;
  RecentFiles* recent_ = nullptr;
  QLabel* status_source_ = nullptr;
  QLabel* status_rate_ = nullptr;
  QLabel* status_stream_ = nullptr;  // the live stream's counts and status, hidden when it is off
  QLabel* status_state_ = nullptr;
  QLabel* status_data_out_ = nullptr;  // shown while Data Out writes
  QAction* data_out_action_ = nullptr;
  QString source_description_;
  bool opening_paths_ = false;  // openPaths selects File itself: no second selection for the worker
  static constexpr int kReadoutMs = 100;
  QTimer* readout_timer_ = nullptr;
  QElapsedTimer readout_clock_;
  DisplayPacketPtr latest_;
  bool readouts_dirty_ = false;
  QString last_error_;
  QString data_out_path_;
  std::int64_t packets_shown_ = 0;
  QAction* freeze_action_ = nullptr;
  bool frozen_for_screenshot_ = false;
  std::optional<std::pair<SourceKind, CameraModel>> unsaved_calibration_;
};

}  // namespace imagepro::app
