// The calibration wizard (thesis 4.6, appendix A): it runs on virtual pattern images and
// recovers the lens the settings rendered them with, lists every iteration as it ends, gives
// the result to the settings with Set and Use, and names every problem in words.
#include <QAction>
#include <QApplication>
#include <QElapsedTimer>
#include <QLabel>
#include <QMessageBox>
#include <QTimer>
#include <QFile>
#include <QImage>
#include <QLineEdit>
#include <QMenuBar>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTableWidget>
#include <QTest>
#include <QThreadPool>

#include <cmath>

#include "app/calibration_wizard/calibration_views.h"
#include "app/calibration_wizard/calibration_wizard.h"
#include "app/main_window/main_window.h"
#include "app/settings/settings_dialog.h"
#include "app/panels/source_panel.h"
#include "app_test_classes.h"
#include "app_test_support.h"
#include "core/calibration/distortion_fit.h"

namespace imagepro::app::test {

namespace {

double relativeError(double value, double truth) { return std::abs(value - truth) / std::abs(truth); }

// Renders the four virtual views into the wizard and waits for their analysis.
bool renderAll(CalibrationWizard& wizard) {
  for (int i = 0; i < kCalibrationSlots; ++i) wizard.renderVirtual(i);
  return QTest::qWaitFor([&] { return !wizard.isAnalysing(); }, 30000);
}

// The wizard with its four virtual views rendered through `lens`, the settings' camera
// then without distortion and correction: a calibration starts from none, and Set and
// Use has something to change. False when the views were not analysed in time.
bool renderThroughLens(MainWindow& w, CalibrationWizard& wizard, const Distortion& lens) {
  Settings through = w.settings();
  through.camera().distortion = lens;
  w.setSettings(through);
  if (!renderAll(wizard)) return false;
  Settings plain = w.settings();
  plain.camera().distortion = {};
  plain.pipeline.reconstruction.distortion_correction = false;
  w.setSettings(plain);
  return true;
}

QAction* menuAction(MainWindow& w, const QString& text) {
  for (QAction* a : w.menuBar()->findChildren<QAction*>())
    if (a->text() == text) return a;
  return nullptr;
}

}  // namespace

void CalibrationWizardTest::init() {
  window_ = std::make_unique<MainWindow>();
  window_->show();
}

void CalibrationWizardTest::cleanup() {
  window_.reset();
  QThreadPool::globalInstance()->waitForDone(30000);  // no run carries over into the next test
}

void CalibrationWizardTest::recoversTheLensFromVirtualPatternImages() {
  MainWindow& w = *window_;
  // The Virtual source renders through the settings' lens: the thesis camera's.
  Settings lens = w.settings();
  lens.camera().distortion = kThesisCameraDistortion;
  w.setSettings(lens);
  CalibrationWizard& wizard = showCalibrationWizard(w);
  QVERIFY(renderAll(wizard));
  for (int i = 0; i < kCalibrationSlots; ++i) {
    QVERIFY(wizard.hasImage(i));
    QVERIFY2(wizard.slotStatus(i).contains(QStringLiteral("Ready:")), qPrintable(wizard.slotStatus(i)));
    // Before the run: the target, the spots and the first iteration's matches are drawn.
    const CalibrationOverlay& o = wizard.imageView(i)->overlay();
    QVERIFY(o.target.has_value());
    QVERIFY(std::abs(o.target->cx - 319.5) < 3.0 && std::abs(o.target->cy - 239.5) < 3.0);  // on the optical axis
    QVERIFY(o.spots.size() > 500);
    QVERIFY(o.ideal.size() > 500);
    QCOMPARE(o.seen.size(), o.ideal.size());
  }

  // The calibration starts from zero whatever the settings hold; the settings then start
  // without distortion and correction, so that Set and Use has something to change.
  Settings plain = w.settings();
  plain.camera().distortion = {};
  plain.pipeline.reconstruction.distortion_correction = false;
  w.setSettings(plain);

  QSignalSpy finished(&wizard, &CalibrationWizard::calibrationFinished);
  int rows_before_result = 0;
  connect(wizard.iterationTable()->model(), &QAbstractItemModel::rowsInserted, &wizard,
          [&] { rows_before_result += wizard.result() == nullptr ? 1 : 0; });
  QElapsedTimer clock;
  clock.start();
  wizard.calibrate();
  QVERIFY(wizard.isCalibrating());  // off the GUI thread: calibrate() returned at once
  QVERIFY(finished.wait(60000));
  qInfo("calibration in the wizard: %lld ms", static_cast<long long>(clock.elapsed()));
  QCOMPARE(finished.first().at(0).toBool(), true);
  QVERIFY(!wizard.isCalibrating());
  const CalibrationResult* r = wizard.result();
  QVERIFY(r);
  QVERIFY2(r->status == Status::Ok, statusName(r->status).data());
  QVERIFY(r->converged);

  // One row per iteration, each delivered as its iteration ended (before the result).
  QTableWidget* table = wizard.iterationTable();
  QCOMPARE(table->rowCount(), r->iterations);
  QCOMPARE(rows_before_result, r->iterations);
  for (int row = 0; row < table->rowCount(); ++row) {
    const CalibrationIteration& it = r->history[static_cast<size_t>(row)];
    QCOMPARE(table->item(row, 0)->text().toInt(), it.iteration);
    QCOMPARE(table->item(row, 1)->text(), QString::number(it.distortion.k1, 'e', 4));
    QCOMPARE(table->item(row, 5)->text(), QString::number(it.relative_change, 'f', 4));
    QCOMPARE(table->item(row, 7)->text().toInt(), it.matches);
    QCOMPARE(table->item(row, 8)->text().toInt(), kCalibrationSlots);
  }
  QCOMPARE(table->item(0, 5)->text(), QStringLiteral("1.0000"));  // the first from zero
  QVERIFY(r->history.back().relative_change < w.settings().pipeline.calibration.relative_change);
  QVERIFY(wizard.runStatus().contains(QStringLiteral("Converged after %1 iterations").arg(r->iterations)));

  // docs/calibration.md measures this procedure on the same four views: with noise and blur
  // its parameters come within 0.05 % (k1), 0.34 % (k2), 0.25 % (p1) and 0.13 % (p2) of the
  // truth, its field within 0.0018 px RMS in every trial. These noise-free images are not
  // harder; the bounds below leave a margin of about five and more. k2 gets the widest: it
  // moves the image's corners by 1.2 px of their 16 px, so it is the least determined.
  const Distortion& d = r->distortion;
  const Distortion& t = kThesisCameraDistortion;
  QVERIFY2(relativeError(d.k1, t.k1) < 0.005, qPrintable(QString::number(d.k1)));
  QVERIFY2(relativeError(d.k2, t.k2) < 0.03, qPrintable(QString::number(d.k2)));
  QVERIFY2(relativeError(d.p1, t.p1) < 0.015, qPrintable(QString::number(d.p1)));
  QVERIFY2(relativeError(d.p2, t.p2) < 0.015, qPrintable(QString::number(d.p2)));
  const CameraModel& camera = w.settings().camera();
  QVERIFY(compareDistortionFields(camera, d, t).rms_px < 0.01);

  // The field view: the displacement found, its largest value stated (16.23 px at the
  // corners for the thesis lens, docs/calibration.md), arrows lengthened by a round factor.
  const double largest = compareDistortionFields(camera, d, Distortion{}).max_px;
  QCOMPARE(wizard.fieldView()->largestDisplacementPx(), largest);
  QVERIFY(std::abs(largest - 16.23) < 0.1);
  QVERIFY(wizard.fieldView()->arrowScale() >= 1.0);
  // Every image was used; its view now shows the run's last matches.
  for (int i = 0; i < kCalibrationSlots; ++i) {
    QVERIFY2(wizard.slotStatus(i).contains(QStringLiteral("Used:")), qPrintable(wizard.slotStatus(i)));
    QCOMPARE(wizard.imageView(i)->overlay().ideal.size(), r->images[static_cast<size_t>(i)].correspondences.size());
  }

  if (const QString shot = qEnvironmentVariable("IMAGEPRO_WIZARD_SCREENSHOT"); !shot.isEmpty()) {
    wizard.findChild<QSpinBox*>(QStringLiteral("matchLineScale"))->setValue(4);
    QVERIFY(wizard.grab().save(shot, "PNG", 0));  // 0: the smallest file
    wizard.findChild<QSpinBox*>(QStringLiteral("matchLineScale"))->setValue(1);
  }

  // Set and Use: the camera of the source in use takes the distortion (here File: the
  // pattern's images as opened files), the other sources keep theirs, and correction goes
  // on; the worker runs with it, and the Settings dialog shows it.
  w.selectSource(SourceKind::File);
  wizard.findChild<QPushButton*>(QStringLiteral("setAndUse"))->click();
  QCOMPARE(w.settings().source, SourceKind::File);
  QVERIFY2(wizard.runStatus().contains(QStringLiteral("the File source's camera")), qPrintable(wizard.runStatus()));
  QCOMPARE(w.settings().camera(SourceKind::Virtual).distortion.k1, 0.0);
  QCOMPARE(w.settings().camera(SourceKind::Camera).distortion.k1, 0.0);
  QCOMPARE(w.settings().camera().distortion.k1, d.k1);
  QCOMPARE(w.settings().camera().distortion.k2, d.k2);
  QCOMPARE(w.settings().camera().distortion.p1, d.p1);
  QCOMPARE(w.settings().camera().distortion.p2, d.p2);
  QVERIFY(w.settings().pipeline.reconstruction.distortion_correction);
  QVERIFY(waitForApplied(w, [&](const Settings& s) {
    return s.camera().distortion.k1 == d.k1 && s.pipeline.reconstruction.distortion_correction;
  }));
  QAction* settings_action = menuAction(w, QStringLiteral("Se&ttings..."));
  QVERIFY(settings_action);
  settings_action->trigger();
  auto* dialog = w.findChild<SettingsDialog*>();
  QVERIFY(dialog);
  auto* k1 = dialog->findChild<QLineEdit*>(QStringLiteral("distortionK1"));
  QVERIFY(k1);
  QVERIFY2(relativeError(k1->text().toDouble(), d.k1) < 1e-3, qPrintable(k1->text()));
  dialog->close();

  // Save Calibration: the camera section with the distortion found.
  const QString dir = scratchDir(QStringLiteral("calibration"));
  const QString file = dir + QStringLiteral("/camera.json");
  QVERIFY(wizard.saveCalibration(file));
  Settings loaded;
  std::string error;
  QVERIFY2(ok(loadSettings(file.toStdString(), loaded, error)), error.c_str());
  QCOMPARE(loaded.camera(SourceKind::File).distortion.k1, d.k1);  // the file binds it to File alone
  QCOMPARE(loaded.camera(SourceKind::File).distortion.p2, d.p2);
  QCOMPARE(loaded.camera(SourceKind::Camera).distortion.k1, 0.0);
  QVERIFY(!wizard.saveCalibration(dir + QStringLiteral("/no/such/folder/camera.json")));
  QVERIFY(wizard.runStatus().contains(QStringLiteral("camera.json")));
  QVERIFY(QFile::exists(file));
}

// A lens without distortion calibrates to a field of a few thousandths of a pixel at
// most: it is said to be none worth speaking of, not magnified into a lens's field.
void CalibrationWizardTest::aDistortionFreeLensIsNotDrawnAsOne() {
  MainWindow& w = *window_;
  CalibrationWizard& wizard = showCalibrationWizard(w);
  QVERIFY(renderAll(wizard));  // through the default camera: no distortion
  QSignalSpy finished(&wizard, &CalibrationWizard::calibrationFinished);
  wizard.calibrate();
  QVERIFY(finished.wait(60000));
  const CalibrationResult* r = wizard.result();
  QVERIFY(r && ok(r->status));
  const double largest = wizard.fieldView()->largestDisplacementPx();
  QVERIFY2(largest < DistortionFieldView::kNegligiblePx, qPrintable(QString::number(largest)));
  QCOMPARE(wizard.fieldView()->arrowScale(), 0.0);
  const QString caption = wizard.findChild<QLabel*>(QStringLiteral("distortionFieldCaption"))->text();
  QVERIFY2(caption.contains(QStringLiteral("no distortion to speak of")), qPrintable(caption));
  QVERIFY(!caption.contains(QStringLiteral("times their length")));
  // A real lens is still drawn, magnified.
  Settings lens = w.settings();
  lens.camera().distortion = kThesisCameraDistortion;
  w.setSettings(lens);
  wizard.fieldView()->setField(lens.camera(), kThesisCameraDistortion);
  QVERIFY(wizard.fieldView()->arrowScale() >= 1.0);
}

// Quitting with a calibration set and in use, and not saved, asks first: Cancel keeps the
// window, Save writes the settings (and then quits), Discard quits. Saved, or replaced
// since, it asks nothing.
void CalibrationWizardTest::quittingAsksBeforeLosingTheCalibration() {
  MainWindow& w = *window_;
  CalibrationWizard& wizard = showCalibrationWizard(w);
  QVERIFY(renderThroughLens(w, wizard, kThesisCameraDistortion));
  QSignalSpy finished(&wizard, &CalibrationWizard::calibrationFinished);
  wizard.calibrate();
  QVERIFY(finished.wait(60000));
  QVERIFY(!w.hasUnsavedCalibration());
  wizard.findChild<QPushButton*>(QStringLiteral("setAndUse"))->click();
  QVERIFY(w.hasUnsavedCalibration());
  wizard.close();

  // Answers the question with `button`; notes that it was asked.
  // `waiting` counts the answers still looking for their question (one that is never asked
  // gives up after 3 s): a later question must not be answered by an earlier answer.
  int waiting = 0;
  const auto answer = [&waiting](QMessageBox::StandardButton button, bool& asked) {
    asked = false;
    ++waiting;
    QTimer::singleShot(0, qApp, [button, &asked, &waiting] {
      QMessageBox* box = nullptr;
      for (int i = 0; i < 300 && !box; ++i) {
        box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        if (!box) QTest::qWait(10);
      }
      --waiting;
      if (!box) return;
      asked = box->objectName() == QStringLiteral("unsavedCalibration") &&
              box->text().contains(QStringLiteral("has not been saved"));
      box->button(button)->click();
    });
  };
  bool asked = false;
  answer(QMessageBox::Cancel, asked);
  QVERIFY(!w.close());
  QVERIFY(asked);
  QVERIFY(w.isVisible());
  // Save: the settings dialog; the file written, the window goes.
  const QString file = scratchDir(QStringLiteral("unsaved-calibration")) + QStringLiteral("/settings.json");
  FileDialogAnswer saved;
  answer(QMessageBox::Save, asked);
  QTimer::singleShot(0, qApp, [&saved, file] { answerFileDialog(saved, file); });
  QVERIFY(w.close());
  QVERIFY(asked && saved.seen);
  Settings written;
  std::string error;
  QVERIFY2(ok(loadSettings(file.toStdString(), written, error)), error.c_str());
  QCOMPARE(written.camera(w.settings().source).distortion.k1, wizard.result()->distortion.k1);
  QVERIFY(!w.hasUnsavedCalibration());

  // Set again: Restore Defaults and Load Settings would replace it, and ask first.
  w.show();
  wizard.findChild<QPushButton*>(QStringLiteral("setAndUse"))->click();
  QVERIFY(w.hasUnsavedCalibration());
  const double calibrated_k1 = w.settings().camera().distortion.k1;
  answer(QMessageBox::Cancel, asked);
  w.restoreDefaults();
  QVERIFY(asked);
  QVERIFY(w.hasUnsavedCalibration());
  QCOMPARE(w.settings().camera().distortion.k1, calibrated_k1);
  const QString defaults_file = scratchDir(QStringLiteral("unsaved-calibration")) + QStringLiteral("/defaults.json");
  QVERIFY2(ok(saveSettings(defaults_file.toStdString(), Settings{}, error)), error.c_str());
  answer(QMessageBox::Cancel, asked);
  QVERIFY(!w.loadSettingsFile(defaults_file));
  QVERIFY(asked);
  QCOMPARE(w.settings().camera().distortion.k1, calibrated_k1);
  // Settings with the same camera replace nothing: nothing asked.
  const QString same_file = scratchDir(QStringLiteral("unsaved-calibration")) + QStringLiteral("/same-camera.json");
  Settings same = w.settings();
  same.stream.port += 1;
  QVERIFY2(ok(saveSettings(same_file.toStdString(), same, error)), error.c_str());
  answer(QMessageBox::Cancel, asked);
  QVERIFY(w.loadSettingsFile(same_file));
  QTRY_COMPARE_WITH_TIMEOUT(waiting, 0, 5000);
  QVERIFY(!asked);
  QVERIFY(w.hasUnsavedCalibration());
  // Discard: the defaults replace it, nothing is left to lose.
  answer(QMessageBox::Discard, asked);
  w.restoreDefaults();
  QVERIFY(asked);
  QVERIFY(!w.hasUnsavedCalibration());
  QCOMPARE(w.settings().camera().distortion.k1, Settings{}.camera().distortion.k1);
  // Set again and discarded.
  wizard.findChild<QPushButton*>(QStringLiteral("setAndUse"))->click();
  answer(QMessageBox::Discard, asked);
  QVERIFY(w.close());
  QVERIFY(asked);
  // Saved as the wizard's calibration file: kept, nothing asked.
  w.show();
  wizard.findChild<QPushButton*>(QStringLiteral("setAndUse"))->click();
  QVERIFY(wizard.saveCalibration(scratchDir(QStringLiteral("unsaved-calibration-2")) + QStringLiteral("/camera.json")));
  QVERIFY(!w.hasUnsavedCalibration());
  QVERIFY(w.close());
}

void CalibrationWizardTest::problemsAreNamedPerImageAndForTheRun() {
  MainWindow& w = *window_;
  CalibrationWizard& wizard = showCalibrationWizard(w);
  const QString dir = scratchDir(QStringLiteral("calibration-errors"));
  QFile broken(dir + QStringLiteral("/broken.png"));
  QVERIFY(broken.open(QIODevice::WriteOnly));
  broken.write("this is not an image");
  broken.close();

  wizard.openImage(0, broken.fileName());
  QVERIFY(!wizard.hasImage(0));
  QVERIFY2(wizard.slotStatus(0).contains(QStringLiteral("FileUnreadable")), qPrintable(wizard.slotStatus(0)));
  QVERIFY(wizard.slotStatus(0).contains(QStringLiteral("broken.png")));
  wizard.openImage(1, dir + QStringLiteral("/missing.png"));
  QVERIFY2(wizard.slotStatus(1).contains(QStringLiteral("FileNotFound")), qPrintable(wizard.slotStatus(1)));
  QVERIFY(!wizard.findChild<QPushButton*>(QStringLiteral("calibrate"))->isEnabled());  // nothing to calibrate from

  // Not the size of the settings' camera.
  QImage small(320, 240, QImage::Format_Grayscale8);
  small.fill(200);
  QVERIFY(small.save(dir + QStringLiteral("/small.png")));
  wizard.openImage(1, dir + QStringLiteral("/small.png"));
  QTRY_VERIFY_WITH_TIMEOUT(!wizard.isAnalysing(), 20000);
  QVERIFY2(wizard.slotStatus(1).contains(QStringLiteral("FrameSizeMismatch")), qPrintable(wizard.slotStatus(1)));
  QVERIFY(wizard.slotStatus(1).contains(QStringLiteral("320 x 240 px, the settings' camera 640 x 480")));
  wizard.clearImage(1);
  QVERIFY(!wizard.hasImage(1));

  // The target alone, without the pattern around it: found, but no spots to match.
  wizard.openImage(2, QStringLiteral(IMAGEPRO_DATA_DIR "/samples/sample01_facing.png"));
  QTRY_VERIFY_WITH_TIMEOUT(!wizard.isAnalysing(), 20000);
  QVERIFY(wizard.hasImage(2));
  QVERIFY2(wizard.slotStatus(2).contains(QStringLiteral("TooFewMatches")), qPrintable(wizard.slotStatus(2)));
  QVERIFY(wizard.imageView(2)->overlay().target.has_value());
  // No target at all.
  wizard.openImage(3, QStringLiteral(IMAGEPRO_DATA_DIR "/samples/sample06_no_target.png"));
  QTRY_VERIFY_WITH_TIMEOUT(!wizard.isAnalysing(), 20000);
  QVERIFY2(wizard.slotStatus(3).contains(QStringLiteral("Not usable")), qPrintable(wizard.slotStatus(3)));
  QVERIFY(!wizard.imageView(3)->overlay().target.has_value());

  // The run fails with the first image's error, in words, and nothing can be set.
  QSignalSpy finished(&wizard, &CalibrationWizard::calibrationFinished);
  wizard.calibrate();
  QVERIFY(finished.wait(30000));
  QCOMPARE(finished.first().at(0).toBool(), false);
  QVERIFY2(wizard.runStatus().contains(QStringLiteral("Calibration failed: TooFewMatches")),
           qPrintable(wizard.runStatus()));
  QVERIFY(!wizard.findChild<QPushButton*>(QStringLiteral("setAndUse"))->isEnabled());
  const Distortion before = w.settings().camera().distortion;
  wizard.setAndUse();
  QCOMPARE(w.settings().camera().distortion.k1, before.k1);
  QVERIFY(wizard.slotStatus(2).contains(QStringLiteral("Left out of the calibration: TooFewMatches")));
}

// An A4 page's grid (11 x 7 spots) seen from the wizard's 800 mm covers only the middle
// of the image: the run is refused with PoorCoverage and what to do, never an estimate
// that is wrong in the corners, and Set and Use stays off.
void CalibrationWizardTest::aPatternTooSmallForTheImageIsRefused() {
  MainWindow& w = *window_;
  Settings small_sheet = w.settings();
  small_sheet.camera().distortion = kThesisCameraDistortion;
  small_sheet.pattern.columns = 11;
  small_sheet.pattern.rows = 7;
  w.setSettings(small_sheet);
  CalibrationWizard& wizard = showCalibrationWizard(w);
  QVERIFY(renderAll(wizard));
  QSignalSpy finished(&wizard, &CalibrationWizard::calibrationFinished);
  wizard.calibrate();
  QVERIFY(finished.wait(60000));
  QCOMPARE(finished.first().at(0).toBool(), false);
  const CalibrationResult* r = wizard.result();
  QVERIFY(r);
  QVERIFY2(r->status == Status::PoorCoverage, statusName(r->status).data());
  QVERIFY(r->coverage_radius_fraction > 0.0 && r->coverage_radius_fraction < 0.6);
  QVERIFY2(wizard.runStatus().contains(QStringLiteral("Calibration failed: PoorCoverage")),
           qPrintable(wizard.runStatus()));
  QVERIFY(wizard.runStatus().contains(QStringLiteral("move the pattern closer or print it larger")));
  QVERIFY(wizard.runStatus().contains(QString::number(r->coverage_radius_fraction, 'f', 2)));
  QVERIFY(!wizard.findChild<QPushButton*>(QStringLiteral("setAndUse"))->isEnabled());
}

void CalibrationWizardTest::captureTakesTheRunningSourcesFrame() {
  MainWindow& w = *window_;
  CalibrationWizard& wizard = showCalibrationWizard(w);
  QSignalSpy ready(&wizard, &CalibrationWizard::imageReady);
  wizard.captureFrame(1);
  QVERIFY(ready.wait(5000));
  QVERIFY(!wizard.hasImage(1));
  QVERIFY2(wizard.slotStatus(1).contains(QStringLiteral("Nothing to capture")), qPrintable(wizard.slotStatus(1)));

  w.selectSource(SourceKind::Virtual);
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.status == Status::Ok; }));
  ready.clear();
  wizard.captureFrame(1);
  QTRY_VERIFY_WITH_TIMEOUT(wizard.hasImage(1) && !wizard.isAnalysing(), 20000);
  QVERIFY2(wizard.slotStatus(1).startsWith(QStringLiteral("Captured from")), qPrintable(wizard.slotStatus(1)));
  // The virtual target alone: it is found, the pattern's spots are not there.
  QVERIFY(wizard.imageView(1)->overlay().target.has_value());
  QVERIFY(wizard.slotStatus(1).contains(QStringLiteral("TooFewMatches")));
  w.stopSource();
}

