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

 signals:
  void dataOutToggled(bool on);
  void screenshotRequested();
  void settingsDialogRequested();
  void saveSettingsRequested();
  void loadSettingsRequested();
  void restoreDefaultsRequested();

 private:
  QCheckBox* data_out_;
  QLabel* data_out_path_;
  QCheckBox* stream_;
};

}  // namespace imagepro::app
