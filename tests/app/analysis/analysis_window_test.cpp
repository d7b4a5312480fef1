// The Analysis window runs both case studies of thesis 5.3: the virtual pendulum gives
// g within the pendulum chain's goal of the scene's own g; a data-out file gives the
// very numbers `imagepro-cli pendulum` prints for it; broken input gives the named
// error in words; the virtual two-target object gives small errors; live frames are
// collected from the main window's worker; and the GUI thread is never the one that
// computes.
#include <QAction>
#include <QChart>
#include <QComboBox>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLineSeries>
#include <QLabel>
#include <QMenuBar>
#include <QProcess>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalSpy>
#include <QTest>

#include <opencv2/imgcodecs.hpp>

#include <cmath>

#include "app/plots/analysis_plots.h"
#include "app/analysis/analysis_window.h"
#include "app/main_window/main_window.h"
#include "app/main_window/responsiveness_probe.h"
#include "app/panels/control_panel.h"
#include "app/panels/source_panel.h"
#include "app/worker/worker.h"
#include "app_test_classes.h"
#include "app_test_support.h"
#include "core/analysis/pendulum_scene.h"
#include "core/analysis/two_targets.h"
#include "core/pipeline/data_out.h"
#include "core/pipeline/engine.h"
#include "core/source/virtual_motion.h"

