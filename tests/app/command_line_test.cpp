// The imagepro program's command line (src/app/main.cpp): --help and --version print and
// quit with 0 without a display, where the window could not open.
#include <QProcess>
#include <QProcessEnvironment>
#include <QTest>

#include "app_test_classes.h"
#include "core/common/version.h"

namespace imagepro::app::test {

namespace {

struct Run {
  int exit_code = -1;
  QProcess::ExitStatus status = QProcess::CrashExit;
  QString out, err;
};

// imagepro with `args` and no display at all: no X, no Wayland, no platform chosen.
Run runWithoutDisplay(const QStringList& args) {
  QProcess process;
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM"}) env.remove(QLatin1String(name));
  process.setProcessEnvironment(env);
  process.start(QStringLiteral(IMAGEPRO_APP), args);
  Run run;
  if (!process.waitForFinished(30000)) {
    process.kill();
    process.waitForFinished();
    return run;
  }
  run.exit_code = process.exitCode();
  run.status = process.exitStatus();
  run.out = QString::fromUtf8(process.readAllStandardOutput());
  run.err = QString::fromUtf8(process.readAllStandardError());
  return run;
}

}  // namespace

void CommandLineTest::helpAndVersionNeedNoDisplay() {
  for (const QString& help : {QStringLiteral("--help"), QStringLiteral("-h")}) {
    const Run run = runWithoutDisplay({help});
    QCOMPARE(run.status, QProcess::NormalExit);
    QVERIFY2(run.exit_code == 0, qPrintable(run.err));
    QVERIFY2(run.out.contains(QStringLiteral("--config <file>")), qPrintable(run.out));
    QVERIFY(run.out.contains(QStringLiteral("--camera <device>")));
    QVERIFY(run.out.contains(QStringLiteral("Images or folders to process")));
  }
  for (const QString& version : {QStringLiteral("--version"), QStringLiteral("-v")}) {
    const Run run = runWithoutDisplay({version});
    QCOMPARE(run.status, QProcess::NormalExit);
    QVERIFY2(run.exit_code == 0, qPrintable(run.err));
    QCOMPARE(run.out.trimmed(), QStringLiteral("ImagePro %1").arg(QLatin1String(kVersion)));
  }
  // With other options before it, --help still answers alone.
  const Run run = runWithoutDisplay({QStringLiteral("--source"), QStringLiteral("virtual"), QStringLiteral("--help")});
  QCOMPARE(run.exit_code, 0);
  QVERIFY(run.out.contains(QStringLiteral("--source <kind>")));
}

}  // namespace imagepro::app::test
