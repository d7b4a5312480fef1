#pragma once
// The Internal Camera Calibration panel of thesis appendix A: the lens distortion the
// settings' camera has now, whether it is corrected, and the button that opens the
// calibration wizard (calibration_wizard.h, thesis 4.6).
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

 signals:
  void wizardRequested();

 private:
  QLabel* readout_;
  QPushButton* wizard_;
};

}  // namespace imagepro::app
