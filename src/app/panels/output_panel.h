#pragma once
// Data Out, Screenshot and Settings controls (thesis appendix A), plus saving,
// loading and restoring the settings file, and the live pose stream (its settings
// section: on or off, host, port, format).
#include <QWidget>

class QCheckBox;
class QLabel;
class QPushButton;

namespace imagepro::app {

class SettingsBinder;

class OutputPanel : public QWidget {
  Q_OBJECT

 public:
  explicit OutputPanel(SettingsBinder& binder, QWidget* parent = nullptr);

  // Shows the file Data Out writes to; an empty path unticks the box.
  void setDataOutPath(const QString& path);
  QCheckBox* dataOutBox() const { return data_out_; }
  QCheckBox* streamBox() const { return stream_; }
  // The screenshot option: freeze processing while the screenshot is being saved.
  void setFreezeOnScreenshot(bool on);
  QCheckBox* freezeBox() const { return freeze_; }

 signals:
  void dataOutToggled(bool on);
  void screenshotRequested();
  void freezeOnScreenshotToggled(bool on);
  void settingsDialogRequested();
  void saveSettingsRequested();
  void loadSettingsRequested();
  void restoreDefaultsRequested();

 private:
  QCheckBox* data_out_;
  QCheckBox* freeze_;
  QLabel* data_out_path_;
  QCheckBox* stream_;
};

}  // namespace imagepro::app
