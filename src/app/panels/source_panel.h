#pragma once
// Input Source panel (thesis appendix A): File, Camera or Virtual, and one button that
// reads "Start" / "Stop" for the live sources and for a list of images or a video open
// on the File source, "Open File..." when File has nothing to play. With a list of
// images open, a row below steps through it (first, previous, next, last) and says which
// image is shown; the line under it names the source in use.
#include <QWidget>

#include "app/worker/source_kind.h"

class QComboBox;
class QLabel;
class QPushButton;
class QToolButton;

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
  QString description() const;
  // What the File source has open: -1 nothing, 0 a video, n a list of n images.
  void setFileCount(int count);
  int fileCount() const { return file_count_; }
  // The image shown of the open list (from 0).
  void setFileIndex(int index);
  // True when Start has something to start: a live source, or a list or video on File.
  bool canStart() const;
  QPushButton* button() const { return button_; }
  QComboBox* combo() const { return combo_; }
  QWidget* fileRow() const { return file_row_; }
  QLabel* filePosition() const { return position_; }

 signals:
  void kindChanged(imagepro::SourceKind kind);
  void openFileRequested();
  void startRequested(imagepro::SourceKind kind);
  void stopRequested();
  void stepRequested(imagepro::app::FileStep step);

 private:
  void updateButton();
  QToolButton* stepButton(FileStep step, const QString& text, const char* name, const QString& tooltip);

  QComboBox* combo_;
  QPushButton* button_;
  QWidget* file_row_;
  QLabel* position_;
  QLabel* description_;
  bool running_ = false;
  int file_count_ = -1;
  int file_index_ = -1;
};

}  // namespace imagepro::app
