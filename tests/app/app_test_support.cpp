#include "app_test_support.h"

#include <QCoreApplication>
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QFileDialog>
#include <QLineEdit>
#include <QTest>
#include <QTimer>

#include "app/main_window/frame_view.h"
#include "app/worker/worker.h"

#include <QThread>

#include <ctime>

namespace imagepro::app::test {

namespace {
double threadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}
}  // namespace

QString numberedFolder(const QString& name, int n) {
  const QString samples = QStringLiteral(IMAGEPRO_DATA_DIR "/samples/");
  const QString dir = scratchDir(name);
  const QStringList names{QStringLiteral("sample01_facing.png"), QStringLiteral("sample02_clutter.png"),
                          QStringLiteral("sample03_tilted50.png")};
  for (int i = 1; i <= n; ++i)
    QFile::copy(samples + names[(i - 1) % names.size()], QStringLiteral("%1/img%2.png").arg(dir).arg(i));
  return dir;
}

bool ProbeApplication::notify(QObject* receiver, QEvent* event) {
  // Only outermost events of the GUI thread: nested ones are part of their parent's time.
  if (!probing || depth_ > 0 || QThread::currentThread() != thread()) return QApplication::notify(receiver, event);
  ++depth_;
  QElapsedTimer wall;
  wall.start();
  const double cpu0 = threadCpuMs();
  const bool handled = QApplication::notify(receiver, event);
  const double cpu = threadCpuMs() - cpu0;
  const double ms = wall.nsecsElapsed() / 1e6;
  --depth_;
  if (cpu > worst_cpu_ms) {
    worst_cpu_ms = cpu;
    worst_wall_ms = std::max(worst_wall_ms, ms);
    worst_what = QStringLiteral("%1 \"%2\" event %3")
                     .arg(QLatin1String(receiver->metaObject()->className()), receiver->objectName())
                     .arg(static_cast<int>(event->type()));
  }
  worst_wall_ms = std::max(worst_wall_ms, ms);
  return handled;
}

QString scratchDir(const QString& name) {
  QDir dir(QStringLiteral(IMAGEPRO_TEST_TMP "/app/") + name);
  dir.removeRecursively();
  QDir().mkpath(dir.path());
  return dir.path();
}

bool waitForFrame(MainWindow& window, const std::function<bool(const FrameResult&)>& pred, int ms) {
  QElapsedTimer clock;
  clock.start();
  while (clock.elapsed() < ms) {
    const DisplayPacketPtr& packet = window.frameView()->packet();
    if (packet && pred(packet->result)) return true;
    QTest::qWait(10);
  }
  return false;
}

bool waitForApplied(MainWindow& window, const std::function<bool(const Settings&)>& pred, int ms) {
  QElapsedTimer clock;
  clock.start();
  while (clock.elapsed() < ms) {
    if (pred(window.worker()->appliedSettings())) return true;
    QTest::qWait(10);
  }
  return false;
}

void answerFileDialog(FileDialogAnswer& answer, const QString& name, int wait_ms) {
  answer = {};
  QTimer::singleShot(0, qApp, [&answer, name, wait_ms] {
    QFileDialog* dialog = nullptr;
    for (int i = 0; i < wait_ms / 10 && !dialog; ++i) {
      dialog = qobject_cast<QFileDialog*>(QApplication::activeModalWidget());
      if (!dialog) QTest::qWait(10);
    }
    if (!dialog) return;
    answer.seen = true;
    answer.directory = dialog->directory().absolutePath();
    if (name.isEmpty()) {
      static_cast<QDialog*>(dialog)->reject();
      return;
    }
    // The name typed in (selectFile keeps the suggested name here).
    if (auto* edit = dialog->findChild<QLineEdit*>(QStringLiteral("fileNameEdit"))) edit->setText(name);
    else dialog->selectFile(name);
    static_cast<QDialog*>(dialog)->accept();  // public as QDialog's
  });
}

}  // namespace imagepro::app::test
