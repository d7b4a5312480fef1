// Virtual input in the window: Start / Stop, and the appendix A keys moving the target.
#include <QCoreApplication>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QPushButton>
#include <QSpinBox>
#include <QTest>
#include <QTimer>

#include <cmath>

#include "app/panels/control_panel.h"
#include "app/main_window/frame_view.h"
#include "app/main_window/main_window.h"
#include "app/panels/source_panel.h"
#include "app/settings/settings_dialog.h"
#include "app/worker/worker.h"
#include "app_test_classes.h"
#include "app_test_support.h"

namespace imagepro::app::test {

namespace {

bool near(double a, double b) { return std::abs(a - b) < 1e-9; }

}  // namespace

void VirtualTest::init() {
  window_ = std::make_unique<MainWindow>();
  Settings s;
  s.virtual_scene.frame_rate_hz = 100.0;
  window_->setSettings(s);
  window_->show();
}

void VirtualTest::cleanup() { window_.reset(); }

void VirtualTest::startStopProducesFrames() {
  MainWindow& w = *window_;
  SourcePanel* source = w.controlPanel()->sourcePanel();
  source->setKind(SourceKind::Virtual);
  QCOMPARE(source->button()->text(), QStringLiteral("Start"));
  source->button()->click();
  QTRY_VERIFY_WITH_TIMEOUT(w.worker()->isRunning(), 5000);
  QTRY_COMPARE_WITH_TIMEOUT(source->button()->text(), QStringLiteral("Stop"), 5000);
  // Frames arrive, carry their ground truth, and the results text shows them.
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.index >= 5 && r.truth.has_value(); }));
  QVERIFY(w.packetsShown() >= 2);
  QTRY_VERIFY(w.resultsText().contains(QStringLiteral("Status")));
  QTRY_VERIFY(w.resultsText().contains(QStringLiteral("Tz")));
  source->button()->click();
  QTRY_VERIFY_WITH_TIMEOUT(!w.worker()->isRunning(), 5000);
  QTRY_COMPARE(source->button()->text(), QStringLiteral("Start"));
  const std::int64_t frames = w.worker()->framesProcessed();
  QTest::qWait(150);
  QCOMPARE(w.worker()->framesProcessed(), frames);
  // Start again: it goes on.
  source->button()->click();
  QTRY_VERIFY_WITH_TIMEOUT(w.worker()->framesProcessed() > frames + 3, 5000);
  w.stopSource();
  QTRY_VERIFY(!w.worker()->isRunning());
}

void VirtualTest::keysMoveTheTarget() {
  MainWindow& w = *window_;
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.truth.has_value(); }));
  const Pose start = *w.frameView()->packet()->result.truth;
  const VirtualSceneOptions scene = w.settings().virtual_scene;
  w.frameView()->setFocus();

  struct Press {
    Qt::Key key;
    double Pose::*field;
    double change;
  };
  const Press presses[] = {
      {Qt::Key_6, &Pose::tx_mm, scene.key_step_mm},      {Qt::Key_4, &Pose::tx_mm, -scene.key_step_mm},
      {Qt::Key_8, &Pose::ty_mm, scene.key_step_mm},      {Qt::Key_2, &Pose::ty_mm, -scene.key_step_mm},
      {Qt::Key_Delete, &Pose::tz_mm, scene.key_step_mm}, {Qt::Key_Insert, &Pose::tz_mm, -scene.key_step_mm},
      {Qt::Key_Down, &Pose::rx_deg, scene.key_step_deg}, {Qt::Key_Up, &Pose::rx_deg, -scene.key_step_deg},
      {Qt::Key_Right, &Pose::ry_deg, scene.key_step_deg}, {Qt::Key_Left, &Pose::ry_deg, -scene.key_step_deg},
      {Qt::Key_End, &Pose::rz_deg, scene.key_step_deg},  {Qt::Key_Home, &Pose::rz_deg, -scene.key_step_deg},
  };
  for (const Press& p : presses) {
    const Pose before = *w.frameView()->packet()->result.truth;
    QTest::keyClick(w.frameView(), p.key);
    QVERIFY2(waitForFrame(w, [&](const FrameResult& r) { return r.truth && near((*r.truth).*p.field, before.*p.field + p.change); }),
             qPrintable(QStringLiteral("key %1").arg(QKeySequence(p.key).toString())));
    // Only that parameter moved.
    const Pose now = *w.frameView()->packet()->result.truth;
    for (double Pose::*other : {&Pose::rx_deg, &Pose::ry_deg, &Pose::rz_deg, &Pose::tx_mm, &Pose::ty_mm, &Pose::tz_mm})
      if (other != p.field) QVERIFY(near(now.*other, before.*other));
  }
  // Every pair cancelled out.
  const Pose end = *w.frameView()->packet()->result.truth;
  QVERIFY(near(end.tx_mm, start.tx_mm) && near(end.tz_mm, start.tz_mm) && near(end.rz_deg, start.rz_deg));
  w.stopSource();
}

