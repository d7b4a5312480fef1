// MainWindow: drag and drop of images and folders, the appendix A keys, and the keys
// that step through the File source's images.
#include <QAbstractItemView>
#include <QAbstractSpinBox>
#include <QComboBox>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QKeyEvent>
#include <QLineEdit>
#include <QMimeData>

#include "app/panels/control_panel.h"
#include "app/main_window/main_window.h"
#include "app/panels/source_panel.h"
#include "app/main_window/virtual_keys.h"
#include "app/worker/worker.h"
#include "app/main_window/dialog_folder.h"

namespace imagepro::app {

namespace {

QStringList localPaths(const QMimeData* mime) {
  QStringList paths;
  if (!mime || !mime->hasUrls()) return paths;
  for (const QUrl& url : mime->urls())
    if (url.isLocalFile()) paths << url.toLocalFile();
  return paths;
}

// Widgets that need the digits and arrows themselves.
bool editsText(const QObject* o) {
  for (; o; o = o->parent()) {
    if (qobject_cast<const QAbstractSpinBox*>(o) || qobject_cast<const QLineEdit*>(o) ||
        qobject_cast<const QComboBox*>(o) || qobject_cast<const QAbstractItemView*>(o))
      return true;
    if (o->isWidgetType() && static_cast<const QWidget*>(o)->isWindow()) break;
  }
  return false;
}

std::optional<FileStep> fileStepFor(int key) {
  switch (key) {
    case Qt::Key_Home: return FileStep::First;
    case Qt::Key_Left:
    case Qt::Key_PageUp: return FileStep::Previous;
    case Qt::Key_Right:
    case Qt::Key_PageDown: return FileStep::Next;
    case Qt::Key_End: return FileStep::Last;
    default: return std::nullopt;
  }
}

}  // namespace

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
  if (!localPaths(event->mimeData()).isEmpty()) event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
  const QStringList paths = localPaths(event->mimeData());
  if (paths.isEmpty()) return;
  event->acceptProposedAction();
  rememberDialogFolder(paths.front());
  openPaths(paths);
}

bool MainWindow::eventFilter(QObject* watched, QEvent* event) {
  if (event->type() != QEvent::KeyPress) return QMainWindow::eventFilter(watched, event);
  // Only key presses meant for this window, and not those a field needs.
  auto* widget = qobject_cast<QWidget*>(watched);
  if (!widget || widget->window() != this || editsText(watched)) return QMainWindow::eventFilter(watched, event);
  const auto* key_event = static_cast<QKeyEvent*>(event);
  if (key_event->modifiers() & (Qt::ControlModifier | Qt::AltModifier | Qt::MetaModifier))
    return QMainWindow::eventFilter(watched, event);
  const SourceKind kind = control_panel_->sourcePanel()->kind();
  if (kind == SourceKind::File) {
    const std::optional<FileStep> step = fileStepFor(key_event->key());
    if (!step || control_panel_->sourcePanel()->fileCount() < 2) return QMainWindow::eventFilter(watched, event);
    stepFile(*step);
    return true;
  }
  if (kind != SourceKind::Virtual) return QMainWindow::eventFilter(watched, event);
  const std::optional<VirtualKey> key = virtualKeyFor(key_event->key());
  if (!key) return QMainWindow::eventFilter(watched, event);
  worker_->pressKey(*key);
  return true;  // consumed: it must not also move focus or scroll
}

}  // namespace imagepro::app