namespace imagepro::app::test {

namespace {

constexpr int kRunMs = 60000;

bool writeText(const QString& path, const QByteArray& text) {
  QFile f(path);
  return f.open(QIODevice::WriteOnly | QIODevice::Truncate) && f.write(text) == text.size();
}

int pointsIn(QChart* chart) {
  int n = 0;
  for (QAbstractSeries* s : chart->series())
    if (auto* line = qobject_cast<QLineSeries*>(s)) n += static_cast<int>(line->count());
  return n;
}

// For the documentation: IMAGEPRO_ANALYSIS_SCREENSHOT names a PNG to write the window
// to (with `suffix` before ".png"); nothing to do without it.
bool saveScreenshot(AnalysisWindow& w, const QString& suffix) {
  QString path = qEnvironmentVariable("IMAGEPRO_ANALYSIS_SCREENSHOT");
  if (path.isEmpty()) return true;
  if (path.endsWith(QStringLiteral(".png"))) path.chop(4);
  w.resize(1180, 720);
  QTest::qWait(200);
  return w.grab().save(path + suffix + QStringLiteral(".png"), "PNG");
}

// Runs the window's study and waits for its result.
bool runAndWait(AnalysisWindow& w) {
  QSignalSpy finished(&w, &AnalysisWindow::finished);
  w.run();
  return finished.count() > 0 || finished.wait(kRunMs);
}

}  // namespace

void AnalysisWindowTest::init() {
  main_ = std::make_unique<MainWindow>();
  main_->setSettings(Settings{});
  window_ = std::make_unique<AnalysisWindow>(*main_);
  window_->show();
}

void AnalysisWindowTest::cleanup() {
  window_.reset();
  main_.reset();
}

void AnalysisWindowTest::menuOpensTheWindow() {
  AnalysisWindow* before = main_->findChild<AnalysisWindow*>();
  QVERIFY(!before);
  QAction* action = nullptr;
  for (QAction* a : main_->menuBar()->findChildren<QAction*>())
    if (a->text() == QStringLiteral("&Analysis...")) action = a;
  QVERIFY(action);
  action->trigger();
  AnalysisWindow* opened = main_->findChild<AnalysisWindow*>();
  QVERIFY(opened);
  QVERIFY(opened->isVisible());
  action->trigger();  // the same window again, not a second one
  QCOMPARE(main_->findChildren<AnalysisWindow*>().size(), 1);
}

void AnalysisWindowTest::virtualPendulumGivesG() {
  AnalysisWindow& w = *window_;
  w.setStudy(AnalysisStudy::Pendulum);
  w.setInput(AnalysisInput::VirtualScene);
  w.setPendulumParams(VirtualPendulumParams{});  // imagepro-cli pendulum --virtual: 250 frames, noise 3
  QSignalSpy finished(&w, &AnalysisWindow::finished);
  w.run();
  // The work runs elsewhere: the GUI thread goes on handling events meanwhile.
  QVERIFY(w.isBusy());
  QVERIFY(finished.wait(kRunMs));
  QVERIFY(!w.isBusy());
  const PendulumStudyResult& r = w.pendulumResult();
  QCOMPARE(r.status, Status::Ok);
  QVERIFY(r.has_truth);
  const PendulumOptions truth = Settings{}.virtual_scene.pendulum;
  QCOMPARE(r.truth.g_m_s2, truth.gravity_m_s2);
  QCOMPARE(r.truth.length_mm, truth.length_mm);
  // The goals of the pendulum chain test (thesis 5.3.2 on the virtual pendulum).
  QCOMPARE(r.analysis.valid_frames, 250);
  QVERIFY(std::abs(r.analysis.g_m_s2 - truth.gravity_m_s2) < 0.005 * truth.gravity_m_s2);
  QVERIFY(std::abs(r.analysis.length_mm - truth.length_mm) < 0.002 * truth.length_mm);
  QVERIFY(r.analysis.g_sigma_m_s2 > 0.0);
  // Shown: the numbers in the table, the translations and their fit in the chart.
  const QString table = w.summaryText();
  QVERIFY2(table.contains(QString::number(r.analysis.g_m_s2, 'f', 4)), qPrintable(table));
  QVERIFY(table.contains(QString::number(truth.gravity_m_s2, 'f', 5)));
  QVERIFY(table.contains(QString::number(r.analysis.length_mm, 'f', 2)));
  QVERIFY(w.message().contains(QStringLiteral("g = ")));
  QCOMPARE(w.pendulumChart()->chart()->series().size(), 6);  // Tx, Ty, Tz and their fits
  QVERIFY(pointsIn(w.pendulumChart()->chart()) >= 3 * 250);

  QVERIFY(saveScreenshot(w, QString()));
}

void AnalysisWindowTest::harmonicFitFollowsThePendulum() {
  // The chart's fit: two harmonics of the period reproduce the exact swing's
  // translations (the height has twice the swing's frequency).
  Settings s;
  const PendulumOptions& p = s.virtual_scene.pendulum;
  const double period = pendulumPeriodS(p);
  s.virtual_scene.motion.kind = MotionKind::Pendulum;
  std::vector<double> t, x, y;
  for (int i = 0; i < 200; ++i) {
    t.push_back(i * 0.02);
    const Pose pose = virtualPoseAt(s.virtual_scene, t.back());
    x.push_back(pose.tx_mm);
    y.push_back(pose.ty_mm);
  }
  for (const auto* values : {&x, &y}) {
    const Eigen::VectorXd c = fitHarmonics(t, *values, period, 2);
    QCOMPARE(c.size(), 5);
    double worst = 0.0, spread = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      worst = std::max(worst, std::abs(evaluateHarmonics(c, period, t[i]) - (*values)[i]));
      spread = std::max(spread, std::abs((*values)[i] - c(0)));
    }
    QVERIFY2(worst < 0.01 * spread, qPrintable(QStringLiteral("%1 of %2").arg(worst).arg(spread)));
  }
  QCOMPARE(fitHarmonics(t, x, 0.0, 2).size(), 0);
  QCOMPARE(fitHarmonics(std::span<const double>(t).first(4), x, period, 2).size(), 0);
}

