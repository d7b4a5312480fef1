// The calibration wizard's full intrinsic mode (app/calibration_wizard/intrinsics_page.h):
// printed grids photographed by a camera of known intrinsics (the core tests' renderer) go
// in as files, the camera comes out within the core's measured accuracy, the report shows
// it, and it reaches the settings and OpenCV's camera file; bad input is named.
#include <QCheckBox>
#include <QFile>
#include <QImage>
#include <QLabel>
#include <QListWidget>
#include <QProgressBar>
#include <QRadioButton>
#include <QPushButton>
#include <QSignalSpy>
#include <QTabWidget>
#include <QTableWidget>
#include <QTest>
#include <QThreadPool>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>

#include "app/calibration_wizard/calibration_views.h"
#include "app/calibration_wizard/calibration_wizard.h"
#include "app/calibration_wizard/intrinsics_page.h"
#include "app/calibration_wizard/intrinsics_report_page.h"
#include "app/main_window/main_window.h"
#include "app_test_classes.h"
#include "app_test_support.h"
#include "core/calibration/intrinsic_scenes.h"  // tests/core: the rendered grids
#include "core/calibration/opencv_camera_file.h"

namespace imagepro::app::test {

namespace {

DotGridSpec asymmetricGrid() { return testing::gridSpec(DotGridKind::AsymmetricCircles, 4, 11, 15.0, 7.5); }

// The grid photographed from the core tests' ten views (face on to 60 deg) by the truth
// camera through the webcam lens, written as PNG files.
QStringList renderedGridFiles(const QString& dir) {
  testing::RenderedGrid rendered;
  std::string error;
  const CameraModel truth = testing::intrinsicTruthCamera(testing::kWebcamLens);
  if (!testing::renderGridViews(asymmetricGrid(), Paper::A4, truth, testing::intrinsicViews(420.0),
                                testing::PhotoConditions{}, rendered, error)) {
    qWarning("%s", error.c_str());
    return {};
  }
  QStringList paths;
  for (size_t i = 0; i < rendered.images.size(); ++i) {
    const QString path = dir + QStringLiteral("/view%1.png").arg(i + 1);
    if (!cv::imwrite(path.toStdString(), rendered.images[i])) return {};
    paths << path;
  }
  return paths;
}

IntrinsicsPage& intrinsicMode(MainWindow& w) {
  CalibrationWizard& wizard = showCalibrationWizard(w);
  wizard.setMode(CalibrationMode::Intrinsics);
  return *wizard.intrinsicsPage();
}

}  // namespace

void CalibrationWizardTest::intrinsicModeRecoversTheCamera() {
  MainWindow& w = *window_;
  CalibrationWizard& wizard = showCalibrationWizard(w);
  QCOMPARE(wizard.mode(), CalibrationMode::Distortion);  // the thesis's procedure stays the default
  wizard.findChild<QRadioButton*>(QStringLiteral("intrinsicsMode"))->click();
  QCOMPARE(wizard.mode(), CalibrationMode::Intrinsics);
  IntrinsicsPage& page = *wizard.intrinsicsPage();
  QVERIFY(page.isVisible());

  const QString dir = scratchDir(QStringLiteral("intrinsics"));
  const QStringList files = renderedGridFiles(dir);
  QCOMPARE(files.size(), 10);
  page.setSpec(asymmetricGrid());
  page.addImageFiles(files);
  QCOMPARE(page.imageCount(), 10);
  QVERIFY2(page.imageStatus(0).contains(QStringLiteral("not calibrated yet")), qPrintable(page.imageStatus(0)));

  // The printable sheet of this description, as imagepro-cli pattern writes it.
  QVERIFY(page.writePatternPdf(dir + QStringLiteral("/grid.pdf")));
  QFile pdf(dir + QStringLiteral("/grid.pdf"));
  QVERIFY(pdf.open(QIODevice::ReadOnly));
  QVERIFY(pdf.read(5) == "%PDF-");
  QVERIFY2(page.runStatus().contains(QStringLiteral("4 x 11 dots")), qPrintable(page.runStatus()));

  QSignalSpy finished(&page, &IntrinsicsPage::calibrationFinished);
  auto* progress = page.findChild<QProgressBar*>(QStringLiteral("intrinsicsProgress"));
  QList<int> progress_seen;
  connect(progress, &QProgressBar::valueChanged, &page, [&](int v) { progress_seen << v; });
  page.calibrate();
  QVERIFY(page.isCalibrating());  // off the GUI thread: calibrate() returned at once
  QCOMPARE(progress->maximum(), 11);  // ten grid searches, then the fit
  QVERIFY(finished.wait(120000));
  QCOMPARE(finished.first().at(0).toBool(), true);
  QVERIFY(progress_seen.contains(10));  // the searches were reported before the fit
  QCOMPARE(progress->value(), 11);
  const IntrinsicsResult* r = page.result();
  QVERIFY(r);
  QVERIFY2(r->status == Status::Ok, statusName(r->status).data());
  QCOMPARE(r->views_used, 10);

  // The truth: fx = fy = 800 px, principal point (324.3, 236.8). The core measures this
  // grid and lens within 0.02 % and 0.12 px (docs/calibration.md); the goals are
  // 0.1 % and 0.5 px.
  const CameraModel truth = testing::intrinsicTruthCamera(testing::kWebcamLens);
  qInfo("wizard's intrinsics: fx %+.4f %%, fy %+.4f %%, cx %+.3f px, cy %+.3f px, rms %.4f px",
        100 * (r->fx / truth.fu() - 1), 100 * (r->fy / truth.fv() - 1), r->cx - truth.u0(), r->cy - truth.v0(),
        r->rms_px);
  QVERIFY2(std::abs(r->fx / truth.fu() - 1.0) < 1e-3, qPrintable(QString::number(r->fx)));
  QVERIFY2(std::abs(r->fy / truth.fv() - 1.0) < 1e-3, qPrintable(QString::number(r->fy)));
  QVERIFY2(std::abs(r->cx - truth.u0()) < 0.5, qPrintable(QString::number(r->cx)));
  QVERIFY2(std::abs(r->cy - truth.v0()) < 0.5, qPrintable(QString::number(r->cy)));

  // Each image says what became of it, and its preview shows the dots found.
  for (int i = 0; i < page.imageCount(); ++i)
    QVERIFY2(page.imageStatus(i).contains(QStringLiteral("44 dots")), qPrintable(page.imageStatus(i)));
  page.findChild<QListWidget*>(QStringLiteral("intrinsicsImages"))->setCurrentRow(3);
  QCOMPARE(page.preview()->overlay().spots.size(), size_t{44});

  // The report, shown on its tab: per image and overall RMS, the parameters with their
  // deviations, the coverage picture, the warnings.
  IntrinsicsReportPage& report = *page.report();
  QCOMPARE(page.tabs()->currentWidget(), &report);
  QTableWidget* images = report.imageTable();
  QCOMPARE(images->rowCount(), 11);
  for (int i = 0; i < 10; ++i) {
    QCOMPARE(images->item(i, 0)->text(), QStringLiteral("view%1.png").arg(i + 1));
    QCOMPARE(images->item(i, 1)->text(), QStringLiteral("used"));
    QCOMPARE(images->item(i, 3)->text(), QString::number(r->views[static_cast<size_t>(i)].rms_px, 'f', 4));
  }
  QCOMPARE(images->item(10, 3)->text(), QString::number(r->rms_px, 'f', 4));
  QTableWidget* parameters = report.parameterTable();
  QCOMPARE(parameters->item(0, 0)->text(), QStringLiteral("fx, px"));
  QCOMPARE(parameters->item(0, 1)->text(), QString::number(r->fx, 'f', 3));
  QCOMPARE(parameters->item(0, 2)->text(), QString::number(r->deviation.fx, 'f', 3));
  QVERIFY(r->deviation.fx > 0.0);
  QCOMPARE(parameters->item(3, 2)->text(), QString::number(r->deviation.cy, 'f', 3));
  QVERIFY(report.summary().contains(QStringLiteral("Calibrated from 10 of 10 images")));
  // The coverage picture is the core's, at the image's size: cells with dots green, without red.
  const QImage coverage = report.coverageView()->image();
  QCOMPARE(coverage.size(), QSize(640, 480));
  cv::Mat bgr = coverageImage(*r, report.coverage()), rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  QCOMPARE(coverage, QImage(rgb.data, rgb.cols, rgb.rows, static_cast<qsizetype>(rgb.step), QImage::Format_RGB888));
  int covered = 0;
  for (const int views : report.coverage().views) covered += views > 0 ? 1 : 0;
  QVERIFY(covered > 0);
  QCOMPARE(static_cast<double>(covered) / (kCoverageColumns * kCoverageRows), report.coverage().covered_fraction);
  const QString caption = report.findChild<QLabel*>(QStringLiteral("intrinsicsCoverageCaption"))->text();
  QVERIFY2(caption.startsWith(QStringLiteral("Dots in %1 of the 8 x 6 cells").arg(covered)), qPrintable(caption));
  // Warnings as the CLI names them, one line each; none is an item saying so.
  const auto& warnings = report.warnings();
  QCOMPARE(warnings.size(), intrinsicsWarnings(*r, report.coverage()).size());
  for (size_t i = 0; i < warnings.size(); ++i)
    QVERIFY(report.warningList()->item(static_cast<int>(i))->text().startsWith(QString::fromStdString(warnings[i].name)));
  if (warnings.empty()) QVERIFY(report.warningList()->item(0)->text().startsWith(QStringLiteral("None")));

  if (const QString shot = qEnvironmentVariable("IMAGEPRO_WIZARD_REPORT_SCREENSHOT"); !shot.isEmpty())
    QVERIFY(wizard.grab().save(shot, "PNG", 0));

  // Set and Use: the camera section takes the result, correction goes on.
  auto* set_and_use = page.findChild<QPushButton*>(QStringLiteral("setAndUseIntrinsics"));
  QVERIFY(set_and_use->isEnabled());
  set_and_use->click();
  const CameraModel& used = w.settings().camera();
  QVERIFY(std::abs(used.fu() - r->fx) < 1e-6 * r->fx);
  QVERIFY(std::abs(used.fv() - r->fy) < 1e-6 * r->fy);
  QVERIFY(std::abs(used.u0() - r->cx) < 1e-9 && std::abs(used.v0() - r->cy) < 1e-9);
  QCOMPARE(used.distortion.k1, r->distortion.k1);
  QVERIFY(w.settings().pipeline.reconstruction.distortion_correction);

  // Save calibration: the camera section as a file.
  QVERIFY(page.saveCalibration(dir + QStringLiteral("/camera.json")));
  Settings loaded;
  std::string error;
  QVERIFY2(ok(loadSettings((dir + QStringLiteral("/camera.json")).toStdString(), loaded, error)), error.c_str());
  QCOMPARE(loaded.camera().principal_point_px[0], used.principal_point_px[0]);

  // OpenCV's camera file: written from the result, read back the same; imported into settings
  // that had another camera, it gives this one again.
  const QString yaml = dir + QStringLiteral("/camera.yaml");
  QVERIFY(page.exportOpenCvCamera(yaml));
  OpenCvCamera back;
  QVERIFY2(readOpenCvCamera(yaml.toStdString(), back, error), error.c_str());
  QCOMPARE(back.width, 640);
  QVERIFY(std::abs(back.camera_matrix(0, 0) - r->fx) < 1e-6);
  QVERIFY(std::abs(back.camera_matrix(1, 2) - r->cy) < 1e-6);
  QVERIFY(std::abs(back.distortion[0] - r->opencv_dist[0]) < 1e-9);
  Settings other = w.settings();
  other.camera() = CameraModel{};
  other.pipeline.reconstruction.distortion_correction = false;
  w.setSettings(other);
  QVERIFY(page.importOpenCvCamera(yaml));
  QVERIFY(std::abs(w.settings().camera().fu() - r->fx) < 1e-6 * r->fx);
  QVERIFY(std::abs(w.settings().camera().u0() - r->cx) < 1e-6);
  QVERIFY(w.settings().pipeline.reconstruction.distortion_correction);
  QVERIFY2(page.runStatus().startsWith(QStringLiteral("Imported camera.yaml")), qPrintable(page.runStatus()));

  // k3 on request: fitted, with its deviation in the report.
  page.findChild<QCheckBox*>(QStringLiteral("fitK3"))->setChecked(true);
  finished.clear();
  page.calibrate();
  QVERIFY(finished.wait(120000));
  QVERIFY(page.result() && page.result()->status == Status::Ok);
  QVERIFY(page.result()->deviation.k3 > 0.0);
  QCOMPARE(parameters->item(8, 0)->text(), QStringLiteral("k3 (OpenCV)"));
  QCOMPARE(parameters->item(8, 2)->text(), QString::number(page.result()->deviation.k3, 'f', 5));

  // Back to the thesis mode: its page is there as before.
  wizard.setMode(CalibrationMode::Distortion);
  QVERIFY(wizard.findChild<QPushButton*>(QStringLiteral("calibrate"))->isVisible());
  QVERIFY(!page.isVisible());
}

void CalibrationWizardTest::intrinsicModeNamesBadInput() {
  MainWindow& w = *window_;
  IntrinsicsPage& page = intrinsicMode(w);
  const QString dir = scratchDir(QStringLiteral("intrinsics-errors"));

  // A description that cannot be: named, nothing run or written.
  DotGridSpec bad = asymmetricGrid();
  bad.rows = 0;
  page.setSpec(bad);
  QVERIFY(!page.writePatternPdf(dir + QStringLiteral("/grid.pdf")));
  QVERIFY2(page.runStatus().contains(QStringLiteral("InvalidPattern")), qPrintable(page.runStatus()));
  QVERIFY(!QFile::exists(dir + QStringLiteral("/grid.pdf")));
  page.calibrate();
  QVERIFY(!page.isCalibrating());
  QVERIFY2(page.runStatus().startsWith(QStringLiteral("Not calibrated: InvalidPattern")), qPrintable(page.runStatus()));
  bad = asymmetricGrid();
  bad.dot_diameter_mm = 40.0;  // wider than the spacing
  page.setSpec(bad);
  page.calibrate();
  QVERIFY2(page.runStatus().startsWith(QStringLiteral("Not calibrated: InvalidPattern")), qPrintable(page.runStatus()));

  // Files that are not images, and too few images.
  page.setSpec(asymmetricGrid());
  QFile broken(dir + QStringLiteral("/broken.png"));
  QVERIFY(broken.open(QIODevice::WriteOnly));
  broken.write("this is not an image");
  broken.close();
  page.addImageFiles({broken.fileName(), dir + QStringLiteral("/missing.png")});
  QCOMPARE(page.imageCount(), 0);
  QVERIFY2(page.runStatus().contains(QStringLiteral("FileUnreadable")), qPrintable(page.runStatus()));
  QVERIFY(page.runStatus().contains(QStringLiteral("FileNotFound")));
  const cv::Mat blank(480, 640, CV_8UC1, cv::Scalar(200));
  page.addImage(blank, QStringLiteral("blank 1"));
  page.addImage(blank, QStringLiteral("blank 2"));
  page.calibrate();
  QVERIFY(!page.isCalibrating());
  QVERIFY2(page.runStatus().startsWith(QStringLiteral("Not calibrated: TooFewViews")), qPrintable(page.runStatus()));

  // Images without the grid: the run fails with TooFewViews, each image says GridNotFound.
  page.addImage(blank, QStringLiteral("blank 3"));
  // An image taken out while the run is on: the report still names the run's images.
  QSignalSpy finished(&page, &IntrinsicsPage::calibrationFinished);
  page.calibrate();
  page.removeImage(0);
  QVERIFY(finished.wait(60000));
  QCOMPARE(finished.first().at(0).toBool(), false);
  QVERIFY2(page.runStatus().startsWith(QStringLiteral("Calibration failed: TooFewViews")), qPrintable(page.runStatus()));
  QVERIFY(page.runStatus().contains(QStringLiteral("found in 0 of 3 images")));
  QCOMPARE(page.imageCount(), 2);
  for (int i = 0; i < 2; ++i)
    QVERIFY2(page.imageStatus(i).contains(QStringLiteral("left out: GridNotFound")), qPrintable(page.imageStatus(i)));
  QVERIFY(page.report()->summary().startsWith(QStringLiteral("Calibration failed: TooFewViews")));
  QVERIFY(page.report()->coverageView()->image().isNull());
  for (int i = 0; i < 3; ++i) {
    QCOMPARE(page.report()->imageTable()->item(i, 0)->text(), QStringLiteral("blank %1").arg(i + 1));
    QCOMPARE(page.report()->imageTable()->item(i, 1)->text(), QStringLiteral("GridNotFound"));
  }
  page.addImage(blank, QStringLiteral("blank 4"));
  QVERIFY(!page.findChild<QPushButton*>(QStringLiteral("setAndUseIntrinsics"))->isEnabled());
  const CameraModel before = w.settings().camera();
  page.setAndUse();
  QVERIFY(!page.saveCalibration(dir + QStringLiteral("/camera.json")));
  QCOMPARE(w.settings().camera().image_plane_distance_mm, before.image_plane_distance_mm);

  // A camera file that is missing or not OpenCV's.
  QVERIFY(!page.importOpenCvCamera(dir + QStringLiteral("/none.yaml")));
  QVERIFY2(page.runStatus().startsWith(QStringLiteral("Not imported")), qPrintable(page.runStatus()));
  QVERIFY(!page.importOpenCvCamera(broken.fileName()));
  QCOMPARE(w.settings().camera().image_plane_distance_mm, before.image_plane_distance_mm);

  // Capture with no source running, through the wizard's request to the worker.
  page.findChild<QPushButton*>(QStringLiteral("captureIntrinsicsImage"))->click();
  QTRY_VERIFY_WITH_TIMEOUT(page.runStatus().startsWith(QStringLiteral("Nothing to capture")), 5000);
  QCOMPARE(page.imageCount(), 3);

  // Cancel: the run is dropped, nothing arrives afterwards; closing while it runs is safe.
  page.calibrate();
  QVERIFY(page.isCalibrating());
  page.cancelCalibration();
  QVERIFY(!page.isCalibrating());
  QVERIFY(QThreadPool::globalInstance()->waitForDone(60000));
  QTest::qWait(50);
  QVERIFY(!page.result());
  QVERIFY(page.runStatus().startsWith(QStringLiteral("Cancelled")));
  page.calibrate();
  delete w.findChild<CalibrationWizard*>();
  QVERIFY(QThreadPool::globalInstance()->waitForDone(60000));
  QTest::qWait(50);
}

void CalibrationWizardTest::intrinsicModeCapturesTheRunningSource() {
  MainWindow& w = *window_;
  IntrinsicsPage& page = intrinsicMode(w);
  w.selectSource(SourceKind::Virtual);
  w.startSource();
  QVERIFY(waitForFrame(w, [](const FrameResult& r) { return r.status == Status::Ok; }));
  page.findChild<QPushButton*>(QStringLiteral("captureIntrinsicsImage"))->click();
  QTRY_VERIFY_WITH_TIMEOUT(page.imageCount() == 1, 5000);
  QVERIFY2(page.imageStatus(0).startsWith(QStringLiteral("Captured from")), qPrintable(page.imageStatus(0)));
  QVERIFY(!page.preview()->image().isNull());
  // The thesis mode's slots were not touched by it.
  QVERIFY(!w.findChild<CalibrationWizard*>()->hasImage(0));
  w.stopSource();
}

}  // namespace imagepro::app::test
