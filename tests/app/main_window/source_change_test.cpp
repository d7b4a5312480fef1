// A change of source leaves nothing of the one before on screen: File -> Virtual ->
// Camera (failing) -> Virtual, and at each step the frame view, the results text, the
// status bar, the Input Source panel, the banner, the plots and the window title say
// what the selected source has. The title and the status bar name the source and say
// when Data Out or the stream is on.
#include <QComboBox>
#include <QFile>
#include <QLabel>
#include <QPushButton>
#include <QStatusBar>
#include <QTest>

#include "app/main_window/frame_view.h"
#include "app/main_window/main_window.h"
#include "app/panels/control_panel.h"
#include "app/panels/source_panel.h"
#include "app/plots/pose_plots.h"
#include "app/worker/worker.h"
#include "app_test_classes.h"
#include "app_test_support.h"

namespace imagepro::app::test {

namespace {

const QString kSamples = QStringLiteral(IMAGEPRO_DATA_DIR "/samples/");
// A device no machine has, so the camera fails to start whatever is attached.
const QString kNoCamera = QStringLiteral("/dev/imagepro-test-no-camera");

// As the user does it: the Input Source list.
void choosePanelSource(MainWindow& w, SourceKind kind) {
  QComboBox* combo = w.controlPanel()->sourcePanel()->combo();
  combo->setCurrentIndex(combo->findData(static_cast<int>(kind)));
}

QLabel* statusLabel(MainWindow& w, const char* name) { return w.statusBar()->findChild<QLabel*>(QLatin1String(name)); }

// The source's name is the same in the status bar, the panel and the title.
bool namedEverywhere(MainWindow& w, const QString& description) {
  return statusLabel(w, "statusSource")->text() == description &&
         w.controlPanel()->sourcePanel()->description() == description && w.windowTitle().contains(description);
}

// No frame shown, nor the numbers, status or plots of one.
bool nothingShown(MainWindow& w) {
  return w.frameView()->packet() == nullptr && w.resultsText() == QStringLiteral("No results yet.") &&
         w.posePlots()->recorded().empty() && !statusLabel(w, "statusState")->text().startsWith(QStringLiteral("ok"));
}

}  // namespace

void SourceChangeTest::init() {
  window_ = std::make_unique<MainWindow>();
  Settings s;
  s.virtual_scene.frame_rate_hz = 100.0;
  s.camera_source.device = kNoCamera.toStdString();
  window_->setSettings(s);
  window_->resize(1200, 800);
  window_->show();
}

void SourceChangeTest::cleanup() { window_.reset(); }

void SourceChangeTest::eachSourceShowsOnlyItsOwnState() {
  MainWindow& w = *window_;
  SourcePanel* panel = w.controlPanel()->sourcePanel();
  const QString virtual_source = QStringLiteral("virtual 100 Hz, Grey, Static");
  // Virtual, running: its frames and its name.
  QTRY_VERIFY(namedEverywhere(w, virtual_source));
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.truth && r.index >= 3; }));
  QTRY_VERIFY(!w.posePlots()->recorded().empty());

  // File chosen: Virtual stops, and nothing of it stays.
  choosePanelSource(w, SourceKind::File);
  QTRY_VERIFY(!w.worker()->isRunning());
  QTRY_VERIFY(namedEverywhere(w, QStringLiteral("file: none open")));
  QTRY_VERIFY(nothingShown(w));
  QVERIFY(w.frameView()->message().startsWith(QStringLiteral("No image open")));
  QCOMPARE(panel->button()->text(), QStringLiteral("Open File..."));
  // A file opened: its frame and its name.
  w.openPaths({kSamples + QStringLiteral("sample01_facing.png")});
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "sample01_facing.png"; }));
  QTRY_VERIFY(namedEverywhere(w, QStringLiteral("file sample01_facing.png")));

  // Virtual again: the file's frame goes; Virtual is named, waiting for Start.
  choosePanelSource(w, SourceKind::Virtual);
  QTRY_VERIFY(namedEverywhere(w, virtual_source));
  QTRY_VERIFY(nothingShown(w));
  QVERIFY(w.frameView()->message().contains(QStringLiteral("press Start")));

  // Camera, started where there is none: the device named, the error shown, no frame,
  // no "ok" left from Virtual.
  choosePanelSource(w, SourceKind::Camera);
  QTRY_VERIFY(namedEverywhere(w, QStringLiteral("camera %1 (not started)").arg(kNoCamera)));
  w.startSource();
  QTRY_VERIFY_WITH_TIMEOUT(w.bannerText().contains(kNoCamera), 5000);
  QTRY_VERIFY(namedEverywhere(w, QStringLiteral("camera %1 (unavailable)").arg(kNoCamera)));
  QVERIFY(!w.worker()->isRunning());
  QVERIFY(nothingShown(w));
  QVERIFY(w.frameView()->message().startsWith(QStringLiteral("Camera not opened: ")));
  QCOMPARE(panel->button()->text(), QStringLiteral("Start"));

  // Virtual once more: the camera's problem and name are gone; it starts as before.
  choosePanelSource(w, SourceKind::Virtual);
  QTRY_VERIFY(namedEverywhere(w, virtual_source));
  QVERIFY(w.bannerText().isEmpty());
  QVERIFY(nothingShown(w));
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.truth.has_value(); }));
  QTRY_VERIFY(statusLabel(w, "statusState")->text().startsWith(QStringLiteral("ok")));
  w.stopSource();
  QTRY_VERIFY(!w.worker()->isRunning());
}