void AnalysisWindowTest::dataOutFileGivesTheCliNumbers() {
  // A data-out file of the virtual pendulum, written by the core's DataOut as the
  // window's Data Out and `imagepro-cli pendulum --data-out` write it.
  const QString path = scratchDir(QStringLiteral("analysis-dataout")) + QStringLiteral("/pendulum.csv");
  {
    Settings s;
    s.virtual_scene.noise_sigma = 3.0;
    PendulumSource source(s, MotionBlur{});
    Engine engine(s);
    DataOut out;
    std::string error;
    QCOMPARE(out.open(path.toStdString(), ExistingFile::Fail, error), Status::Ok);
    FrameResult r;
    for (int i = 0; i < 150; ++i) {
      engine.step(source, r);
      QVERIFY(out.write(r, error));
    }
  }
  QProcess cli;
  cli.start(QStringLiteral(IMAGEPRO_CLI),
            {QStringLiteral("pendulum"), QStringLiteral("--format"), QStringLiteral("json"), path});
  QVERIFY(cli.waitForFinished(60000));
  QCOMPARE(cli.exitCode(), 0);
  const QJsonObject expected = QJsonDocument::fromJson(cli.readAllStandardOutput()).object();
  QVERIFY(expected.contains(QStringLiteral("g_m_s2")));

  AnalysisWindow& w = *window_;
  w.setStudy(AnalysisStudy::Pendulum);
  w.setInput(AnalysisInput::DataOutFile);
  w.setFilePath(path);
  QVERIFY(runAndWait(w));
  const PendulumStudyResult& r = w.pendulumResult();
  QCOMPARE(r.status, Status::Ok);
  QVERIFY(!r.has_truth);  // a file carries no truth
  const PendulumAnalysis& a = r.analysis;
  QCOMPARE(a.frames, expected[QStringLiteral("frames")].toInt());
  QCOMPARE(a.valid_frames, expected[QStringLiteral("valid_frames")].toInt());
  QCOMPARE(a.length_mm, expected[QStringLiteral("length_mm")].toDouble());
  QCOMPARE(a.length_sigma_mm, expected[QStringLiteral("length_sigma_mm")].toDouble());
  QCOMPARE(a.period_s, expected[QStringLiteral("period_s")].toDouble());
  QCOMPARE(a.period_sigma_s, expected[QStringLiteral("period_sigma_s")].toDouble());
  QCOMPARE(a.g_m_s2, expected[QStringLiteral("g_m_s2")].toDouble());
  QCOMPARE(a.g_sigma_m_s2, expected[QStringLiteral("g_sigma_m_s2")].toDouble());
  QCOMPARE(a.g_uncorrected_m_s2, expected[QStringLiteral("g_uncorrected_m_s2")].toDouble());
  QVERIFY(w.summaryText().contains(QString::number(a.g_m_s2, 'f', 4)));
}

