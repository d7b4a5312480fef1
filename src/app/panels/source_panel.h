#pragma once
// Input Source panel (thesis appendix A): File, Camera or Virtual, and one button
// that reads "Open File" for files and "Start" / "Stop" for the live sources.
#include <QWidget>

#include "app/worker/source_kind.h"

class QComboBox;
class QLabel;
class QPushButton;

namespace imagepro::app {

class SourcePanel : public QWidget {
  Q_OBJECT

 public:
  explicit SourcePanel(QWidget* parent = nullptr);

  SourceKind kind() const;
  void setKind(SourceKind kind);
  bool isRunning() const { return running_; }
  void setRunning(bool running);
  void setDescription(const QString& text);
  QPushButton* button() const { return button_; }
  QComboBox* combo() const { return combo_; }

 signals:
  void kindChanged(imagepro::SourceKind kind);
  void openFileRequested();
  void startRequested(imagepro::SourceKind kind);
  void stopRequested();

 private:
  void updateButton();

  QComboBox* combo_;
  QPushButton* button_;
  QLabel* description_;
  bool running_ = false;
};

}  // namespace imagepro::app
