// File input: the image is processed and its parameters shown; an option change
// reprocesses it; folders play in natural order; a bad file is a message, not a crash.
#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QDir>
#include <QDropEvent>
#include <QFileInfo>
#include <QMimeData>
#include <QUrl>
#include <QFile>
#include <QSpinBox>
#include <QTest>

#include <cmath>

#include "app/panels/control_panel.h"
#include "app/main_window/frame_view.h"
#include "app/main_window/main_window.h"
#include "app/main_window/results_text.h"
#include "app/panels/source_panel.h"
#include "app/worker/worker.h"
#include "app_test_classes.h"
#include "app_test_support.h"

namespace imagepro::app::test {

namespace {

const QString kSamples = QStringLiteral(IMAGEPRO_DATA_DIR "/samples/");

}  // namespace

void FileTest::init() {
  window_ = std::make_unique<MainWindow>();
  window_->show();
}

void FileTest::cleanup() { window_.reset(); }

void FileTest::fileIsProcessedAndParametersShown() {
  MainWindow& w = *window_;
  w.openPaths({kSamples + QStringLiteral("sample01_facing.png")});
  QCOMPARE(w.controlPanel()->sourcePanel()->kind(), SourceKind::File);
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "sample01_facing.png"; }));
  const FrameResult& r = w.frameView()->packet()->result;
  // data/samples/truth.csv: facing the camera at Tz = 800 mm.
  QVERIFY2(r.status == Status::Ok, statusName(r.status).data());
  QVERIFY(r.pose.has_value());
  QVERIFY(std::abs(r.pose->tz_mm - 800.0) < 16.0);
  QVERIFY(std::abs(r.pose->tx_mm) < 5.0 && std::abs(r.pose->ty_mm) < 5.0);
  // The results text follows within its refresh interval.
  QTRY_VERIFY(w.resultsText().contains(QStringLiteral("sample01_facing.png")));
  const QString text = w.resultsText();
  QVERIFY(text.contains(QString::number(r.pose->tz_mm, 'f', 2)));
  QVERIFY(text.contains(QStringLiteral("Threshold %1").arg(r.threshold)));
  QVERIFY(text.contains(QStringLiteral("Status    ok")));
  // A single file is processed once; the worker then waits.
  QTRY_VERIFY(!w.worker()->isRunning());
}

void FileTest::optionChangeReprocessesTheFile() {
  MainWindow& w = *window_;
  w.openPaths({kSamples + QStringLiteral("sample02_clutter.png")});
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "sample02_clutter.png"; }));
  QTRY_VERIFY(!w.worker()->isRunning());
  QVERIFY(choose(w.findChild<QComboBox*>(QStringLiteral("thresholdMethod")), ThresholdMethod::Manual));
  w.findChild<QSpinBox*>(QStringLiteral("thresholdValue"))->setValue(61);
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "sample02_clutter.png" && r.threshold == 61; }));
  QVERIFY(!w.worker()->isRunning());
}

void FileTest::folderIsPlayedInNaturalOrder() {
  MainWindow& w = *window_;
  const QString dir = scratchDir(QStringLiteral("folder"));
  // img10 after img2: natural order, not text order.
  QVERIFY(QFile::copy(kSamples + QStringLiteral("sample01_facing.png"), dir + QStringLiteral("/img2.png")));
  QVERIFY(QFile::copy(kSamples + QStringLiteral("sample03_tilted50.png"), dir + QStringLiteral("/img10.png")));
  w.openPaths({dir});
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "img10.png"; }));
  QTRY_VERIFY(!w.worker()->isRunning());
  // The last image stays and is the one reprocessed.
  QCOMPARE(w.frameView()->packet()->result.name, std::string("img10.png"));
}

// A list of paths plays in its order whatever its name ends in (the CLI's rule, one
// function for both); a file that is neither an image nor text is refused by name.
void FileTest::listFilePlaysInItsOrder() {
  MainWindow& w = *window_;
  const QString dir = scratchDir(QStringLiteral("list"));
  QFile list(dir + QStringLiteral("/frames.lst"));
  QVERIFY(list.open(QIODevice::WriteOnly));
  list.write((kSamples + QStringLiteral("sample03_tilted50.png\n# a comment\n") + kSamples +
              QStringLiteral("sample01_facing.png\n")).toUtf8());
  list.close();
  w.openPaths({list.fileName()});
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "sample01_facing.png"; }));
  QTRY_VERIFY(!w.worker()->isRunning());

  QFile binary(dir + QStringLiteral("/clip.mp4"));
  QVERIFY(binary.open(QIODevice::WriteOnly));
  binary.write(QByteArray("\0\0\0\x18" "ftypmp42", 12));
  binary.close();
  w.openPaths({binary.fileName(), kSamples + QStringLiteral("sample01_facing.png")});
  QTRY_VERIFY_WITH_TIMEOUT(w.lastError().contains(QStringLiteral("clip.mp4: neither an image file")), 5000);
}