// As the thesis ran it: the length from a still recording, the period from the swing,
// here by the thesis's first to last maximum; the window gives what the CLI prints.
void AnalysisWindowTest::stillAndSwingFilesGiveTheCliNumbers() {
  const QString dir = scratchDir(QStringLiteral("analysis-still-swing"));
  const QString still = dir + QStringLiteral("/still.csv"), swing = dir + QStringLiteral("/swing.csv");
  auto record = [](FrameSource& source, Settings s, const QString& path, int frames) {
    Engine engine(s);
    DataOut out;
    std::string error;
    if (!ok(out.open(path.toStdString(), ExistingFile::Fail, error))) return false;
    FrameResult r;
    for (int i = 0; i < frames && engine.step(source, r) != Status::EndOfStream; ++i)
      if (!out.write(r, error)) return false;
    return true;
  };
  Settings s;
  s.virtual_scene.noise_sigma = 3.0;
  PendulumSource swinging(s, MotionBlur{});
  QVERIFY(record(swinging, s, swing, 150));
  Settings whole = s;
  whole.pipeline.tracking.mode = TrackingMode::Off;
  PendulumStillSource held(whole, PendulumStillParams{});
  QVERIFY(record(held, whole, still, 1000));

  QProcess cli;
  cli.start(QStringLiteral(IMAGEPRO_CLI), {QStringLiteral("pendulum"), QStringLiteral("--still"), still,
                                           QStringLiteral("--swing"), swing, QStringLiteral("--period-method"),
                                           QStringLiteral("maxima"), QStringLiteral("--format"), QStringLiteral("json")});
  QVERIFY(cli.waitForFinished(60000));
  QCOMPARE(cli.exitCode(), 0);
  const QJsonObject expected = QJsonDocument::fromJson(cli.readAllStandardOutput()).object();
  QVERIFY(expected[QStringLiteral("length_from_still")].toBool());

  AnalysisWindow& w = *window_;
  w.setStudy(AnalysisStudy::Pendulum);
  w.setInput(AnalysisInput::DataOutFile);
  w.setFilePath(swing);
  w.setStillPath(still);
  auto* method = w.findChild<QComboBox*>(QStringLiteral("analysisPeriodMethod"));
  QVERIFY(method);
  method->setCurrentIndex(method->findData(static_cast<int>(PeriodMethod::Maxima)));
  QVERIFY(runAndWait(w));
  const PendulumStudyResult& r = w.pendulumResult();
  QCOMPARE(r.status, Status::Ok);
  const PendulumAnalysis& a = r.analysis;
  QVERIFY(a.length_from_still);
  QCOMPARE(a.still_frames, expected[QStringLiteral("still_frames")].toInt());
  QCOMPARE(a.length_mm, expected[QStringLiteral("length_mm")].toDouble());
  QCOMPARE(a.period_s, a.maxima.period_s);
  QCOMPARE(a.period_s, expected[QStringLiteral("maxima_period_s")].toDouble());
  QCOMPARE(a.g_m_s2, expected[QStringLiteral("g_m_s2")].toDouble());
  QVERIFY(std::abs(a.length_mm - 444.0) < 0.005 * 444.0);
  QVERIFY(w.summaryText().contains(QStringLiteral("first to last maximum [s] (g's)")));
  QVERIFY(w.summaryText().contains(QStringLiteral("Still frames")));
  w.setStillPath(QString());
}

void AnalysisWindowTest::brokenFilesGiveNamedErrors() {
  AnalysisWindow& w = *window_;
  w.setStudy(AnalysisStudy::Pendulum);
  w.setInput(AnalysisInput::DataOutFile);
  const QString dir = scratchDir(QStringLiteral("analysis-broken"));
  const QByteArray header = "frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm,timestamp_s\n";

  struct Case {
    QString name;
    QByteArray text;
    Status status;
    QString words;  // what the message must say
  };
  QByteArray still = header;
  for (int i = 0; i < 40; ++i) still += QByteArray::number(i) + ",ok,0,0,0,0,0,1000," + QByteArray::number(i * 0.04) + "\n";
  QByteArray few = header;
  for (int i = 0; i < 5; ++i) few += QByteArray::number(i) + ",ok,0,0,0," + QByteArray::number(i) + ",0,1000," + QByteArray::number(i * 0.04) + "\n";
  QByteArray lost = header;
  for (int i = 0; i < 40; ++i)
    lost += i % 3 == 0 ? QByteArray::number(i) + ",ok,0,0,0,1,0,1000," + QByteArray::number(i * 0.04) + "\n"
                       : QByteArray::number(i) + ",NoTarget,,,,,,," + QByteArray::number(i * 0.04) + "\n";
  const Case cases[] = {
      {QStringLiteral("not-a-pose-csv.csv"), "name,value\nx,1\n", Status::FileUnreadable, QStringLiteral("Rx_deg")},
      {QStringLiteral("bad-number.csv"), header + "0,ok,1,2,3,abc,5,6,0.0\n", Status::FileUnreadable,
       QStringLiteral("line 2")},
      {QStringLiteral("empty.csv"), QByteArray(), Status::FileUnreadable, QStringLiteral("empty")},
      {QStringLiteral("still.csv"), still, Status::NoSwing, QString::fromUtf8(statusMessage(Status::NoSwing).data())},
      {QStringLiteral("few.csv"), few, Status::TooFewFrames, QString::fromUtf8(statusMessage(Status::TooFewFrames).data())},
      {QStringLiteral("lost.csv"), lost, Status::TargetLost, QString::fromUtf8(statusMessage(Status::TargetLost).data())},
  };
  for (const Case& c : cases) {
    const QString path = dir + QLatin1Char('/') + c.name;
    QVERIFY(writeText(path, c.text));
    w.setFilePath(path);
    QVERIFY(runAndWait(w));
    QCOMPARE(w.pendulumResult().status, c.status);
    const QString name = QString::fromUtf8(statusName(c.status).data());
    QVERIFY2(w.message().contains(name), qPrintable(c.name + QStringLiteral(": ") + w.message()));
    QVERIFY2(w.message().contains(c.words), qPrintable(c.name + QStringLiteral(": ") + w.message()));
    QCOMPARE(w.summaryText(), QString());  // no numbers from a failed analysis
  }
  w.setFilePath(dir + QStringLiteral("/missing.csv"));
  QVERIFY(runAndWait(w));
  QCOMPARE(w.pendulumResult().status, Status::FileNotFound);
  QVERIFY(w.message().contains(QStringLiteral("FileNotFound")));
  QVERIFY(w.message().contains(QStringLiteral("missing.csv")));
  w.setFilePath(QString());
  QVERIFY(runAndWait(w));
  QCOMPARE(w.pendulumResult().status, Status::FileNotFound);
}

