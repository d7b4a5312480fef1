#pragma once
// Shared helpers of the application tests: scratch folders, waiting for the frame
// the worker sends, and driving the control panel's widgets.
#include <QAbstractButton>
#include <QApplication>
#include <QComboBox>
#include <QString>
#include <QWidget>

#include <functional>

#include "app/main_window/main_window.h"
#include "app/settings/enum_text.h"

namespace imagepro::app::test {

// The test application: while `probing`, measures how long the GUI thread spends in
// each event it handles, in wall time and in the thread's own CPU time (the latter
// does not count waiting for a CPU on a busy machine).
class ProbeApplication : public QApplication {
 public:
  using QApplication::QApplication;
  bool notify(QObject* receiver, QEvent* event) override;

  bool probing = false;
  double worst_wall_ms = 0.0;
  double worst_cpu_ms = 0.0;
  QString worst_what;

 private:
  int depth_ = 0;
};

// An empty folder IMAGEPRO_TEST_TMP/app/<name>.
QString scratchDir(const QString& name);

// A folder IMAGEPRO_TEST_TMP/app/<name> of `n` images img1.png ... imgN.png, the samples
// facing, clutter and tilted in turn.
QString numberedFolder(const QString& name, int n);

// Processes events until the shown frame satisfies `pred` (false after `ms`).
bool waitForFrame(MainWindow& window, const std::function<bool(const FrameResult&)>& pred, int ms = 15000);
// Until the worker runs with settings satisfying `pred`.
bool waitForApplied(MainWindow& window, const std::function<bool(const Settings&)>& pred, int ms = 5000);

// Answers the next modal file dialog as the user would: notes the folder it opened in,
// then types `name` and accepts it, or with no name cancels it. Call before the action
// that opens the dialog; `seen` stays false if no dialog came within `wait_ms`.
struct FileDialogAnswer {
  bool seen = false;
  QString directory;
};
void answerFileDialog(FileDialogAnswer& answer, const QString& name = {}, int wait_ms = 5000);

// Selects `value` in a combo box built from the enum's table, where it shows its
// display name; false if absent.
template <class E>
bool choose(QComboBox* box, E value) {
  if (!box) return false;
  const int i = box->findData(static_cast<int>(value));
  if (i < 0 || box->itemText(i) != labelOf(value)) return false;
  box->setCurrentIndex(i);
  return true;
}

// Clicks the radio button that shows `value`'s display name inside the widget `group`.
template <class E>
bool chooseRadio(QWidget* group, E value) {
  if (!group) return false;
  for (QAbstractButton* b : group->findChildren<QAbstractButton*>()) {
    if (b->text() == labelOf(value)) {
      b->click();
      return true;
    }
  }
  return false;
}

}  // namespace imagepro::app::test