void VirtualTest::keysInFieldsDoNotMoveTheTarget() {
  MainWindow& w = *window_;
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.truth.has_value(); }));
  auto* value = w.findChild<QSpinBox*>(QStringLiteral("cropMargin"));
  value->setFocus();
  const Pose before = *w.frameView()->packet()->result.truth;
  QTest::keyClick(value, Qt::Key_6);
  QTest::keyClick(value, Qt::Key_Up);
  const std::int64_t frames = w.worker()->framesProcessed();
  QTRY_VERIFY_WITH_TIMEOUT(w.worker()->framesProcessed() > frames + 5, 5000);
  QVERIFY(waitForFrame(w, [&](const FrameResult& r) { return r.index > frames + 3; }));
  const Pose after = *w.frameView()->packet()->result.truth;
  QVERIFY(near(after.tx_mm, before.tx_mm));
  QVERIFY(near(after.rx_deg, before.rx_deg));
  w.stopSource();
}

void VirtualTest::guiStaysResponsiveAtFullSpeed() {
  // Measured, not asserted (timing depends on the machine): the longest gap between
  // two ticks of a 5 ms GUI timer while the worker renders and processes as fast as
  // it can and the window shows every frame it gets.
  MainWindow& w = *window_;
  Settings s = w.settings();
  s.virtual_scene.frame_rate_hz = 10000.0;
  s.virtual_scene.motion.kind = MotionKind::Sinusoid;
  w.setSettings(s);
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.index > 2; }));
  QElapsedTimer clock;
  clock.start();
  qint64 last = 0, worst = 0;
  QTimer tick;
  QObject::connect(&tick, &QTimer::timeout, [&] {
    const qint64 now = clock.elapsed();
    worst = std::max(worst, now - last);
    last = now;
  });
  const std::int64_t frames0 = w.worker()->framesProcessed();
  const std::int64_t shown0 = w.packetsShown();
  auto* probe = static_cast<ProbeApplication*>(QCoreApplication::instance());
  probe->worst_cpu_ms = probe->worst_wall_ms = 0.0;
  probe->probing = true;
  tick.start(5);
  QTest::qWait(3000);
  tick.stop();
  probe->probing = false;
  const double seconds = clock.elapsed() / 1000.0;
  const double processed_hz = (w.worker()->framesProcessed() - frames0) / seconds;
  const double shown_hz = (w.packetsShown() - shown0) / seconds;
  qInfo("GUI responsiveness at full speed: longest GUI event-loop gap %lld ms; longest single GUI event %.1f ms "
        "wall, %.1f ms GUI-thread CPU (%s); %.0f frames/s processed, %.0f shown",
        static_cast<long long>(worst), probe->worst_wall_ms, probe->worst_cpu_ms, qPrintable(probe->worst_what),
        processed_hz, shown_hz);
  QVERIFY(processed_hz > 0.0);
  QVERIFY(shown_hz > 0.0);
  w.stopSource();
}

