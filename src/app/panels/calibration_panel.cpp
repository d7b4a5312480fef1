#include "app/panels/calibration_panel.h"

#include <QFontDatabase>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>

namespace imagepro::app {

CalibrationPanel::CalibrationPanel(SettingsBinder& binder, QWidget* parent)
    : QWidget(parent), readout_(new QLabel), wizard_(new QPushButton(tr("Calibration Wizard..."))) {
  readout_->setObjectName(QStringLiteral("calibrationReadout"));
  readout_->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
  readout_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  readout_->setToolTip(tr("The lens distortion of the settings' camera (thesis eq. 4.7), found by the calibration of "
                          "thesis 4.6 or typed in Settings"));
  wizard_->setObjectName(QStringLiteral("calibrationWizardButton"));
  wizard_->setToolTip(tr("Lens distortion calibration (thesis 4.6): up to four images of the calibration pattern, "
                         "Calibrate, then Set and Use for the source in use (thesis appendix A.2.2)"));
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(readout_);
  layout->addWidget(wizard_);
  connect(wizard_, &QPushButton::clicked, this, &CalibrationPanel::wizardRequested);
  binder.onAnyUpdate([this, &binder] {
    const Settings& s = binder.model();
    const Distortion& d = s.camera.distortion;
    readout_->setText(tr("k1 %1  k2 %2\np1 %3  p2 %4\ncorrection %5")
                          .arg(d.k1, 0, 'e', 2)
                          .arg(d.k2, 0, 'e', 2)
                          .arg(d.p1, 0, 'e', 2)
                          .arg(d.p2, 0, 'e', 2)
                          .arg(s.pipeline.reconstruction.distortion_correction ? tr("on") : tr("off")));
  });
}

}  // namespace imagepro::app
