#pragma once
// The calibration wizard: the "Internal Camera Calibration" panel of thesis appendix A
// (A.1.1, A.2.2). Two modes, chosen at its top: the lens distortion calibration of thesis
// 4.6 (core/calibration/calibrate.h), described below, and the full intrinsic calibration
// of a camera nothing is known about (intrinsics_page.h).
//  * Four image slots. Each takes an image of the calibration pattern from a file, from the
//    running source's current frame, or rendered by the Virtual source (the pattern turned
//    +-45 deg about x and y, through the settings' lens), and shows what the procedure sees
//    in it (thesis fig. 4.6) and what is wrong with it, in words.
//  * Calibrate runs the procedure on a thread of the pool, never on the GUI thread; every
//    iteration lands in the table as it ends (queued through a QFuture), with a progress bar.
//    Closing the window or Cancel leaves the run to finish in the background: its result is
//    dropped, and nothing of the window is touched after it is gone.
//  * The distortion field found, as arrows over the camera's image.
//  * Set and Use gives the distortion to the settings' camera (the one camera model every
//    source uses) and turns distortion correction on; Save Calibration writes the
//    calibration file (core/calibration/calibration_file.h).
#include <QDialog>
#include <QFutureWatcher>

#include <array>
#include <map>
#include <memory>
#include <optional>

#include "app/calibration_wizard/calibration_images.h"

class QLabel;
class QProgressBar;
class QPushButton;
class QRadioButton;
class QSpinBox;
class QStackedWidget;
class QTableWidget;

namespace imagepro::app {

class CalibrationImageView;
class DistortionFieldView;
class IntrinsicsPage;
class MainWindow;

enum class CalibrationMode { Distortion, Intrinsics };

// What the calibration thread hands back: one per iteration, then the result.
struct CalibrationRunUpdate {
  std::optional<CalibrationIteration> iteration;
  std::shared_ptr<const CalibrationResult> result;
};

class CalibrationWizard : public QDialog {
  Q_OBJECT

 public:
  explicit CalibrationWizard(MainWindow& window);
  ~CalibrationWizard() override;

  void setMode(CalibrationMode mode);
  CalibrationMode mode() const;
  IntrinsicsPage* intrinsicsPage() const { return intrinsics_; }

  // The buttons' actions, without their file dialogs (slot 0-3).
  void openImage(int slot, const QString& path);
  void captureFrame(int slot);
  void renderVirtual(int slot);
  void clearImage(int slot);
  void calibrate();
  void cancelCalibration();  // drops the run; it finishes in the background
  void setAndUse();
  bool saveCalibration(const QString& path);

  bool hasImage(int slot) const;
  bool isAnalysing() const;  // an image is still being rendered or analysed
  bool isCalibrating() const { return run_ != nullptr; }
  QString slotStatus(int slot) const;
  QString runStatus() const;
  // The last run that finished (whatever its status); nullptr before one has.
  const CalibrationResult* result() const { return result_.get(); }
  QTableWidget* iterationTable() const { return table_; }
  DistortionFieldView* fieldView() const { return field_; }
  CalibrationImageView* imageView(int slot) const;

 signals:
  void imageReady(int slot);  // a slot's image analysed, or the attempt failed
  void calibrationFinished(bool ok);

 protected:
  void showEvent(QShowEvent* event) override;

 private:
  struct Slot {
    CalibrationImageView* view = nullptr;
    QLabel* status = nullptr;
    QPushButton* clear = nullptr;
    CalibrationImage image;  // grey empty: no image
    quint64 generation = 0;  // a new one with every change of the slot's image
    bool busy = false;
    QString note;            // shown instead of the summary until the next image
    bool note_is_error = false;
  };

  static constexpr int kIntrinsicsCapture = -1;  // a capture for the intrinsic mode, not a slot

  QWidget* buildModeChoice();
  QWidget* buildDistortionPage();
  QWidget* buildSlot(int slot);
  QWidget* buildRunColumn();
  void chooseImageFile(int slot);
  // Renders or takes `grey` on a pool thread and analyses it there.
  void startAnalysis(int slot, std::function<void(cv::Mat&)> produce, const QString& origin);
  void onFrameCaptured(quint64 request, const cv::Mat& grey, const QString& source, bool running);
  void setSlotNote(int slot, const QString& text, bool error);
  void refreshSlot(int slot);
  const CalibrationImageReport* runReport(int slot) const;
  void onRunUpdate(const CalibrationRunUpdate& update);
  void addIterationRow(const CalibrationIteration& it);
  void showField();
  void setRunStatus(const QString& text, bool error);
  void updateButtons();

  MainWindow& window_;
  QRadioButton* distortion_mode_ = nullptr;
  QRadioButton* intrinsics_mode_ = nullptr;
  QStackedWidget* pages_ = nullptr;
  IntrinsicsPage* intrinsics_ = nullptr;
  std::array<Slot, kCalibrationSlots> slots_;
  std::map<quint64, int> pending_captures_;  // capture request -> slot
  quint64 next_capture_ = 0;

  // The run in progress and the slots (with their image generations) it was given.
  QFutureWatcher<CalibrationRunUpdate>* run_ = nullptr;
  std::vector<int> run_slots_;
  std::vector<quint64> run_generations_;
  std::shared_ptr<const CalibrationResult> result_;
  CalibrationOptions run_options_;  // of the run in progress or the last one

  QPushButton* calibrate_ = nullptr;
  QPushButton* cancel_ = nullptr;
  QPushButton* set_and_use_ = nullptr;
  QPushButton* save_ = nullptr;
  QProgressBar* progress_ = nullptr;
  QLabel* run_status_ = nullptr;
  QTableWidget* table_ = nullptr;
  DistortionFieldView* field_ = nullptr;
  QLabel* field_caption_ = nullptr;
  QSpinBox* match_scale_ = nullptr;
};

// The window's one wizard (made on first use; it keeps its images while closed), shown and raised.
CalibrationWizard& showCalibrationWizard(MainWindow& window);

}  // namespace imagepro::app