void AnalysisWindowTest::virtualTwoTargetsHaveSmallErrors() {
  AnalysisWindow& w = *window_;
  w.setStudy(AnalysisStudy::TwoTargets);
  w.setInput(AnalysisInput::VirtualScene);
  VirtualTwoTargetParams params;
  params.frames_per_position = 6;
  w.setTwoTargetParams(params);
  QVERIFY(runAndWait(w));
  const TwoTargetStudyResult& r = w.twoTargetResult();
  QCOMPARE(r.status, Status::Ok);
  QCOMPARE(r.frames.size(), std::size_t{18});
  QCOMPARE(r.summaries.size(), std::size_t{6});  // three positions, with and without correction
  for (const TwoTargetSummary& s : r.summaries) {
    QCOMPARE(s.frames, 6);
    QCOMPARE(s.distance_mm.samples, 6);
    if (!s.correction) continue;
    // The thesis's figures stay within about 0.5 mm and 0.5 degrees (the core test's bounds).
    QVERIFY2(s.distance_mm.max_abs < 0.5, qPrintable(QString::number(s.distance_mm.max_abs)));
    QVERIFY2(s.angle_deg.max_abs < 0.5, qPrintable(QString::number(s.angle_deg.max_abs)));
  }
  // Without correction the thesis lens shows in the angle (position 1: rows 0 and 1).
  QVERIFY(r.summaries[1].angle_deg.mean > std::abs(r.summaries[0].angle_deg.mean) + 0.2);
  QVERIFY(r.failures.empty());
  QCOMPARE(w.summaryText().count(QLatin1Char('\n')), 6);  // header and six rows
  QVERIFY(w.message().contains(QStringLiteral("200.00 mm")));
  QCOMPARE(pointsIn(w.twoTargetCharts()->distanceChart()), 2 * 18 + 2);  // both runs and the known line
  QCOMPARE(pointsIn(w.twoTargetCharts()->angleChart()), 2 * 18 + 2);
  QVERIFY(saveScreenshot(w, QStringLiteral("-two-targets")));
  // The very summaries of `imagepro-cli two-targets --virtual` with the same frames.
  QProcess cli;
  cli.start(QStringLiteral(IMAGEPRO_CLI), {QStringLiteral("two-targets"), QStringLiteral("--virtual"),
                                          QStringLiteral("--frames"), QStringLiteral("6"), QStringLiteral("--format"),
                                          QStringLiteral("json")});
  QVERIFY(cli.waitForFinished(60000));
  QCOMPARE(cli.exitCode(), 0);
  const QJsonArray expected =
      QJsonDocument::fromJson(cli.readAllStandardOutput()).object()[QStringLiteral("summaries")].toArray();
  QCOMPARE(expected.size(), 6);
  for (int i = 0; i < 6; ++i) {
    const QJsonObject e = expected[i].toObject();
    const TwoTargetSummary& s = r.summaries[static_cast<std::size_t>(i)];
    QCOMPARE(s.position, e[QStringLiteral("position")].toInt());
    QCOMPARE(s.correction, e[QStringLiteral("distortion_correction")].toBool());
    QCOMPARE(s.distance_mm.mean, e[QStringLiteral("distance_error_mm")].toObject()[QStringLiteral("mean")].toDouble());
    QCOMPARE(s.distance_mm.max_abs, e[QStringLiteral("distance_error_mm")].toObject()[QStringLiteral("max_abs")].toDouble());
    QCOMPARE(s.angle_deg.std, e[QStringLiteral("angle_error_deg")].toObject()[QStringLiteral("std")].toDouble());
  }

  // An object whose cards cannot fit is refused in words.
  params.object.spacing_mm = 50.0;
  w.setTwoTargetParams(params);
  QVERIFY(runAndWait(w));
  QCOMPARE(w.twoTargetResult().status, Status::InvalidSettings);
  QVERIFY(w.message().contains(QStringLiteral("do not fit")));

  // A data-out file cannot hold both targets of a frame: the window says so and does not run.
  w.setInput(AnalysisInput::DataOutFile);
  QVERIFY(!w.findChild<QPushButton*>(QStringLiteral("analysisRun"))->isEnabled());
  QVERIFY(w.findChild<QLabel*>(QStringLiteral("analysisNote"))->text().contains(QStringLiteral("one pose per frame")));
}

