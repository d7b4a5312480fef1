#include "app_test_support.h"

#include <QCoreApplication>
#include <QDir>
#include <QElapsedTimer>
#include <QTest>

#include "app/frame_view.h"
#include "app/worker.h"

namespace imagepro::app::test {

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

}  // namespace imagepro::app::test
