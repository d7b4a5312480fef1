// Screenshot writes the results area as PNG; Data Out writes the pose CSV of every
// processed frame and never replaces a file unasked; the stream sends every frame to
// a reader and names its problems; the plots record and export.
#include <QAction>
#include <QAreaSeries>
#include <QChartView>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QImage>
#include <QLabel>
#include <QLineEdit>
#include <QLineSeries>
#include <QPointer>
#include <QSpinBox>
#include <QStatusBar>
#include <QPushButton>
#include <QTest>
#include <QTimer>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <iterator>
#include <vector>

#include "app/main_window/frame_view.h"
#include "app/main_window/main_window.h"
#include "app/panels/control_panel.h"
#include "app/panels/output_panel.h"
#include "app/panels/source_panel.h"
#include "app/plots/histogram_chart.h"
#include "app/plots/pose_plots.h"
#include "app/worker/worker.h"
#include "app_test_classes.h"
#include "app_test_support.h"
#include "core/common/pose_csv.h"
#include "core/pipeline/data_out.h"
#include "support/udp_receiver.h"

namespace imagepro::app::test {

namespace {

QStringList readLines(const QString& path) {
  QFile f(path);
  if (!f.open(QIODevice::ReadOnly)) return {};
  return QString::fromUtf8(f.readAll()).split(QLatin1Char('\n'), Qt::SkipEmptyParts);
}

// Sets the stream's destination in the Data Out panel and ticks its box, as a user would.
void switchStreamOn(MainWindow& w, const QString& host, int port) {
  QWidget* panel = w.findChild<OutputPanel*>();
  auto* host_edit = panel->findChild<QLineEdit*>(QStringLiteral("streamHost"));
  auto* port_box = panel->findChild<QSpinBox*>(QStringLiteral("streamPort"));
  QVERIFY(host_edit && port_box && panel->findChild<QComboBox*>(QStringLiteral("streamFormat")));
  QCOMPARE(host_edit->property("settingKey").toString(), QStringLiteral("stream.host"));
  QCOMPARE(port_box->maximum(), 65535);  // the settings table's range
  host_edit->setText(host);
  emit host_edit->editingFinished();
  port_box->setValue(port);
  QCheckBox* box = panel->findChild<QCheckBox*>(QStringLiteral("stream"));
  QVERIFY(box && !box->isChecked());  // off by default
  box->click();
}

}  // namespace

void OutputTest::init() {
  window_ = std::make_unique<MainWindow>();
  Settings s;
  s.virtual_scene.frame_rate_hz = 100.0;
  window_->setSettings(s);
  window_->resize(1000, 700);
  window_->show();
}

void OutputTest::cleanup() { window_.reset(); }

void OutputTest::screenshotWritesPng() {
  MainWindow& w = *window_;
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.index >= 2; }));
  w.stopSource();
  const QString path = scratchDir(QStringLiteral("screenshot")) + QStringLiteral("/results.png");
  QVERIFY(w.saveScreenshot(path));
  QImage shot;
  QVERIFY(shot.load(path, "PNG"));
  QCOMPARE(shot.size(), w.resultsArea()->size() * w.resultsArea()->devicePixelRatioF());
  // It shows the frame: the view's pixels are not all one colour.
  const QRect view(w.frameView()->mapTo(w.resultsArea(), QPoint(0, 0)), w.frameView()->size());
  const QImage part = shot.copy(view);
  QSet<QRgb> colours;
  for (int y = 0; y < part.height(); y += 7)
    for (int x = 0; x < part.width(); x += 7) colours.insert(part.pixel(x, y));
  QVERIFY(colours.size() > 3);
}

void OutputTest::screenshotToBadPathShowsError() {
  MainWindow& w = *window_;
  const QString path = scratchDir(QStringLiteral("bad")) + QStringLiteral("/no/such/folder/shot.png");
  QVERIFY(!w.saveScreenshot(path));
  QVERIFY(w.lastError().contains(path));
}