void AnalysisWindowTest::cancelStopsTheRun() {
  AnalysisWindow& w = *window_;
  w.setStudy(AnalysisStudy::Pendulum);
  w.setInput(AnalysisInput::VirtualScene);
  VirtualPendulumParams params;
  params.frames = 100000;
  w.setPendulumParams(params);
  QSignalSpy finished(&w, &AnalysisWindow::finished);
  w.run();
  QVERIFY(w.isBusy());
  auto* bar = w.findChild<QProgressBar*>(QStringLiteral("analysisProgress"));
  QTRY_VERIFY_WITH_TIMEOUT(bar->maximum() == 100000 && bar->value() > 0, 20000);
  w.cancel();
  QVERIFY(finished.wait(kRunMs));
  QCOMPARE(w.pendulumResult().status, Status::Stopped);
  QVERIFY(w.message().contains(QStringLiteral("cancelled")));
  // Closing the window while a run is under way stops it too.
  w.run();
  QVERIFY(w.isBusy());
  window_.reset();
}

void AnalysisWindowTest::livePendulumIsCollected() {
  // The main window's Virtual source swinging the pendulum at 100 frames/s: its
  // frames' poses are collected from the worker's packets, every frame, shown or not.
  Settings s;
  s.virtual_scene.motion.kind = MotionKind::Pendulum;
  s.virtual_scene.frame_rate_hz = 100.0;
  main_->setSettings(s);
  main_->show();
  AnalysisWindow& w = *window_;
  w.setStudy(AnalysisStudy::Pendulum);
  w.setInput(AnalysisInput::LiveStream);
  w.run();
  QVERIFY(w.isCollecting());
  main_->selectSource(SourceKind::Virtual);
  main_->startSource();
  // Two swings and a bit (1.34 s each).
  QTRY_VERIFY_WITH_TIMEOUT(w.collectedFrames() >= 300, 60000);
  main_->stopSource();
  QTRY_VERIFY_WITH_TIMEOUT(!main_->worker()->isRunning(), 5000);
  // The last poses are still queued to the GUI thread when the worker stops: wait for them.
  QTRY_COMPARE_WITH_TIMEOUT(w.collectedFrames(), main_->worker()->framesProcessed(), 5000);
  QVERIFY(runAndWait(w));  // stop collecting: analysed on the background thread
  QVERIFY(!w.isCollecting());
  const PendulumStudyResult& r = w.pendulumResult();
  QCOMPARE(r.status, Status::Ok);
  QCOMPARE(static_cast<std::int64_t>(r.samples.size()), main_->worker()->framesProcessed());
  // Consecutive frames, 10 ms apart: none was lost between the worker and the window.
  for (std::size_t i = 1; i < r.samples.size(); ++i) QVERIFY(std::abs(r.samples[i].t_s - r.samples[i - 1].t_s - 0.01) < 1e-9);
  const PendulumOptions& truth = s.virtual_scene.pendulum;
  QVERIFY(std::abs(r.analysis.g_m_s2 - truth.gravity_m_s2) < 0.005 * truth.gravity_m_s2);
}

