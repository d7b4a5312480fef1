// Runs every application test class on the offscreen platform, with the window
// layout and recent files kept in a scratch folder instead of the user's settings.
#include <QApplication>
#include <QDir>
#include <QStandardPaths>
#include <QTest>

#include "app_test_classes.h"
#include "app_test_support.h"

int main(int argc, char** argv) {
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  const QString config = QStringLiteral(IMAGEPRO_TEST_TMP "/app/config");
  QDir(config).removeRecursively();
  QDir().mkpath(config);
  qputenv("XDG_CONFIG_HOME", config.toUtf8());
  QStandardPaths::setTestModeEnabled(true);
  imagepro::app::test::ProbeApplication app(argc, argv);
  QApplication::setOrganizationName(QStringLiteral("ImageProTest"));
  QApplication::setApplicationName(QStringLiteral("ImageProTest"));

  int failed = 0;
  imagepro::app::test::PanelTest panels;
  imagepro::app::test::WorkerTest worker;
  imagepro::app::test::VirtualTest virtual_source;
  imagepro::app::test::FileTest files;
  imagepro::app::test::SourceChangeTest source_change;
  imagepro::app::test::PlotsTest plots;
  imagepro::app::test::OutputTest outputs;
  imagepro::app::test::SettingsFileTest settings;
  imagepro::app::test::CalibrationWizardTest calibration;
  imagepro::app::test::AnalysisWindowTest analysis;
  imagepro::app::test::CameraSettingsTest camera_settings;
  imagepro::app::test::CalibrationCheckTest calibration_check;
  imagepro::app::test::D0DialogTest d0_dialog;
  imagepro::app::test::CommandLineTest command_line;
  for (QObject* t : std::initializer_list<QObject*>{&panels, &worker, &virtual_source, &files, &source_change,
                                                      &plots, &outputs, &settings, &calibration, &analysis, &camera_settings,
                                                      &calibration_check, &d0_dialog, &command_line})
    failed += QTest::qExec(t, argc, argv);
  return failed == 0 ? 0 : 1;
}
