// File input: the image is processed and its parameters shown; an option change
// reprocesses it; folders are stepped through in natural order, with the keys and the
// panel's buttons, and played with Start; a bad file is a message, not a crash, and
// leaves the recent list; the file dialogs start where the user last was.
#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QDir>
#include <QLabel>
#include <QPushButton>
#include <QSettings>
#include <QToolButton>
#include <QDropEvent>
#include <QFileInfo>
#include <QMimeData>
#include <QUrl>
#include <QFile>
#include <QSpinBox>
#include <QTest>

#include <cmath>

#include "app/calibration_wizard/calibration_wizard.h"
#include "app/panels/control_panel.h"
#include "app/plots/pose_plots.h"
#include "app/main_window/dialog_folder.h"
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

void FileTest::folderIsInNaturalOrder() {
  MainWindow& w = *window_;
  const QString dir = scratchDir(QStringLiteral("folder"));
  // img10 after img2: natural order, not text order.
  QVERIFY(QFile::copy(kSamples + QStringLiteral("sample01_facing.png"), dir + QStringLiteral("/img2.png")));
  QVERIFY(QFile::copy(kSamples + QStringLiteral("sample03_tilted50.png"), dir + QStringLiteral("/img10.png")));
  w.openPaths({dir});
  // The first image is shown and stays; the next one is a step away.
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "img2.png"; }));
  QTRY_VERIFY(!w.worker()->isRunning());
  w.stepFile(FileStep::Next);
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "img10.png"; }));
  QVERIFY(!w.worker()->isRunning());
}

namespace {

// A folder of `n` sample frames named img1.png ... imgN.png.
bool shows(MainWindow& w, const char* name) {
  return waitForFrame(w, [name](const FrameResult& r) { return r.name == name; }, 10000);
}

}  // namespace

// `imagepro FOLDER` shows the first image, and the user steps to any other: the keys the
// manual names on the frame, and the Input Source panel's buttons, which say where they are.
void FileTest::folderIsSteppedWithKeysAndButtons() {
  MainWindow& w = *window_;
  w.openPaths({numberedFolder(QStringLiteral("stepped"), 4)});
  QVERIFY(shows(w, "img1.png"));
  QTRY_VERIFY(!w.worker()->isRunning());
  const std::int64_t processed = w.worker()->framesProcessed();
  SourcePanel* panel = w.controlPanel()->sourcePanel();
  QTRY_COMPARE(panel->filePosition()->text(), QStringLiteral("1 of 4"));
  QVERIFY(panel->fileRow()->isVisible());
  QCOMPARE(panel->button()->text(), QStringLiteral("Start"));
  QTRY_VERIFY(w.windowTitle().contains(QStringLiteral("file img1.png (1 of 4)")));

  w.frameView()->setFocus();
  QTest::keyClick(w.frameView(), Qt::Key_Right);
  QVERIFY(shows(w, "img2.png"));
  QTest::keyClick(w.frameView(), Qt::Key_PageDown);
  QVERIFY(shows(w, "img3.png"));
  QTest::keyClick(w.frameView(), Qt::Key_End);
  QVERIFY(shows(w, "img4.png"));
  QTRY_COMPARE(panel->filePosition()->text(), QStringLiteral("4 of 4"));
  QTRY_VERIFY(w.windowTitle().contains(QStringLiteral("file img4.png (4 of 4)")));
  QTest::keyClick(w.frameView(), Qt::Key_Left);
  QVERIFY(shows(w, "img3.png"));
  QTest::keyClick(w.frameView(), Qt::Key_PageUp);
  QVERIFY(shows(w, "img2.png"));
  QTest::keyClick(w.frameView(), Qt::Key_Home);
  QVERIFY(shows(w, "img1.png"));
  // At the first image, back goes nowhere.
  panel->findChild<QToolButton*>(QStringLiteral("filePrevious"))->click();
  QTest::qWait(200);
  QCOMPARE(w.frameView()->packet()->result.name, std::string("img1.png"));

  // The buttons.
  panel->findChild<QToolButton*>(QStringLiteral("fileNext"))->click();
  QVERIFY(shows(w, "img2.png"));
  panel->findChild<QToolButton*>(QStringLiteral("fileLast"))->click();
  QVERIFY(shows(w, "img4.png"));
  panel->findChild<QToolButton*>(QStringLiteral("filePrevious"))->click();
  QVERIFY(shows(w, "img3.png"));
  panel->findChild<QToolButton*>(QStringLiteral("fileFirst"))->click();
  QVERIFY(shows(w, "img1.png"));
  QTRY_COMPARE(panel->filePosition()->text(), QStringLiteral("1 of 4"));
  // Each step processed its one image; nothing played on.
  QCOMPARE(w.worker()->framesProcessed(), processed + 10);
  QVERIFY(!w.worker()->isRunning());

  // The image shown is the one an option change reprocesses.
  QVERIFY(choose(w.findChild<QComboBox*>(QStringLiteral("thresholdMethod")), ThresholdMethod::Manual));
  w.findChild<QSpinBox*>(QStringLiteral("thresholdValue"))->setValue(77);
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "img1.png" && r.threshold == 77; }));
}