void FileTest::missingFileShowsAnError() {
  MainWindow& w = *window_;
  const QString missing = scratchDir(QStringLiteral("missing")) + QStringLiteral("/nothing-here.png");
  w.openPaths({missing});
  QTRY_VERIFY_WITH_TIMEOUT(!w.lastError().isEmpty(), 5000);
  QVERIFY(w.lastError().contains(QStringLiteral("nothing-here.png")));
  // A folder without images is refused with a message as well.
  const QString empty = scratchDir(QStringLiteral("empty"));
  w.openPaths({empty});
  QTRY_VERIFY_WITH_TIMEOUT(w.lastError().contains(QStringLiteral("empty")), 5000);
  // The window still works: a good file afterwards is processed.
  w.openPaths({kSamples + QStringLiteral("sample01_facing.png")});
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "sample01_facing.png"; }));
}

void FileTest::droppedFilesAreOpenedAndRemembered() {
  MainWindow& w = *window_;
  const QString file = kSamples + QStringLiteral("sample03_tilted50.png");
  QMimeData mime;
  mime.setUrls({QUrl::fromLocalFile(file)});
  QDragEnterEvent enter(QPoint(10, 10), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(&w, &enter);
  QVERIFY(enter.isAccepted());
  QDropEvent drop(QPointF(10, 10), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(&w, &drop);
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "sample03_tilted50.png"; }));
  QCOMPARE(w.recentPaths().value(0), QFileInfo(file).absoluteFilePath());
  // Remembered by the next window too.
  window_.reset();
  MainWindow again;
  QCOMPARE(again.recentPaths().value(0), QFileInfo(file).absoluteFilePath());
  // Something that is not a file is not accepted.
  QMimeData text;
  text.setText(QStringLiteral("hello"));
  QDragEnterEvent refuse(QPoint(10, 10), Qt::CopyAction, &text, Qt::LeftButton, Qt::NoModifier);
  refuse.setAccepted(false);
  QApplication::sendEvent(&again, &refuse);
  QVERIFY(!refuse.isAccepted());
}

// File > Open Samples plays the shipped sample frames, found as the installed program
// finds them (here, from the build tree: the sources' data/samples).
void FileTest::samplesOpenFromTheMenu() {
  MainWindow& w = *window_;
  QAction* open = nullptr;
  for (QAction* a : w.findChildren<QAction*>())
    if (a->text() == QStringLiteral("Open S&amples")) open = a;
  QVERIFY(open);
  open->trigger();
  QCOMPARE(w.controlPanel()->sourcePanel()->kind(), SourceKind::File);
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "sample08_pattern.png"; }));
  QTRY_VERIFY(!w.worker()->isRunning());
  QVERIFY(w.lastError().isEmpty());
}

// The results text of a frame whose spots could not tell the rim's two circles apart: an
// ok pose halfway between them, or AmbiguousPose without one; both circles are listed.
void FileTest::resultsShowBothPosesOfADoubt() {
  DisplayPacket packet;
  FrameResult& r = packet.result;
  r.status = Status::Ok;
  r.pose = Pose{0, 0, 10, 1, 2, 2000};
  r.ambiguous_poses = std::array<Pose, 2>{Pose{3, 0, 10, 1, 2, 2000}, Pose{-3, 0, 10, 1, 2, 2000}};
  QString text = formatResults(packet);
  QVERIFY(text.contains(QStringLiteral("halfway between:")));
  QVERIFY(text.contains(QStringLiteral("Alt 1 Rx    3.00")));
  QVERIFY(text.contains(QStringLiteral("Alt 2 Rx   -3.00")));
  r.status = Status::AmbiguousPose;
  r.pose.reset();
  text = formatResults(packet);
  QVERIFY(text.contains(QStringLiteral("Pose      -")));
  QVERIFY(text.contains(QStringLiteral("the rim's two poses:")));
  QVERIFY(text.contains(QStringLiteral("Alt 2 Rx   -3.00")));
  r.ambiguous_poses.reset();
  QVERIFY(!formatResults(packet).contains(QStringLiteral("Alt 1")));
}

}  // namespace imagepro::app::test