void AnalysisWindowTest::liveTwoTargetsNeedTwoTargets() {
  // The Virtual source shows one target: every live frame is measured on the analysis
  // thread and gives TooFewTargets, said in words.
  main_->show();
  AnalysisWindow& w = *window_;
  w.setStudy(AnalysisStudy::TwoTargets);
  w.setInput(AnalysisInput::LiveStream);
  w.run();
  QVERIFY(w.isCollecting());
  main_->selectSource(SourceKind::Virtual);
  main_->startSource();
  QTRY_VERIFY_WITH_TIMEOUT(w.collectedFrames() >= 5, 30000);
  QVERIFY(runAndWait(w));
  main_->stopSource();
  const TwoTargetStudyResult& r = w.twoTargetResult();
  QCOMPARE(r.status, Status::TooFewTargets);
  QVERIFY(w.message().contains(QString::fromUtf8(statusMessage(Status::TooFewTargets).data())));
  QVERIFY(r.frames.size() >= 5);
  for (const TwoTargetFrame& f : r.frames) QCOMPARE(f.status[0], Status::TooFewTargets);
}

void AnalysisWindowTest::liveTwoTargetsFromImageFiles() {
  // Pictures of the two-target object played as the main window's File input: the
  // frames it shows are measured on the analysis thread, both targets of each.
  Settings s;
  s.camera().distortion = kThesisCameraDistortion;
  s.virtual_scene.noise_sigma = 2.0;
  const QString dir = scratchDir(QStringLiteral("analysis-two-target-images"));
  TwoTargetRenderWorkspace ws;
  cv::Mat image;
  for (int i = 0; i < 3; ++i) {
    renderTwoTargets(s.camera(), s.target, s.virtual_scene, TwoTargetObject{}, twoTargetStudyPosition(1), image,
                     static_cast<std::uint64_t>(i), ws);
    QVERIFY(cv::imwrite(QStringLiteral("%1/object%2.png").arg(dir).arg(i).toStdString(), image));
  }
  main_->setSettings(s);
  main_->show();
  AnalysisWindow& w = *window_;
  w.setStudy(AnalysisStudy::TwoTargets);
  w.setInput(AnalysisInput::LiveStream);
  w.run();
  main_->openPaths({dir});
  QTRY_VERIFY_WITH_TIMEOUT(main_->controlPanel()->sourcePanel()->canStart(), 30000);  // the list is open
  main_->startSource();  // plays it on from its first image
  QTRY_VERIFY_WITH_TIMEOUT(!main_->worker()->isRunning() && main_->worker()->framesProcessed() == 3, 30000);
  QTRY_VERIFY_WITH_TIMEOUT(w.collectedFrames() >= 1, 30000);
  QTest::qWait(200);  // the last file's packet
  QVERIFY(runAndWait(w));
  const TwoTargetStudyResult& r = w.twoTargetResult();
  QCOMPARE(r.status, Status::Ok);
  QVERIFY(!r.frames.empty() && r.frames.size() <= 3);  // the frames shown, each once
  for (const TwoTargetFrame& f : r.frames) {
    QCOMPARE(f.status[0], Status::Ok);
    QVERIFY(std::abs(f.measurement[0].distance_mm - r.object.spacing_mm) < 0.5);
    QVERIFY(std::abs(f.measurement[0].angle_deg - r.object.angle_deg) < 0.5);
  }
  QCOMPARE(r.summaries.size(), std::size_t{2});  // one group: with and without correction
  QCOMPARE(r.summaries[0].position, 0);
  QVERIFY(w.summaryText().contains(QStringLiteral("live")));
}