// Start / Stop (F5) plays the list from the image shown to the last, as the manual says;
// with nothing to play it asks for files.
void FileTest::startPlaysTheRestOfTheImages() {
  MainWindow& w = *window_;
  w.openPaths({numberedFolder(QStringLiteral("played"), 5)});
  QVERIFY(shows(w, "img1.png"));
  w.stepFile(FileStep::Next);
  QVERIFY(shows(w, "img2.png"));
  QTRY_VERIFY(!w.worker()->isRunning());
  const std::int64_t before = w.worker()->framesProcessed();
  w.activateWindow();
  QVERIFY(QTest::qWaitForWindowActive(&w));
  QTest::keyClick(&w, Qt::Key_F5);
  QVERIFY(shows(w, "img5.png"));
  QTRY_VERIFY(!w.worker()->isRunning());
  QCOMPARE(w.worker()->framesProcessed(), before + 3);  // img3, img4, img5
  QVERIFY(QApplication::activeModalWidget() == nullptr);  // no file dialog
  // Played to its end, Start plays it again from the first image.
  w.controlPanel()->sourcePanel()->button()->click();
  QTRY_VERIFY_WITH_TIMEOUT(w.worker()->framesProcessed() == before + 8, 10000);
  QVERIFY(shows(w, "img5.png"));

  // One image has nothing to play: the button and F5 ask for files.
  w.openPaths({kSamples + QStringLiteral("sample01_facing.png")});
  QVERIFY(shows(w, "sample01_facing.png"));
  QTRY_COMPARE(w.controlPanel()->sourcePanel()->button()->text(), QStringLiteral("Open File..."));
  FileDialogAnswer answer;
  answerFileDialog(answer);
  QTest::keyClick(&w, Qt::Key_F5);
  QTRY_VERIFY(answer.seen);
}

// Only what loaded is remembered: a missing file, an empty folder, or a remembered file
// that has since gone leave the recent list.
void FileTest::recentFilesKeepOnlyWhatLoaded() {
  MainWindow& w = *window_;
  const QString dir = scratchDir(QStringLiteral("recent"));
  const QString missing = dir + QStringLiteral("/missing.png");
  w.openPaths({missing});
  QTRY_VERIFY_WITH_TIMEOUT(w.lastError().contains(QStringLiteral("missing.png")), 5000);
  QTest::qWait(100);
  QVERIFY(!w.recentPaths().contains(missing));
  const QString empty = scratchDir(QStringLiteral("recent-empty"));
  w.openPaths({empty});
  QTRY_VERIFY_WITH_TIMEOUT(w.lastError().contains(QStringLiteral("recent-empty")), 5000);
  QTest::qWait(100);
  QVERIFY(!w.recentPaths().contains(empty));

  const QString file = dir + QStringLiteral("/kept.png");
  QVERIFY(QFile::copy(kSamples + QStringLiteral("sample01_facing.png"), file));
  w.openPaths({file});
  QVERIFY(shows(w, "kept.png"));
  QTRY_COMPARE(w.recentPaths().value(0), file);
  // Gone since: chosen from File > Recent, it fails and leaves the list.
  QVERIFY(QFile::remove(file));
  QAction* entry = nullptr;
  for (QAction* a : w.findChildren<QAction*>())
    if (a->toolTip() == file) entry = a;
  QVERIFY(entry);
  entry->trigger();
  QTRY_VERIFY_WITH_TIMEOUT(!w.recentPaths().contains(file), 5000);
  QVERIFY(w.bannerText().contains(QStringLiteral("kept.png")));
}