void CalibrationWizardTest::panelAndMenuOpenTheWizard() {
  MainWindow& w = *window_;
  QVERIFY(!w.findChild<CalibrationWizard*>());
  auto* button = w.findChild<QPushButton*>(QStringLiteral("calibrationWizardButton"));
  QVERIFY(button);
  QVERIFY(button->toolTip().contains(QStringLiteral("thesis 4.6")));
  button->click();
  auto* wizard = w.findChild<CalibrationWizard*>();
  QVERIFY(wizard);
  QTRY_VERIFY(wizard->isVisible());
  wizard->close();
  QAction* action = menuAction(w, QStringLiteral("&Calibration Wizard..."));
  QVERIFY(action);
  QVERIFY(action->toolTip().contains(QStringLiteral("thesis 4.6")));
  action->trigger();
  QTRY_VERIFY(wizard->isVisible());
  QCOMPARE(w.findChildren<CalibrationWizard*>().size(), 1);  // the same window, images kept
  // The calibration buttons name the method and its section.
  for (const char* name : {"calibrate", "setAndUse", "saveCalibration", "cancelCalibration"})
    QVERIFY2(wizard->findChild<QPushButton*>(QLatin1String(name))->toolTip().contains(QStringLiteral("thesis 4.6")),
             name);
}