// The screenshot option (thesis A.1.1): while the file is being chosen the live source is
// stopped, the frame stays; after, it runs on. Without the option it never stops.
void OutputTest::screenshotFreezesProcessingWhileSaving() {
  MainWindow& w = *window_;
  w.setFreezeOnScreenshot(false);  // the option is remembered: start from off whatever ran before
  auto* freeze = w.findChild<QCheckBox*>(QStringLiteral("screenshotFreeze"));
  QVERIFY(freeze && !freeze->isChecked());
  freeze->click();
  QVERIFY(w.freezeOnScreenshot());
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.index >= 3; }));
  const QString dir = scratchDir(QStringLiteral("screenshot_freeze"));

  // While the save dialog is open: answers what it saw, then saves to `path`.
  struct Seen {
    bool dialog = false, frozen = false;
    std::int64_t before = -1, after = -1;
  };
  const auto screenshotThrough = [&w](const QString& path, Seen& seen) {
    QTimer::singleShot(0, &w, [&w, &seen, path] {
      QFileDialog* dialog = nullptr;
      for (int i = 0; i < 500 && !dialog; ++i) {
        dialog = qobject_cast<QFileDialog*>(QApplication::activeModalWidget());
        if (!dialog) QTest::qWait(10);
      }
      if (!dialog) return;
      seen.dialog = true;
      QTest::qWait(300);  // the queued stop has reached the worker
      seen.frozen = w.frozenForScreenshot() && !w.worker()->isRunning();
      seen.before = w.worker()->framesProcessed();
      QTest::qWait(300);
      seen.after = w.worker()->framesProcessed();
      // The name typed in, as the operator would (selectFile keeps the suggested name here).
      if (auto* name = dialog->findChild<QLineEdit*>(QStringLiteral("fileNameEdit"))) name->setText(path);
      else dialog->selectFile(path);
      static_cast<QDialog*>(dialog)->accept();  // public as QDialog's
    });
    w.findChild<QPushButton*>(QStringLiteral("screenshot"))->click();  // returns when the dialog closes
  };

  Seen frozen;
  const QString path = dir + QStringLiteral("/frozen.png");
  screenshotThrough(path, frozen);
  QVERIFY(frozen.dialog);
  QVERIFY(frozen.frozen);
  QCOMPARE(frozen.after, frozen.before);  // no frame processed while the operator chose the file
  QVERIFY2(QFileInfo::exists(path), qPrintable(w.lastError() + QLatin1Char(' ') + w.statusBar()->currentMessage()));
  QVERIFY(!w.frozenForScreenshot());
  QTRY_VERIFY_WITH_TIMEOUT(w.worker()->isRunning(), 5000);  // resumed
  const std::int64_t resumed = w.worker()->framesProcessed();
  QTRY_VERIFY_WITH_TIMEOUT(w.worker()->framesProcessed() > resumed + 3, 5000);

  // The option off (also from the File menu's action): the source runs on through the dialog.
  auto* action = w.findChild<QAction*>(QStringLiteral("screenshotFreezeAction"));
  QVERIFY(action && action->isChecked());
  action->trigger();
  QVERIFY(!w.freezeOnScreenshot());
  QVERIFY(!freeze->isChecked());
  Seen running;
  screenshotThrough(dir + QStringLiteral("/running.png"), running);
  QVERIFY(running.dialog);
  QVERIFY(!running.frozen);
  QVERIFY(running.after > running.before);
  w.stopSource();
  QTRY_VERIFY(!w.worker()->isRunning());
}

void OutputTest::dataOutWritesEveryFrame() {
  MainWindow& w = *window_;
  const QString path = scratchDir(QStringLiteral("dataout")) + QStringLiteral("/dataout.csv");
  w.startDataOut(path, ExistingFile::Fail, false);
  QTRY_COMPARE_WITH_TIMEOUT(w.dataOutPath(), path, 5000);
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  QTRY_VERIFY_WITH_TIMEOUT(w.worker()->framesProcessed() >= 10, 10000);
  // Flushed every frame: the rows are on disk while it runs.
  QTRY_VERIFY_WITH_TIMEOUT(readLines(path).size() >= 5, 5000);
  w.stopSource();
  QTRY_VERIFY(!w.worker()->isRunning());
  w.stopDataOut();
  QTRY_VERIFY_WITH_TIMEOUT(w.dataOutPath().isEmpty(), 5000);
  const std::int64_t frames = w.worker()->framesProcessed();
  const QStringList lines = readLines(path);
  QCOMPARE(lines.front(), QString::fromStdString(DataOut::header()));
  QVERIFY(QString::fromStdString(DataOut::header()).startsWith(QString::fromStdString(poseCsvHeader())));
  QCOMPARE(static_cast<std::int64_t>(lines.size() - 1), frames);
  // Rows in frame order, each with a status and, when ok, the pose.
  for (int i = 1; i < lines.size(); ++i) {
    const QStringList cols = lines[i].split(QLatin1Char(','));
    QVERIFY(cols.size() >= 8);
    QCOMPARE(cols[0].toLongLong(), static_cast<long long>(i - 1));
    if (cols[1] == QStringLiteral("ok")) QVERIFY(cols[7].toDouble() > 500.0);  // Tz near the virtual 800 mm
  }
}