// The Open, Data Out and Screenshot dialogs start in the home folder until the user has
// chosen a folder, then where the user last was; never in the shipped samples' folder.
void FileTest::dialogsStartWhereTheUserLastWas() {
  window_.reset();
  QSettings().remove(QStringLiteral("lastDirectory"));
  window_ = std::make_unique<MainWindow>();
  window_->show();
  MainWindow& w = *window_;
  const QString home = QDir(QDir::homePath()).absolutePath();
  QCOMPARE(w.dialogDirectory(), home);
  FileDialogAnswer answer;
  answerFileDialog(answer);
  w.controlPanel()->sourcePanel()->setKind(SourceKind::File);
  w.controlPanel()->sourcePanel()->button()->click();  // Open File...
  QVERIFY(answer.seen);
  QCOMPARE(answer.directory, home);
  // The samples are no place the user chose.
  w.openSamples();
  QVERIFY(shows(w, "sample01_facing.png"));
  QCOMPARE(w.dialogDirectory(), home);

  // An image chosen in the Open dialog: the dialogs then start in its folder.
  const QString dir = numberedFolder(QStringLiteral("dialogs"), 1);
  answerFileDialog(answer, dir + QStringLiteral("/img1.png"));
  w.controlPanel()->sourcePanel()->findChild<QToolButton*>(QStringLiteral("fileOpen"))->click();
  QVERIFY(answer.seen);
  QVERIFY(shows(w, "img1.png"));
  QCOMPARE(w.dialogDirectory(), dir);
  answerFileDialog(answer);
  w.findChild<QAction*>(QStringLiteral("dataOutAction"))->trigger();
  QVERIFY(answer.seen);
  QCOMPARE(answer.directory, dir);
  answerFileDialog(answer);
  w.findChild<QPushButton*>(QStringLiteral("screenshot"))->click();
  QVERIFY(answer.seen);
  QCOMPARE(answer.directory, dir);
  // The windows beside the main one share the folder: the plots' export, the calibration
  // wizard's image; a folder chosen there is where the main window's dialogs start next.
  answerFileDialog(answer);
  w.posePlots()->findChild<QPushButton*>(QStringLiteral("plotsExport"))->click();
  QVERIFY(answer.seen);
  QCOMPARE(answer.directory, dir);
  CalibrationWizard& wizard = showCalibrationWizard(w);
  const QString other = numberedFolder(QStringLiteral("dialogs-wizard"), 1);
  answerFileDialog(answer, other + QStringLiteral("/img1.png"));
  wizard.findChild<QPushButton*>(QStringLiteral("openImage1"))->click();
  QVERIFY(answer.seen);
  QCOMPARE(answer.directory, dir);
  QCOMPARE(w.dialogDirectory(), other);
  wizard.close();
  answerFileDialog(answer);
  w.findChild<QAction*>(QStringLiteral("dataOutAction"))->trigger();
  QVERIFY(answer.seen);
  QCOMPARE(answer.directory, other);
  rememberDialogFolder(dir);
  // And the next session too.
  window_.reset();
  MainWindow again;
  QCOMPARE(again.dialogDirectory(), dir);
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
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "sample03_tilted50.png"; }));
  w.startSource();
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
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "sample01_facing.png"; }));
  w.stepFile(FileStep::Last);
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "sample08_pattern.png"; }));
  QTRY_VERIFY(!w.worker()->isRunning());
  QVERIFY(w.lastError().isEmpty());
}

// The detection's numbers are drawn beside the target, not over its spots and rim, for
// the direct fit's E and for Bennett's wider S, Q, Y alike.
void FileTest::numbersSitBesideTheTarget() {
  MainWindow& w = *window_;
  w.resize(1200, 800);
  w.openPaths({kSamples + QStringLiteral("sample01_facing.png")});
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.name == "sample01_facing.png" && r.pose; }));
  for (EllipseMethod method : {EllipseMethod::DirectFit, EllipseMethod::Bennett}) {
    QVERIFY(choose(w.findChild<QComboBox*>(QStringLiteral("ellipseMethod")), method));
    QVERIFY(waitForApplied(w, [method](const Settings& s) { return s.pipeline.ellipse.method == method; }));
    QTRY_VERIFY(w.frameView()->packet()->ellipse_method == method && !w.frameView()->packet()->result.targets.empty());
    const FrameView& view = *w.frameView();
    const auto labels = view.numberLabels();
    const auto& targets = view.packet()->result.targets;
    QCOMPARE(labels.size(), targets.size());
    QVERIFY(labels[0].text.startsWith(method == EllipseMethod::Bennett ? QStringLiteral("S ") : QStringLiteral("E ")));
    const QRectF target = view.targetScreenBox(targets[0]);
    QVERIFY(target.width() > 20.0);  // the disk as shown, not a point
    QVERIFY2(!labels[0].box.intersects(target), qPrintable(labels[0].text));
    QVERIFY(QRectF(view.rect()).contains(labels[0].box));
    // Next to it: centred under it, a few pixels away.
    QVERIFY(std::abs(labels[0].box.center().x() - target.center().x()) < 1.0);
    QVERIFY(labels[0].box.top() - target.bottom() < 10.0);
  }
}

// A status in words longer than the results column is broken over lines, whole: the
// text beside the frame cuts nothing off.
void FileTest::longStatusIsWrappedNotCut() {
  MainWindow& w = *window_;
  const QString dir = scratchDir(QStringLiteral("truncated"));
  QFile whole(kSamples + QStringLiteral("sample01_facing.png"));
  QVERIFY(whole.open(QIODevice::ReadOnly));
  QFile cut(dir + QStringLiteral("/cut.png"));
  QVERIFY(cut.open(QIODevice::WriteOnly));
  cut.write(whole.read(whole.size() / 2));
  cut.close();
  w.openPaths({cut.fileName()});
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.status == Status::FileTruncated; }));
  QTRY_VERIFY(w.resultsText().startsWith(QStringLiteral("Status    FileTruncated:")));
  const QStringList lines = w.resultsText().split(QLatin1Char('\n'));
  for (const QString& line : lines) QVERIFY2(line.size() <= kResultsColumns, qPrintable(line));
  // Every word of the message is there, in order, the later lines under the first's value.
  QString joined;
  for (const QString& line : lines.mid(0, 4)) joined += line.trimmed() + QLatin1Char(' ');
  QVERIFY2(joined.simplified().contains(QString::fromUtf8(statusMessage(Status::FileTruncated).data())),
           qPrintable(joined));
  QVERIFY(lines[1].startsWith(QString(10, QLatin1Char(' '))));
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