void CalibrationWizardTest::closingOrCancellingWhileRunningIsSafe() {
  MainWindow& w = *window_;
  CalibrationWizard* wizard = &showCalibrationWizard(w);
  QVERIFY(renderAll(*wizard));
  // Cancel: the run is dropped, nothing arrives afterwards.
  wizard->calibrate();
  QVERIFY(wizard->isCalibrating());
  wizard->cancelCalibration();
  QVERIFY(!wizard->isCalibrating());
  QVERIFY(QThreadPool::globalInstance()->waitForDone(60000));
  QTest::qWait(50);
  QCOMPARE(wizard->iterationTable()->rowCount(), 0);
  QVERIFY(!wizard->result());
  QVERIFY(wizard->runStatus().startsWith(QStringLiteral("Cancelled")));
  // The window goes while the run is on: the run ends in the background, nothing breaks.
  wizard->calibrate();
  QVERIFY(wizard->isCalibrating());
  delete wizard;
  QVERIFY(QThreadPool::globalInstance()->waitForDone(60000));
  QTest::qWait(50);
  // And a new one works as before.
  CalibrationWizard& again = showCalibrationWizard(w);
  QVERIFY(!again.hasImage(0));
  for (int i = 0; i < kCalibrationSlots; ++i) again.renderVirtual(i);
  again.clearImage(3);  // while it is being rendered: the render's result is dropped
  QVERIFY(QTest::qWaitFor([&] { return !again.isAnalysing(); }, 30000));
  QVERIFY(QThreadPool::globalInstance()->waitForDone(60000));
  QTest::qWait(50);
  QVERIFY(!again.hasImage(3));
  QVERIFY(again.hasImage(0) && again.hasImage(1) && again.hasImage(2));
}

}  // namespace imagepro::app::test
