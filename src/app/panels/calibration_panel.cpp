#include "app/panels/calibration_panel.h"

#include <QCheckBox>
#include <QFontDatabase>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>

namespace imagepro::app {

CalibrationPanel::CalibrationPanel(SettingsBinder& binder, QWidget* parent)
    : QWidget(parent), readout_(new QLabel), wizard_(new QPushButton(tr("Calibration Wizard..."))),
      d0_(new QPushButton(tr("Image Plane Distance d0..."))) {
  readout_->setObjectName(QStringLiteral("calibrationReadout"));
  readout_->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
  readout_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  readout_->setToolTip(tr("The lens distortion of the settings' camera (thesis eq. 4.7), found by the calibration of "
                          "thesis 4.6 or typed in Settings"));
  wizard_->setObjectName(QStringLiteral("calibrationWizardButton"));
  wizard_->setToolTip(tr("Lens distortion calibration (thesis 4.6): up to four images of the calibration pattern, "
                         "Calibrate, then Set and Use for the source in use (thesis appendix A.2.2)"));
  QCheckBox* check =
      binder.check(tr("Calibration check"), [](Settings& s) -> auto& { return s.pipeline.display.calibration_check; });
  check->setObjectName(QStringLiteral("calibrationCheck"));
  check->setToolTip(tr("Draw the calibration pattern's ideal spot positions (red, from its target's pose: thesis 4.6 "
                       "step 4), the spots found (cyan, step 5) and their matching (yellow, step 6) over the live "
                       "frame, to place the pattern before capturing its images (thesis A.1.1)"));
  d0_->setObjectName(QStringLiteral("d0DialogButton"));
  d0_->setToolTip(tr("The image plane distance d0 from frames of the target at known distances, by the iteration "
                     "of thesis eq. 4.1 from the lens's focal length"));
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(check);
  layout->addWidget(readout_);
  layout->addWidget(wizard_);
  layout->addWidget(d0_);
  connect(wizard_, &QPushButton::clicked, this, &CalibrationPanel::wizardRequested);
  connect(d0_, &QPushButton::clicked, this, &CalibrationPanel::d0Requested);
  binder.onAnyUpdate([this, &binder] {
    const Settings& s = binder.model();
    const Distortion& d = s.camera().distortion;
    readout_->setText(tr("k1 %1  k2 %2\np1 %3  p2 %4\ncorrection %5")
                          .arg(d.k1, 0, 'e', 2)
                          .arg(d.k2, 0, 'e', 2)
                          .arg(d.p1, 0, 'e', 2)
                          .arg(d.p2, 0, 'e', 2)
                          .arg(s.pipeline.reconstruction.distortion_correction ? tr("on") : tr("off")));
  });
}

}  // namespace imagepro::app