// A banner from an earlier failure goes when a later load of the same kind succeeds, so
// the banner and the status bar never say opposite things.
void SourceChangeTest::bannerGoesWhenALaterLoadSucceeds() {
  MainWindow& w = *window_;
  const QString dir = scratchDir(QStringLiteral("banner"));
  const QString bad = dir + QStringLiteral("/bad.json");
  QFile file(bad);
  QVERIFY(file.open(QIODevice::WriteOnly));
  file.write(R"({"pipeline": {"edge_method": "canny"}})");
  file.close();
  QVERIFY(!w.loadSettingsFile(bad));
  QVERIFY(w.bannerText().contains(QStringLiteral("pipeline.edge_method")));
  const QString good = dir + QStringLiteral("/good.json");
  QVERIFY(w.saveSettingsFile(good));
  QVERIFY(w.loadSettingsFile(good));
  QVERIFY(w.bannerText().isEmpty());
  QVERIFY(w.statusBar()->currentMessage().startsWith(QStringLiteral("Settings loaded")));

  // A file that failed, then one that opens.
  w.openPaths({dir + QStringLiteral("/missing.png")});
  QTRY_VERIFY_WITH_TIMEOUT(w.bannerText().contains(QStringLiteral("missing.png")), 5000);
  w.openPaths({kSamples + QStringLiteral("sample02_clutter.png")});
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "sample02_clutter.png"; }));
  QTRY_VERIFY(w.bannerText().isEmpty());
}

// The title and the status bar: the source with the image's place in its list, and Data
// Out and the stream while they are on.
void SourceChangeTest::titleNamesTheSourceDataOutAndStream() {
  MainWindow& w = *window_;
  const QString dir = scratchDir(QStringLiteral("title"));
  for (const char* name : {"a.png", "b.png", "c.png"})
    QVERIFY(QFile::copy(kSamples + QStringLiteral("sample01_facing.png"), dir + QLatin1Char('/') + QLatin1String(name)));
  w.openPaths({dir});
  QTRY_VERIFY(w.windowTitle().contains(QStringLiteral("file a.png (1 of 3)")));
  w.stepFile(FileStep::Next);
  QTRY_VERIFY(namedEverywhere(w, QStringLiteral("file b.png (2 of 3)")));
  QVERIFY(!w.windowTitle().contains(QStringLiteral("Data Out")));

  QLabel* data_out = statusLabel(w, "statusDataOut");
  QVERIFY(data_out && !data_out->isVisible());
  const QString csv = dir + QStringLiteral("/poses.csv");
  QVERIFY(w.startDataOut(csv, ExistingFile::Fail, false));
  QTRY_VERIFY(w.windowTitle().contains(QStringLiteral("Data Out poses.csv")));
  QVERIFY(data_out->isVisible());
  QVERIFY(data_out->text().contains(QStringLiteral("poses.csv")));

  Settings s = w.settings();
  s.stream.enabled = true;
  s.stream.host = "127.0.0.1";
  s.stream.port = 5599;
  w.setSettings(s);
  QVERIFY(w.windowTitle().contains(QStringLiteral("Stream 127.0.0.1:5599")));

  w.stopDataOut();
  QTRY_VERIFY(!w.windowTitle().contains(QStringLiteral("Data Out")));
  QVERIFY(!data_out->isVisible());
  s.stream.enabled = false;
  w.setSettings(s);
  QVERIFY(!w.windowTitle().contains(QStringLiteral("Stream")));
  QVERIFY(w.windowTitle().contains(QStringLiteral("file b.png (2 of 3)")));
}

}  // namespace imagepro::app::test