void AnalysisWindowTest::closingTheMainWindowWhileBusyIsSafe() {
  // The window from the menu is the main window's child: it goes with it, collecting
  // or analysing in the background.
  main_->show();
  for (AnalysisStudy study : {AnalysisStudy::Pendulum, AnalysisStudy::TwoTargets}) {
    QAction* action = nullptr;
    for (QAction* a : main_->menuBar()->findChildren<QAction*>())
      if (a->text() == QStringLiteral("&Analysis...")) action = a;
    QVERIFY(action);
    action->trigger();
    AnalysisWindow* child = main_->findChild<AnalysisWindow*>();
    QVERIFY(child);
    child->setStudy(study);
    child->setInput(AnalysisInput::LiveStream);
    child->run();
    QVERIFY(child->isCollecting());
    main_->selectSource(SourceKind::Virtual);
    main_->startSource();
    QTRY_VERIFY_WITH_TIMEOUT(child->collectedFrames() >= 3, 30000);
    window_.reset();
    main_.reset();
    main_ = std::make_unique<MainWindow>();
    main_->show();
  }
  // And with a virtual scene being rendered.
  QAction* action = nullptr;
  for (QAction* a : main_->menuBar()->findChildren<QAction*>())
    if (a->text() == QStringLiteral("&Analysis...")) action = a;
  action->trigger();
  AnalysisWindow* child = main_->findChild<AnalysisWindow*>();
  child->setInput(AnalysisInput::VirtualScene);
  child->run();
  QVERIFY(child->isBusy());
  main_.reset();
}

void AnalysisWindowTest::responsivenessProbeReports() {
  // The measurement behind `imagepro --measure-responsiveness`, briefly: sane counts,
  // never a timing threshold (timing depends on the machine).
  main_->show();
  ResponsivenessMeasurement m(*main_, 1.0, 2);
  QSignalSpy finished(&m, &ResponsivenessMeasurement::finished);
  m.start();
  QVERIFY(finished.wait(30000));
  const ResponsivenessReport& r = m.report();
  QVERIFY(r.seconds >= 1.0);
  QVERIFY(r.ticks > 10);
  QCOMPARE(r.interval_ms, 2);
  QVERIFY(r.frames_shown > 0);
  QVERIFY(r.frames_processed >= r.frames_shown);
  QVERIFY(r.max_stall_ms >= r.p99_stall_ms);
  QVERIFY(r.p99_stall_ms >= 0.0);
  QVERIFY(r.median_gap_ms > 0.0);
  QVERIFY(r.max_stall_cpu_ms >= 0.0);
  QVERIFY(r.max_gap_cpu_ms >= r.max_stall_cpu_ms);
  QVERIFY(r.backlog_max >= 0);
  QVERIFY(main_->settings().virtual_scene.frame_rate_hz >= 1e5);  // it ran unpaced
  QTRY_VERIFY_WITH_TIMEOUT(!main_->worker()->isRunning(), 5000);
  const QString text = formatReport(r);
  QVERIFY(text.contains(QStringLiteral("99th percentile")));
  QVERIFY(text.contains(QStringLiteral("frames processed %1").arg(r.frames_processed)));
  qInfo("%s", qPrintable(text));
}

}  // namespace imagepro::app::test
