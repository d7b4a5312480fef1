#include "app/calibration_wizard/wizard_widgets.h"

#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QVBoxLayout>

#include "core/calibration/calibration_file.h"

namespace imagepro::app {

QPushButton* wizardButton(const QString& text, const QString& name, const QString& tooltip) {
  auto* b = new QPushButton(text);
  b->setObjectName(name);
  b->setToolTip(tooltip);
  return b;
}

QLabel* wizardTextLabel(const QString& name, int lines) {
  auto* l = new QLabel;
  l->setObjectName(name);
  l->setWordWrap(true);
  l->setAlignment(Qt::AlignLeft | Qt::AlignTop);
  l->setMinimumHeight(lines * l->fontMetrics().lineSpacing());
  l->setTextInteractionFlags(Qt::TextSelectableByMouse);
  return l;
}

void showStatusText(QLabel* label, const QString& text, bool error) {
  label->setText(text);
  label->setStyleSheet(error ? QStringLiteral("color: #b00020;") : QString());
}

QProgressBar* wizardProgressBar(const QString& name) {
  auto* bar = new QProgressBar;
  bar->setObjectName(name);
  resetProgress(bar);
  return bar;
}

void resetProgress(QProgressBar* bar) {
  bar->setRange(0, 1);
  bar->setValue(0);
  bar->setFormat(QString());
}

QGroupBox* wizardRunBox(const QString& title, QPushButton* start, QPushButton* cancel, QProgressBar* bar,
                        QLabel* status) {
  auto* row = new QHBoxLayout;
  row->addWidget(start);
  row->addWidget(cancel);
  row->addWidget(bar, 1);
  auto* box = new QGroupBox(title);
  auto* layout = new QVBoxLayout(box);
  layout->addLayout(row);
  layout->addWidget(status);
  return box;
}

bool saveCameraSection(const QString& path, const Settings& calibrated, QString& message) {
  std::string error;
  if (!writeCalibrationFile(path.toStdString(), calibrated, error)) {
    message = QObject::tr("Calibration not saved: %1").arg(QString::fromStdString(error));
    return false;
  }
  message = QObject::tr("Calibration saved to %1 (load it with Load Settings or imagepro-cli --config).").arg(path);
  return true;
}

}  // namespace imagepro::app
