#pragma once
// The Internal Camera Calibration panel of thesis appendix A: the "calibration" check box
// (the live calibration check over the frame, core/calibration/calibration_check.h), the
// lens distortion the settings' camera has now, whether it is corrected, and the buttons
// that open the calibration wizard (calibration_wizard.h, thesis 4.6) and the image plane
// distance dialog (d0_dialog.h, thesis 4.1).
#include <QWidget>

#include "app/settings/settings_binder.h"

class QLabel;
class QPushButton;

namespace imagepro::app {

class CalibrationPanel : public QWidget {
  Q_OBJECT

 public:
  explicit CalibrationPanel(SettingsBinder& binder, QWidget* parent = nullptr);

  QPushButton* wizardButton() const { return wizard_; }
  QPushButton* d0Button() const { return d0_; }

 signals:
  void wizardRequested();
  void d0Requested();

 private:
  QLabel* readout_;
  QPushButton* wizard_;
  QPushButton* d0_;
};

}  // namespace imagepro::app
