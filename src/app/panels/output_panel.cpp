#include "app/panels/output_panel.h"

#include <QCheckBox>
#include <QFileInfo>
#include <QGridLayout>
#include <QLabel>
#include <QPushButton>

namespace imagepro::app {

namespace {
QPushButton* button(const QString& text, const char* name, const QString& tooltip) {
  auto* b = new QPushButton(text);
  b->setObjectName(QLatin1String(name));
  b->setToolTip(tooltip);
  return b;
}
}  // namespace

OutputPanel::OutputPanel(QWidget* parent)
    : QWidget(parent), data_out_(new QCheckBox(tr("Data Out"))), data_out_path_(new QLabel) {
  data_out_->setObjectName(QStringLiteral("dataOut"));
  data_out_->setToolTip(tr("Write the six parameters of every frame to a CSV file (thesis appendix A, dataout.txt)"));
  data_out_path_->setObjectName(QStringLiteral("dataOutPath"));
  data_out_path_->setWordWrap(true);
  auto* screenshot = button(tr("Screenshot"), "screenshot", tr("Save the results area as a PNG image (Ctrl+Shift+S)"));
  auto* settings = button(tr("Settings..."), "settingsDialog",
                          tr("Target dimensions, camera, distortion and the virtual target's motion (thesis appendix A, Settings menu)"));
  auto* save = button(tr("Save..."), "saveSettings", tr("Save every option to a settings JSON file (Ctrl+S)"));
  auto* load = button(tr("Load..."), "loadSettings", tr("Load the options from a settings JSON file (Ctrl+L)"));
  auto* defaults = button(tr("Defaults"), "restoreDefaults", tr("Restore every option to its default"));

  auto* grid = new QGridLayout(this);
  grid->setContentsMargins(0, 0, 0, 0);
  grid->addWidget(data_out_, 0, 0);
  grid->addWidget(screenshot, 0, 1, 1, 2);
  grid->addWidget(data_out_path_, 1, 0, 1, 3);
  grid->addWidget(settings, 2, 0, 1, 3);
  grid->addWidget(save, 3, 0);
  grid->addWidget(load, 3, 1);
  grid->addWidget(defaults, 3, 2);

  connect(data_out_, &QCheckBox::clicked, this, &OutputPanel::dataOutToggled);
  connect(screenshot, &QPushButton::clicked, this, &OutputPanel::screenshotRequested);
  connect(settings, &QPushButton::clicked, this, &OutputPanel::settingsDialogRequested);
  connect(save, &QPushButton::clicked, this, &OutputPanel::saveSettingsRequested);
  connect(load, &QPushButton::clicked, this, &OutputPanel::loadSettingsRequested);
  connect(defaults, &QPushButton::clicked, this, &OutputPanel::restoreDefaultsRequested);
}

void OutputPanel::setDataOutPath(const QString& path) {
  data_out_->setChecked(!path.isEmpty());
  data_out_path_->setText(path.isEmpty() ? QString() : tr("Writing %1").arg(QFileInfo(path).fileName()));
  data_out_path_->setToolTip(path);
}

}  // namespace imagepro::app
