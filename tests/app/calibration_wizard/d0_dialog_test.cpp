// The d0 dialog (thesis 4.1): frames of the target at a known distance, rendered with a known
// d0, give that d0 whatever the settings' camera says; the chart shows each frame's
// iteration from f to it; Set d0 gives the mean to the settings; Capture takes the running
// source's frame.
#include <QChart>
#include <QLabel>
#include <QLineSeries>
#include <QPushButton>
#include <QTableWidget>
#include <QTest>

#include <opencv2/imgcodecs.hpp>

#include "app/calibration_wizard/d0_dialog.h"
#include "app/main_window/main_window.h"
#include "app/worker/worker.h"
#include "app_test_classes.h"
#include "app_test_support.h"
#include "core/source/virtual_renderer.h"

namespace imagepro::app::test {

namespace {

constexpr double kTrueD0 = 12.0;
constexpr double kDistance = 1000.0;

// Thin lens: the focal length that images depth z at distance d0.
double focalLength(double d0, double z) { return d0 * z / (d0 + z); }

}  // namespace

void D0DialogTest::init() {
  window_ = std::make_unique<MainWindow>();
  Settings s;
  s.camera().image_plane_distance_mm = kTrueD0;
  s.virtual_scene.frame_rate_hz = 50.0;
  window_->setSettings(s);
  window_->show();
}

void D0DialogTest::cleanup() { window_.reset(); }

void D0DialogTest::virtualFramesGiveTheirKnownD0() {
  MainWindow& w = *window_;
  w.findChild<QPushButton*>(QStringLiteral("d0DialogButton"))->click();
  auto* dialog = w.findChild<D0Dialog*>();
  QVERIFY(dialog && dialog->isVisible());
  const double f = focalLength(kTrueD0, kDistance);
  dialog->setFocalLength(f);
  dialog->setKnownDistance(kDistance);
  dialog->findChild<QPushButton*>(QStringLiteral("d0Render"))->click();
  // A second view of the same lens from a file, turned otherwise.
  Settings rendering = w.settings();
  cv::Mat image;
  renderTarget(rendering.camera(), rendering.target, rendering.virtual_scene, Pose{-25, 10, 120, -60, 40, kDistance},
               image);
  const QString path = scratchDir(QStringLiteral("d0_dialog")) + QStringLiteral("/target.png");
  QVERIFY(cv::imwrite(path.toStdString(), image));
  // The settings' own d0 is not what is estimated: put a wrong one in first.
  rendering.camera().image_plane_distance_mm = 8.0;
  w.setSettings(rendering);
  QVERIFY(dialog->openImage(path));
  QCOMPARE(dialog->entries().size(), size_t(2));

  for (const D0Dialog::Entry& e : dialog->entries()) {
    QCOMPARE(e.estimate.status, Status::Ok);
    QVERIFY(std::abs(e.estimate.estimate.d0_mm - kTrueD0) < 2e-3);
    QVERIFY(std::abs(e.estimate.estimate.depth_mm - kDistance) < 2.0);
    QCOMPARE(e.distance_mm, kDistance);
  }
  QTableWidget* table = dialog->table();
  QCOMPARE(table->rowCount(), 2);
  QVERIFY(std::abs(table->item(0, 4)->text().toDouble() - kTrueD0) < 2e-3);
  QVERIFY(std::abs(table->item(1, 7)->text().toDouble()) < 2.0);  // depth - known distance

  // The chart: one line a frame, from f at step 1 to the estimate, each step closer to it.
  const QList<QAbstractSeries*> series = dialog->chart()->series();
  QCOMPARE(series.size(), 2);
  for (int i = 0; i < 2; ++i) {
    const QList<QPointF> points = static_cast<QLineSeries*>(series[i])->points();
    QCOMPARE(points.size(), dialog->entries()[static_cast<size_t>(i)].estimate.estimate.iterations + 1);
    QCOMPARE(points.front().x(), 1.0);
    QVERIFY(std::abs(points.front().y() - f) < 1e-6);  // f as the box shows it, to 6 decimals
    QVERIFY(std::abs(points.back().y() - kTrueD0) < 2e-3);
    const double last = points.back().y();  // converging: each step closer to where it ends
    for (int k = 1; k < points.size(); ++k) QVERIFY(std::abs(points[k].y() - last) <= std::abs(points[k - 1].y() - last));
  }
  QVERIFY(dialog->summaryText().contains(QStringLiteral("mean of 2 of 2 frames")));
  // For the documentation: IMAGEPRO_D0_SCREENSHOT names a PNG of the dialog.
  if (const QString shot = qEnvironmentVariable("IMAGEPRO_D0_SCREENSHOT"); !shot.isEmpty()) {
    dialog->resize(900, 760);
    QTest::qWait(300);
    QVERIFY(dialog->grab().save(shot, "PNG", 0));
  }

  dialog->setKnownDistance(0.0);
  QVERIFY(!dialog->openImage(path + QStringLiteral(".missing")));  // named, not added
  QVERIFY(dialog->findChild<QLabel*>(QStringLiteral("d0Summary"))->text().contains(QStringLiteral("target.png.missing")));
  QCOMPARE(dialog->entries().size(), size_t(2));

  // A wrong focal length moves every estimate; the frames are estimated again.
  dialog->setFocalLength(focalLength(kTrueD0, 2.0 * kDistance));
  QVERIFY(std::abs(dialog->entries()[0].estimate.estimate.d0_mm - kTrueD0) > 0.05);
  dialog->setFocalLength(f);

  // Set d0: the settings' camera takes the mean.
  dialog->findChild<QPushButton*>(QStringLiteral("d0Set"))->click();
  QVERIFY(std::abs(w.settings().camera().image_plane_distance_mm - kTrueD0) < 2e-3);
  QVERIFY(waitForApplied(w, [](const Settings& s) { return std::abs(s.camera().image_plane_distance_mm - kTrueD0) < 2e-3; }));
  dialog->clearFrames();
  QVERIFY(dialog->entries().empty());
  QVERIFY(!dialog->findChild<QPushButton*>(QStringLiteral("d0Set"))->isEnabled());
}

void D0DialogTest::captureTakesTheRunningSourcesFrame() {
  MainWindow& w = *window_;
  D0Dialog& dialog = showD0Dialog(w);
  dialog.setFocalLength(focalLength(kTrueD0, 800.0));  // the virtual target's default distance
  // Nothing running, nothing open: nothing to capture, said in words.
  auto* summary = dialog.findChild<QLabel*>(QStringLiteral("d0Summary"));
  dialog.captureFrame();
  QTRY_VERIFY_WITH_TIMEOUT(summary->text().contains(QStringLiteral("Nothing to capture")), 5000);
  QVERIFY(dialog.entries().empty());
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.index >= 2; }));
  dialog.captureFrame();
  QTRY_COMPARE_WITH_TIMEOUT(dialog.entries().size(), size_t(1), 5000);
  const D0Dialog::Entry& e = dialog.entries().front();
  QVERIFY(e.origin.startsWith(QStringLiteral("Captured from")));
  QCOMPARE(e.estimate.status, Status::Ok);
  QVERIFY(std::abs(e.estimate.estimate.d0_mm - kTrueD0) < 5e-3);
  w.stopSource();
  QTRY_VERIFY(!w.worker()->isRunning());
}

}  // namespace imagepro::app::test
