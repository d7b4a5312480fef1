#pragma once
// What both modes of the calibration wizard build their pages from: buttons and status
// lines of one look, the calibration file, and a run on a thread of the pool whose
// updates reach the GUI thread.
#include <QFutureWatcher>
#include <QPromise>
#include <QThreadPool>

#include <memory>

#include "core/settings/settings.h"

class QGroupBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QString;

namespace imagepro::app {

QPushButton* wizardButton(const QString& text, const QString& name, const QString& tooltip);
// A status line: wrapped, selectable, at least `lines` high.
QLabel* wizardTextLabel(const QString& name, int lines);
// The text, in the error colour when `error`.
void showStatusText(QLabel* label, const QString& text, bool error);
// A bar at rest (empty, no text).
QProgressBar* wizardProgressBar(const QString& name);
void resetProgress(QProgressBar* bar);
// A run's box: start, cancel and the bar in a row, the status line below; its layout is a
// QVBoxLayout for what the page adds.
QGroupBox* wizardRunBox(const QString& title, QPushButton* start, QPushButton* cancel, QProgressBar* bar,
                        QLabel* status);

// Save calibration: the camera section of `calibrated` written as the calibration file
// (core/calibration/calibration_file.h); `message` says where, or why not.
bool saveCameraSection(const QString& path, const Settings& calibrated, QString& message);

// Runs task(promise) on a pool thread, which adds its updates to the promise; each reaches
// deliver(update) on `owner`'s thread until the run is released. The task owns copies of
// everything it reads: the owner may be gone when it ends.
template <class Update, class Task, class Deliver>
QFutureWatcher<Update>* startPoolRun(QObject* owner, Task task, Deliver deliver) {
  auto promise = std::make_shared<QPromise<Update>>();
  auto* watcher = new QFutureWatcher<Update>(owner);
  QObject::connect(watcher, &QFutureWatcherBase::resultReadyAt, owner,
                   [watcher, deliver](int index) { deliver(watcher->resultAt(index)); });
  watcher->setFuture(promise->future());
  promise->start();
  QThreadPool::globalInstance()->start([promise, task] {
    task(*promise);
    promise->finish();
  });
  return watcher;
}

// Drops a run: nothing more it sends reaches its owner (it ends in the background).
template <class Update>
void releaseRun(QFutureWatcher<Update>*& watcher, QObject* owner) {
  watcher->disconnect(owner);
  watcher->deleteLater();
  watcher = nullptr;
}

}  // namespace imagepro::app
