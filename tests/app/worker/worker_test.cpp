// The worker thread on its own: it processes frames whether or not the GUI keeps
// up, sends at most one undisplayed packet, and applies settings between frames.
#include <QSignalSpy>
#include <QTest>
#include <QThread>

#include <opencv2/imgcodecs.hpp>

#include <cmath>

#include "app/worker/worker.h"
#include "app_test_classes.h"
#include "app_test_support.h"
#include "core/source/virtual_renderer.h"

namespace imagepro::app::test {

namespace {

// A worker in its own thread, torn down like the main window does it.
struct WorkerThread {
  explicit WorkerThread(const Settings& settings) : worker(new Worker(settings)) {
    worker->moveToThread(&thread);
    QObject::connect(&thread, &QThread::finished, worker, &QObject::deleteLater);
    thread.start();
  }
  ~WorkerThread() {
    worker->stop();
    thread.quit();
    thread.wait();
  }
  QThread thread;
  Worker* worker;
};

// Keeps the latest packet in `last`, each marked displayed so that the next one comes.
void keepLatest(WorkerThread& w, QObject& context, DisplayPacketPtr& last) {
  QObject::connect(w.worker, &Worker::packetReady, &context, [&w, &last](const DisplayPacketPtr& p) {
    last = p;
    w.worker->markDisplayed();
  });
}

Settings fastVirtual() {
  Settings s;
  s.virtual_scene.frame_rate_hz = 500.0;
  s.virtual_scene.mode = RenderMode::Binary;
  return s;
}

}  // namespace

void WorkerTest::latestFrameWins() {
  WorkerThread w(fastVirtual());
  std::vector<DisplayPacketPtr> received;
  QObject context;
  QObject::connect(w.worker, &Worker::packetReady, &context, [&](const DisplayPacketPtr& p) { received.push_back(p); });
  w.worker->start(SourceKind::Virtual);
  QTRY_VERIFY_WITH_TIMEOUT(w.worker->framesProcessed() >= 30, 20000);
  QTest::qWait(50);
  // Nothing was marked displayed: one packet went out, the later frames were not queued.
  QCOMPARE(received.size(), std::size_t{1});
  const std::int64_t processed = w.worker->framesProcessed();
  w.worker->markDisplayed();
  QTRY_COMPARE_WITH_TIMEOUT(received.size(), std::size_t{2}, 5000);
  QTest::qWait(50);
  QCOMPARE(received.size(), std::size_t{2});
  // The second packet is a recent frame and carries the pose history of every frame since the first.
  const DisplayPacket& second = *received[1];
  QVERIFY(second.result.index >= processed - 1);
  QCOMPARE(static_cast<std::int64_t>(second.history.size()), second.result.index - received[0]->result.index);
  QCOMPARE(second.history.back().index, second.result.index);
  for (std::size_t i = 1; i < second.history.size(); ++i)
    QCOMPARE(second.history[i].index, second.history[i - 1].index + 1);
  QCOMPARE(second.history.front().index, received[0]->result.index + 1);
}

void WorkerTest::settingsApplyAtTheNextFrame() {
  WorkerThread w(fastVirtual());
  DisplayPacketPtr last;
  QObject context;
  keepLatest(w, context, last);
  w.worker->start(SourceKind::Virtual);
  QTRY_VERIFY_WITH_TIMEOUT(last != nullptr, 10000);
  QVERIFY(w.worker->isRunning());

  Settings manual = fastVirtual();
  manual.pipeline.threshold.method = ThresholdMethod::Manual;
  manual.pipeline.threshold.manual_value = 99;
  manual.pipeline.level = ApplicationLevel::Threshold;
  w.worker->setSettings(manual);
  // Without stopping: the frames after the change use the manual threshold and stop at thresholding.
  QTRY_VERIFY_WITH_TIMEOUT(last->result.threshold == 99 && last->result.reached == ApplicationLevel::Threshold, 10000);
  QVERIFY(w.worker->isRunning());
  QCOMPARE(w.worker->appliedSettings().pipeline.threshold.manual_value, 99);
  // The display options decide which images travel: at the threshold level with a
  // binary background the packet carries the binary region and no edge list.
  manual.pipeline.display.background = DisplayOptions::Background::Binary;
  manual.pipeline.display.edges = DisplayOptions::Edges::EdgePixels;
  w.worker->setSettings(manual);
  QTRY_VERIFY_WITH_TIMEOUT(last->display.background == DisplayOptions::Background::Binary, 10000);
  QVERIFY(last->background.isNull());
  QVERIFY(!last->binary.isNull());
  QVERIFY(last->edge_overlay.isNull());

  QSignalSpy stopped(w.worker, &Worker::runningChanged);
  w.worker->stop();
  QTRY_VERIFY(!w.worker->isRunning());
  const std::int64_t frames = w.worker->framesProcessed();
  QTest::qWait(100);
  QCOMPARE(w.worker->framesProcessed(), frames);
}

// Each source's frames are reconstructed with that source's camera model, whatever the
// settings handed over say is in use: a File camera with twice the image plane distance
// puts the same picture of a target facing the camera twice as far away.
void WorkerTest::reconstructsWithTheRunningSourcesCamera() {
  Settings s = fastVirtual();
  s.camera(SourceKind::File).image_plane_distance_mm = 2.0 * s.camera(SourceKind::Virtual).image_plane_distance_mm;
  s.source = SourceKind::File;  // not the worker's to follow: it runs the Virtual source first
  const double tz = s.virtual_scene.initial_pose.tz_mm;
  const QString file = scratchDir(QStringLiteral("worker_cameras")) + QStringLiteral("/facing.png");
  cv::Mat grey;
  renderTarget(s.camera(SourceKind::Virtual), s.target, s.virtual_scene, s.virtual_scene.initial_pose, grey);
  QVERIFY(cv::imwrite(file.toStdString(), grey));

  WorkerThread w(s);
  DisplayPacketPtr last;
  QObject context;
  keepLatest(w, context, last);
  w.worker->start(SourceKind::Virtual);
  QTRY_VERIFY_WITH_TIMEOUT(last && last->result.pose, 10000);
  QVERIFY2(std::abs(last->result.pose->tz_mm - tz) < 0.01 * tz, qPrintable(QString::number(last->result.pose->tz_mm)));
  w.worker->stop();
  QTRY_VERIFY_WITH_TIMEOUT(!w.worker->isRunning(), 5000);

  last.reset();
  w.worker->openFiles({file});
  QTRY_VERIFY_WITH_TIMEOUT(last && !last->result.name.empty() && last->result.pose, 10000);
  QVERIFY2(std::abs(last->result.pose->tz_mm - 2.0 * tz) < 0.01 * tz, qPrintable(QString::number(last->result.pose->tz_mm)));
}

}  // namespace imagepro::app::test