void OutputTest::streamFromTheDataOutPanel() {
  MainWindow& w = *window_;
  imagepro::test::UdpReceiver reader;
  QVERIFY(reader.port() != 0);
  switchStreamOn(w, QStringLiteral("127.0.0.1"), reader.port());
  QTRY_VERIFY(w.worker()->appliedSettings().stream.enabled);
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  std::vector<std::string> got;
  QTRY_VERIFY_WITH_TIMEOUT((std::ranges::move(reader.drain(), std::back_inserter(got)), got.size() >= 20), 10000);
  // One datagram a frame, in order, from the first frame on.
  for (std::size_t i = 0; i < got.size(); ++i) {
    const auto j = nlohmann::json::parse(got[i]);
    QCOMPARE(j["frame"].get<std::int64_t>(), static_cast<std::int64_t>(i));
    QCOMPARE(j["status"].get<std::string>(), std::string("ok"));
  }
  auto* label = w.statusBar()->findChild<QLabel*>(QStringLiteral("statusStream"));
  QVERIFY(label);
  const QString expected = QStringLiteral("Stream udp://127.0.0.1:%1 json: ").arg(reader.port());
  QTRY_VERIFY_WITH_TIMEOUT(label->isVisible() && label->text().startsWith(expected), 5000);
  QVERIFY2(label->text().contains(QStringLiteral(" sent, 0 dropped")), qPrintable(label->text()));
  // Switched off, the sending stops and the label goes.
  w.findChild<OutputPanel*>()->streamBox()->click();
  QTRY_VERIFY_WITH_TIMEOUT(!label->isVisible(), 5000);
  reader.drain();
  QTest::qWait(200);
  QVERIFY(reader.drain().empty());
  w.stopSource();
}

void OutputTest::streamProblemIsNamedInTheStatusBar() {
  MainWindow& w = *window_;
  switchStreamOn(w, QStringLiteral("no such host!"), 5005);
  QTRY_VERIFY_WITH_TIMEOUT(w.lastError().contains(QStringLiteral("no such host!")), 5000);
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  QTRY_VERIFY_WITH_TIMEOUT(w.worker()->framesProcessed() >= 5, 10000);
  auto* label = w.statusBar()->findChild<QLabel*>(QStringLiteral("statusStream"));
  QTRY_VERIFY_WITH_TIMEOUT(label->text().contains(QStringLiteral("StreamHostNotFound")), 5000);
  QVERIFY2(label->text().contains(QStringLiteral("0 sent")), qPrintable(label->text()));
  QVERIFY(label->styleSheet().contains(QStringLiteral("color")));  // shown as a problem
  w.stopSource();
}

void OutputTest::dataOutNeverOverwritesSilently() {
  MainWindow& w = *window_;
  const QString path = scratchDir(QStringLiteral("existing")) + QStringLiteral("/dataout.csv");
  {
    QFile f(path);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("precious\n");
  }
  w.startDataOut(path, ExistingFile::Fail, false);
  QTRY_VERIFY_WITH_TIMEOUT(w.lastError().contains(QStringLiteral("dataout.csv")), 5000);
  QVERIFY(w.dataOutPath().isEmpty());
  QCOMPARE(readLines(path), QStringList{QStringLiteral("precious")});
  // Rows go only under today's header: appending to another file is refused, the file kept.
  w.startDataOut(path, ExistingFile::Append, false);
  QTRY_VERIFY_WITH_TIMEOUT(w.lastError().contains(QStringLiteral("not appended to")), 5000);
  QVERIFY(w.dataOutPath().isEmpty());
  QCOMPARE(readLines(path), QStringList{QStringLiteral("precious")});
  // Under today's header, appending keeps the old content.
  const QByteArray header = QByteArray::fromStdString(DataOut::header()) + "\n";
  {
    QFile f(path);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(header);
  }
  w.startDataOut(path, ExistingFile::Append, false);
  QTRY_COMPARE_WITH_TIMEOUT(w.dataOutPath(), path, 5000);
  w.stopDataOut();
  QTRY_VERIFY(w.dataOutPath().isEmpty());
  QCOMPARE(readLines(path).front(), QString::fromStdString(DataOut::header()));
  // A row a crash cut off: appending starts on a new line and the status bar says the row is lost.
  {
    QFile f(path);
    QVERIFY(f.open(QIODevice::Append));
    f.write("7,ok,1.5");
  }
  w.startDataOut(path, ExistingFile::Append, false);
  QTRY_COMPARE_WITH_TIMEOUT(w.dataOutPath(), path, 5000);
  QTRY_VERIFY_WITH_TIMEOUT(w.statusBar()->currentMessage().contains(QStringLiteral("last row was cut off")), 5000);
  w.stopDataOut();
  QTRY_VERIFY(w.dataOutPath().isEmpty());
  {
    QFile f(path);
    QVERIFY(f.open(QIODevice::ReadOnly));
    QCOMPARE(f.readAll(), header + "7,ok,1.5\n");  // the next row will start on a line of its own
  }
  // Replacing only when asked for.
  w.startDataOut(path, ExistingFile::Fail, true);
  QTRY_COMPARE_WITH_TIMEOUT(w.dataOutPath(), path, 5000);
  w.stopDataOut();
  QTRY_VERIFY(w.dataOutPath().isEmpty());
  QCOMPARE(readLines(path), QStringList{QString::fromStdString(DataOut::header())});
}