// Below the ellipse stage nothing finds the target: the whole frame is searched, not the
// region where it was last tracked, so a target that moved meanwhile is found again as
// soon as the level is raised.
void VirtualTest::searchedRegionIsWholeBelowTheEllipseStage() {
  MainWindow& w = *window_;
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  const auto whole = [](const FrameResult& r) { return r.search_region == cv::Rect(cv::Point(), r.image_size); };
  // Tracked: a region about the target, much smaller than the frame.
  QVERIFY(waitForFrame(w, [](const FrameResult& r) {
    return r.pose && !r.search_region.empty() && r.search_region.area() < r.image_size.area() / 4;
  }));
  const double start_tx = w.frameView()->packet()->result.truth->tx_mm;
  QVERIFY(chooseRadio(w.findChild<QWidget*>(QStringLiteral("applicationLevel")), ApplicationLevel::Connectivity));
  QVERIFY(waitForFrame(w, [&](const FrameResult& r) { return r.reached == ApplicationLevel::Connectivity && whole(r); }));
  // The target moves far from where it was tracked; every frame still searches it all.
  w.frameView()->setFocus();
  for (int i = 0; i < 30; ++i) QTest::keyClick(w.frameView(), Qt::Key_6);
  const double moved = start_tx + 30 * w.settings().virtual_scene.key_step_mm;
  QVERIFY(waitForFrame(w, [&](const FrameResult& r) { return r.truth && near(r.truth->tx_mm, moved); }));
  const std::int64_t frames = w.worker()->framesProcessed();
  QVERIFY(waitForFrame(w, [&](const FrameResult& r) { return r.index > frames + 2; }));
  QVERIFY(whole(w.frameView()->packet()->result));
  // Back to Reconstruction: found where it now is.
  QVERIFY(chooseRadio(w.findChild<QWidget*>(QStringLiteral("applicationLevel")), ApplicationLevel::Reconstruction));
  QVERIFY(waitForFrame(w, [&](const FrameResult& r) {
    return r.reached == ApplicationLevel::Reconstruction && r.pose && std::abs(r.pose->tx_mm - moved) < 5.0;
  }));
  w.stopSource();
}

void VirtualTest::missingCameraShowsAnError() {
  if (QFileInfo::exists(QStringLiteral("/dev/video0"))) QSKIP("a camera is attached: nothing to report");
  MainWindow& w = *window_;
  w.selectSource(SourceKind::Camera);
  w.startSource();
  QTRY_VERIFY_WITH_TIMEOUT(w.lastError().contains(QStringLiteral("/dev/video0")), 5000);
  QVERIFY(!w.worker()->isRunning());
  QCOMPARE(w.controlPanel()->sourcePanel()->button()->text(), QStringLiteral("Start"));
  // The window goes on: the virtual source still runs.
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.truth.has_value(); }));
  w.stopSource();
}

// The constant-velocity motion from the Settings dialog's Virtual page (thesis A.2): the
// frames' true Tx advances at the velocity and wraps inside the box.
void VirtualTest::constantVelocityFromTheSettingsDialog() {
  MainWindow& w = *window_;
  w.findChild<QPushButton*>(QStringLiteral("settingsDialog"))->click();
  auto* dialog = w.findChild<SettingsDialog*>();
  QVERIFY(dialog);
  QVERIFY(choose(dialog->findChild<QComboBox*>(QStringLiteral("virtualMotion")), MotionKind::ConstantVelocity));
  const char* zero[] = {"virtualVelocityRx", "virtualVelocityRy", "virtualVelocityRz", "virtualVelocityTy",
                        "virtualVelocityTz"};
  for (const char* name : zero) dialog->findChild<QDoubleSpinBox*>(QLatin1String(name))->setValue(0.0);
  dialog->findChild<QDoubleSpinBox*>(QStringLiteral("virtualVelocityTx"))->setValue(250.0);
  dialog->findChild<QDoubleSpinBox*>(QStringLiteral("virtualWrapBoxTx"))->setValue(300.0);
  dialog->findChild<QDialogButtonBox*>()->button(QDialogButtonBox::Ok)->click();
  QVERIFY(waitForApplied(w, [](const Settings& s) {
    const MotionOptions& m = s.virtual_scene.motion;
    return m.kind == MotionKind::ConstantVelocity && m.velocity.tx_mm == 250.0 && m.wrap_box.tx_mm == 300.0 &&
           m.velocity.ry_deg == 0.0;
  }));
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  // Past the first wrap (150 mm at 250 mm/s: 0.6 s).
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.truth && r.timestamp_s > 0.8; }, 20000));
  w.stopSource();
  QTRY_VERIFY(!w.worker()->isRunning());
  const FrameResult& r = w.frameView()->packet()->result;
  const double advanced = 250.0 * r.timestamp_s;
  const double wrapped = advanced - 300.0 * std::floor(advanced / 300.0 + 0.5);
  QVERIFY2(std::abs(r.truth->tx_mm - wrapped) < 1e-6, qPrintable(QString::number(r.truth->tx_mm)));
  QVERIFY(r.truth->tx_mm >= -150.0 && r.truth->tx_mm < 150.0);
  QCOMPARE(r.truth->ry_deg, 0.0);
}

}  // namespace imagepro::app::test
