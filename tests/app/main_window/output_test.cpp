// Screenshot writes the results area as PNG; Data Out writes the pose CSV of every
// processed frame and never replaces a file unasked; the plots record and export.
#include <QFile>
#include <QFileInfo>
#include <QImage>
#include <QStatusBar>
#include <QTest>

#include <algorithm>
#include <vector>

#include "app/main_window/frame_view.h"
#include "app/main_window/main_window.h"
#include "app/plots/pose_plots.h"
#include "app/worker/worker.h"
#include "app_test_classes.h"
#include "app_test_support.h"
#include "core/common/pose_csv.h"
#include "core/pipeline/data_out.h"

namespace imagepro::app::test {

namespace {

QStringList readLines(const QString& path) {
  QFile f(path);
  if (!f.open(QIODevice::ReadOnly)) return {};
  return QString::fromUtf8(f.readAll()).split(QLatin1Char('\n'), Qt::SkipEmptyParts);
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
  // Appending keeps the old content.
  w.startDataOut(path, ExistingFile::Append, false);
  QTRY_COMPARE_WITH_TIMEOUT(w.dataOutPath(), path, 5000);
  w.stopDataOut();
  QTRY_VERIFY(w.dataOutPath().isEmpty());
  QCOMPARE(readLines(path).front(), QStringLiteral("precious"));
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
    QCOMPARE(f.readAll(), QByteArray("precious\n7,ok,1.5\n"));  // the next row will start on a line of its own
  }
  // Replacing only when asked for.
  w.startDataOut(path, ExistingFile::Fail, true);
  QTRY_COMPARE_WITH_TIMEOUT(w.dataOutPath(), path, 5000);
  w.stopDataOut();
  QTRY_VERIFY(w.dataOutPath().isEmpty());
  QCOMPARE(readLines(path), QStringList{QString::fromStdString(DataOut::header())});
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
  QVERIFY(lines.front().contains(QStringLiteral("truth_Tz_mm")));
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

}  // namespace imagepro::app::test