// Ctrl+D as the manual says: the file dialog while Data Out is off, Data Out off while it
// writes (no dialog). While it writes the status bar says so, whatever else it shows.
void OutputTest::dataOutTogglesWithCtrlD() {
  MainWindow& w = *window_;
  w.activateWindow();
  QVERIFY(QTest::qWaitForWindowActive(&w));
  const QString path = scratchDir(QStringLiteral("dataout_toggle")) + QStringLiteral("/rows.csv");
  auto* indicator = w.statusBar()->findChild<QLabel*>(QStringLiteral("statusDataOut"));
  QVERIFY(indicator && !indicator->isVisible());
  FileDialogAnswer answer;
  answerFileDialog(answer, path);
  QTest::keyClick(&w, Qt::Key_D, Qt::ControlModifier);
  QVERIFY(answer.seen);
  QTRY_COMPARE_WITH_TIMEOUT(w.dataOutPath(), path, 5000);
  QVERIFY(w.findChild<QAction*>(QStringLiteral("dataOutAction"))->isChecked());
  QVERIFY(w.controlPanel()->outputPanel()->dataOutBox()->isChecked());
  QVERIFY(indicator->isVisible());
  QVERIFY(indicator->text().contains(QStringLiteral("rows.csv")));
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  QTRY_VERIFY_WITH_TIMEOUT(readLines(path).size() >= 5, 10000);
  // A message in the status bar does not hide it.
  w.statusBar()->showMessage(QStringLiteral("something else"), 5000);
  QVERIFY(indicator->isVisible());

  // Ctrl+D while writing: off, without a dialog (one would be cancelled and noted here).
  w.activateWindow();  // back from the dialog
  QVERIFY(QTest::qWaitForWindowActive(&w));
  answerFileDialog(answer, {}, 1000);
  QTest::keyClick(&w, Qt::Key_D, Qt::ControlModifier);
  QTRY_VERIFY_WITH_TIMEOUT(w.dataOutPath().isEmpty(), 5000);
  QVERIFY(!indicator->isVisible());
  QCOMPARE(w.statusBar()->currentMessage(), QStringLiteral("Data Out stopped: %1 closed").arg(path));
  QVERIFY(!w.findChild<QAction*>(QStringLiteral("dataOutAction"))->isChecked());
  QVERIFY(!w.controlPanel()->outputPanel()->dataOutBox()->isChecked());
  const int rows = readLines(path).size();
  QTest::qWait(300);  // also runs the answer's wait for a dialog to its end
  QCOMPARE(readLines(path).size(), rows);  // no row after it went off
  QVERIFY(!answer.seen);
  w.stopSource();
}

