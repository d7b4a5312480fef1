#include "app/panels/output_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFileInfo>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSpinBox>

#include "app/settings/settings_binder.h"

namespace imagepro::app {

namespace {
QPushButton* button(const QString& text, const char* name, const QString& tooltip) {
  auto* b = new QPushButton(text);
  b->setObjectName(QLatin1String(name));
  b->setToolTip(tooltip);
  return b;
}
}  // namespace

OutputPanel::OutputPanel(SettingsBinder& binder, QWidget* parent)
    : QWidget(parent),
      data_out_(new QCheckBox(tr("Data Out"))),
      freeze_(new QCheckBox(tr("Freeze"))),
      data_out_path_(new QLabel),
      stream_(binder.check(tr("Stream"), [](Settings& s) -> auto& { return s.stream.enabled; })) {
  data_out_->setObjectName(QStringLiteral("dataOut"));
  data_out_->setToolTip(tr("Write the six parameters of every frame to a CSV file (thesis appendix A, dataout.txt)"));
  data_out_path_->setObjectName(QStringLiteral("dataOutPath"));
  data_out_path_->setWordWrap(true);
  auto* screenshot = button(tr("Screenshot"), "screenshot", tr("Save the results area as a PNG image (Ctrl+Shift+S)"));
  freeze_->setObjectName(QStringLiteral("screenshotFreeze"));
  freeze_->setToolTip(tr("Screenshot freezes the processing of a running source while its file is chosen, and "
                         "resumes it after (thesis appendix A.1.1)"));
  auto* settings = button(tr("Settings..."), "settingsDialog",
                          tr("Target dimensions, camera, distortion and the virtual target's motion (thesis appendix A, Settings menu)"));
  auto* save = button(tr("Save..."), "saveSettings", tr("Save every option to a settings JSON file (Ctrl+S)"));
  auto* load = button(tr("Load..."), "loadSettings", tr("Load the options from a settings JSON file (Ctrl+L)"));
  auto* defaults = button(tr("Defaults"), "restoreDefaults", tr("Restore every option to its default"));

  // The live stream: every frame to host:port as it is made (docs/streaming.md).
  stream_->setObjectName(QStringLiteral("stream"));
  stream_->setToolTip(tr("Send every frame's pose as it is made, one UDP datagram a frame, to the host and port "
                         "beside; the status bar counts what was sent and dropped"));
  QLineEdit* host = binder.text([](Settings& s) -> auto& { return s.stream.host; });
  host->setObjectName(QStringLiteral("streamHost"));
  host->setToolTip(tr("Where the stream goes: a host name, an IPv4 or an IPv6 address"));
  QSpinBox* port = binder.intSpin([](Settings& s) -> auto& { return s.stream.port; });
  port->setObjectName(QStringLiteral("streamPort"));
  port->setToolTip(tr("The UDP port the reader listens on"));
  QComboBox* format = binder.combo<StreamFormat>([](Settings& s) -> auto& { return s.stream.format; });
  format->setObjectName(QStringLiteral("streamFormat"));
  auto* destination = new QHBoxLayout;
  destination->addWidget(host, 1);
  destination->addWidget(new QLabel(QStringLiteral(":")));
  destination->addWidget(port);

  auto* grid = new QGridLayout(this);
  grid->setContentsMargins(0, 0, 0, 0);
  grid->addWidget(data_out_, 0, 0);
  grid->addWidget(screenshot, 0, 1);
  grid->addWidget(freeze_, 0, 2);
  grid->addWidget(data_out_path_, 1, 0, 1, 3);
  grid->addWidget(stream_, 2, 0);
  grid->addWidget(format, 2, 1, 1, 2);
  grid->addLayout(destination, 3, 0, 1, 3);
  grid->addWidget(settings, 4, 0, 1, 3);
  grid->addWidget(save, 5, 0);
  grid->addWidget(load, 5, 1);
  grid->addWidget(defaults, 5, 2);

  connect(data_out_, &QCheckBox::clicked, this, &OutputPanel::dataOutToggled);
  connect(screenshot, &QPushButton::clicked, this, &OutputPanel::screenshotRequested);
  connect(freeze_, &QCheckBox::toggled, this, &OutputPanel::freezeOnScreenshotToggled);
  connect(settings, &QPushButton::clicked, this, &OutputPanel::settingsDialogRequested);
  connect(save, &QPushButton::clicked, this, &OutputPanel::saveSettingsRequested);
  connect(load, &QPushButton::clicked, this, &OutputPanel::loadSettingsRequested);
  connect(defaults, &QPushButton::clicked, this, &OutputPanel::restoreDefaultsRequested);
}

void OutputPanel::setFreezeOnScreenshot(bool on) {
  const QSignalBlocker quiet(freeze_);
  freeze_->setChecked(on);
}

void OutputPanel::setDataOutPath(const QString& path) {
  data_out_->setChecked(!path.isEmpty());
  data_out_path_->setText(path.isEmpty() ? QString() : tr("Writing %1").arg(QFileInfo(path).fileName()));
  data_out_path_->setToolTip(path);
}

}  // namespace imagepro::app
