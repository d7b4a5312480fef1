#pragma once
// The calibration wizard's full intrinsic mode (core/calibration/intrinsics.h): the focal
// lengths, principal point and distortion of a camera nothing is known about, from 3 or
// more images (4-10 best) of a printed dot grid.
//  * The pattern: its kind (the thesis pattern, OpenCV's symmetric or asymmetric circle
//    grid), columns x rows (OpenCV's points per row x rows), spacing and dot diameter, and
//    the printable sheet written as PDF on an A4, Letter or A3 page, as `imagepro-cli
//    pattern` writes it.
//  * The images: files, or the running source's frame (captured through the wizard).
//  * Calibrate (k3 on request) runs on a thread of the pool with its progress (each image's grid search,
//    then the fit); Cancel stops it between images and drops its result.
//  * The quality report on its own tab (intrinsics_report_page.h).
//  * Set and Use gives the camera found to the settings' camera section, Save calibration
//    writes that section as a file; OpenCV's camera file is exported from the result and
//    imported into the settings' camera.
// Bad input (a description that cannot be, too few images, no grid found) is named in the
// status line, never run.
#include <QFutureWatcher>
#include <QWidget>

#include <atomic>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "core/calibration/dot_grid.h"
#include "core/calibration/intrinsics.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QListWidget;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QTabWidget;

namespace imagepro::app {

class CalibrationImageView;
class IntrinsicsReportPage;
class MainWindow;

// What the calibration thread hands back: progress, then the result.
struct IntrinsicsRunUpdate {
  int searched = 0, images = 0;  // grid searches done, of
  std::shared_ptr<const IntrinsicsResult> result;
};

class IntrinsicsPage : public QWidget {
  Q_OBJECT

 public:
  explicit IntrinsicsPage(MainWindow& window, QWidget* parent = nullptr);
  ~IntrinsicsPage() override;

  // The description in the fields (a thesis pattern takes its card and target from the settings).
  DotGridSpec spec() const;
  void setSpec(const DotGridSpec& spec);
  // Writes the printable sheet for the paper chosen; false with the error in the status line.
  bool writePatternPdf(const QString& path);

  // The buttons' actions, without their file dialogs.
  void addImageFiles(const QStringList& paths);
  void addImage(const cv::Mat& grey, const QString& origin);
  // A captured frame (the wizard asks the worker); empty: nothing to capture.
  void takeCapture(const cv::Mat& grey, const QString& origin);
  void removeImage(int index);
  void clearImages();
  void calibrate();
  void cancelCalibration();  // stops the run between images and drops it
  void setAndUse();
  bool saveCalibration(const QString& path);
  bool exportOpenCvCamera(const QString& path);
  bool importOpenCvCamera(const QString& path);

  int imageCount() const { return static_cast<int>(images_.size()); }
  QString imageStatus(int index) const;
  bool isCalibrating() const { return run_ != nullptr; }
  QString runStatus() const;
  // The last run that finished (whatever its status); nullptr before one has.
  const IntrinsicsResult* result() const { return result_.get(); }
  IntrinsicsReportPage* report() const { return report_; }
  QTabWidget* tabs() const { return tabs_; }
  CalibrationImageView* preview() const { return preview_; }

 signals:
  void captureRequested();
  void calibrationFinished(bool ok);
  void closeRequested();

 private:
  struct Image {
    cv::Mat grey;
    QString origin;
    quint64 id = 0;
  };

  QWidget* buildPatternBox();
  QWidget* buildImagesBox();
  QWidget* buildRunBox();
  QWidget* buildActions();
  void onKindChosen(int index);
  void onRunUpdate(const IntrinsicsRunUpdate& update);
  // The result's view of image `index`, when the last run had it.
  const IntrinsicsView* runView(int index) const;
  void refreshImages();
  void showPreview();
  void setRunStatus(const QString& text, bool error);
  void updateButtons();

  MainWindow& window_;
  std::vector<Image> images_;
  quint64 next_id_ = 0;

  QFutureWatcher<IntrinsicsRunUpdate>* run_ = nullptr;
  std::shared_ptr<std::atomic<bool>> run_cancelled_;
  std::vector<quint64> run_ids_;  // the images of the run in progress or the last one
  QStringList run_names_;         // and their names (an image may be removed meanwhile)
  std::shared_ptr<const IntrinsicsResult> result_;

  QTabWidget* tabs_ = nullptr;
  QComboBox* kind_ = nullptr;
  QSpinBox* columns_ = nullptr;
  QSpinBox* rows_ = nullptr;
  QDoubleSpinBox* spacing_ = nullptr;
  QDoubleSpinBox* diameter_ = nullptr;
  QComboBox* paper_ = nullptr;
  QListWidget* list_ = nullptr;
  CalibrationImageView* preview_ = nullptr;
  QPushButton* remove_ = nullptr;
  QPushButton* clear_ = nullptr;
  QCheckBox* fit_k3_ = nullptr;
  QPushButton* calibrate_ = nullptr;
  QPushButton* cancel_ = nullptr;
  QProgressBar* progress_ = nullptr;
  QLabel* run_status_ = nullptr;
  IntrinsicsReportPage* report_ = nullptr;
  QPushButton* set_and_use_ = nullptr;
  QPushButton* save_ = nullptr;
  QPushButton* export_ = nullptr;
};

}  // namespace imagepro::app