// Data Out writes CSV: an image's name is refused with the reason, a name without an
// extension gets .csv.
void OutputTest::dataOutRefusesANameThatIsNotCsv() {
  MainWindow& w = *window_;
  const QString dir = scratchDir(QStringLiteral("dataout_names"));
  QVERIFY(!w.startDataOut(dir + QStringLiteral("/poses.png"), ExistingFile::Fail, false));
  QVERIFY(w.lastError().contains(QStringLiteral("\"poses.png\"")));
  QVERIFY(w.lastError().contains(QStringLiteral(".csv or .txt")));
  QVERIFY(w.bannerText().contains(QStringLiteral("poses.png")));
  QTest::qWait(200);
  QVERIFY(w.dataOutPath().isEmpty());
  QVERIFY(!QFileInfo::exists(dir + QStringLiteral("/poses.png")));

  // The same from the dialog.
  FileDialogAnswer answer;
  answerFileDialog(answer, dir + QStringLiteral("/shot.png"));
  w.findChild<QCheckBox*>(QStringLiteral("dataOut"))->click();
  QVERIFY(answer.seen);
  QVERIFY(w.lastError().contains(QStringLiteral("\"shot.png\"")));
  QTest::qWait(200);
  QVERIFY(w.dataOutPath().isEmpty());
  QVERIFY(!w.findChild<QCheckBox*>(QStringLiteral("dataOut"))->isChecked());
  QVERIFY(!QFileInfo::exists(dir + QStringLiteral("/shot.png")));

  // No extension: .csv added, and said.
  answerFileDialog(answer, dir + QStringLiteral("/poses"));
  w.findChild<QCheckBox*>(QStringLiteral("dataOut"))->click();
  QVERIFY(answer.seen);
  QTRY_COMPARE_WITH_TIMEOUT(w.dataOutPath(), dir + QStringLiteral("/poses.csv"), 5000);
  QCOMPARE(readLines(dir + QStringLiteral("/poses.csv")).value(0), QString::fromStdString(DataOut::header()));
  // The thesis's dataout.txt is CSV text too.
  w.stopDataOut();
  QTRY_VERIFY(w.dataOutPath().isEmpty());
  QVERIFY(w.startDataOut(dir + QStringLiteral("/dataout.txt"), ExistingFile::Fail, false));
  QTRY_COMPARE_WITH_TIMEOUT(w.dataOutPath(), dir + QStringLiteral("/dataout.txt"), 5000);
  w.stopDataOut();
}

void OutputTest::plotsRecordAndExport() {
  MainWindow& w = *window_;
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  QTRY_VERIFY_WITH_TIMEOUT(w.posePlots()->recorded().size() >= 10, 10000);
  w.posePlots()->setPaused(true);
  w.stopSource();
  QTRY_VERIFY(!w.worker()->isRunning());
  QTest::qWait(100);  // the last packet may still be on its way
  const std::size_t recorded = w.posePlots()->recorded().size();
  // Every frame is recorded even though the display may skip some: indices are consecutive.
  const auto& samples = w.posePlots()->recorded();
  for (std::size_t i = 1; i < samples.size(); ++i) QCOMPARE(samples[i].index, samples[i - 1].index + 1);
  const QString path = scratchDir(QStringLiteral("plots")) + QStringLiteral("/poses.csv");
  QString error;
  QVERIFY2(w.posePlots()->exportCsv(path, error), qPrintable(error));
  const QStringList lines = readLines(path);
  QCOMPARE(static_cast<std::size_t>(lines.size()), recorded + 1);
  QVERIFY(lines.front().startsWith(QString::fromStdString(poseCsvHeader())));
  QVERIFY(lines.front().contains(QStringLiteral("true_Tz_mm")));
  QVERIFY(!w.posePlots()->exportCsv(scratchDir(QStringLiteral("plots2")) + QStringLiteral("/no/dir/x.csv"), error));
  QVERIFY(!error.isEmpty());
}

// A long run's recording levels off at the bound: the oldest samples go, the newest stay
// in order (the application's soak counts on it, docs/reliability.md).
void OutputTest::plotsRecordingIsBounded() {
  PosePlots plots;
  std::vector<PoseSample> chunk(1000);
  std::int64_t next = 0;
  std::size_t largest = 0;
  while (next < static_cast<std::int64_t>(PosePlots::kMaxRecorded) * 3 / 2) {
    for (PoseSample& s : chunk) s.index = next++;
    plots.append(chunk);
    largest = std::max(largest, plots.recorded().size());
  }
  QCOMPARE(largest, PosePlots::kMaxRecorded);
  const auto& recorded = plots.recorded();
  QVERIFY(recorded.size() >= PosePlots::kMaxRecorded * 9 / 10);
  QCOMPARE(recorded.back().index, next - 1);
  for (std::size_t i = 1; i < recorded.size(); ++i) QCOMPARE(recorded[i].index, recorded[i - 1].index + 1);
}

// Every series of the histogram goes with the chart: the area's line of counts, which
// no chart owns, outlived each main window (LeakSanitizer, docs/reliability.md).
void OutputTest::histogramChartFreesItsSeries() {
  QPointer<QLineSeries> counts;
  {
    HistogramChart chart;
    auto* view = chart.findChild<QChartView*>();
    QVERIFY(view != nullptr);
    for (QAbstractSeries* s : view->chart()->series())
      if (auto* area = qobject_cast<QAreaSeries*>(s)) counts = area->upperSeries();
    QVERIFY(!counts.isNull());
  }
  QVERIFY(counts.isNull());
}

}  // namespace imagepro::app::test
