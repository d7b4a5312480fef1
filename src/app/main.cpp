// imagepro: the desktop application (thesis appendix A).
//   imagepro [--source virtual|file|camera] [--config FILE] [FILE|FOLDER ...]
#include <QApplication>
#include <QCommandLineParser>
#include <QTimer>

#include <cstdio>

#include "app/main_window.h"
#include "app/source_kind.h"

int main(int argc, char** argv) {
  QApplication app(argc, argv);
  QApplication::setOrganizationName(QStringLiteral("ImagePro"));
  QApplication::setApplicationName(QStringLiteral("ImagePro"));
  QApplication::setApplicationVersion(QStringLiteral(IMAGEPRO_VERSION));

  QCommandLineParser parser;
  parser.setApplicationDescription(QStringLiteral("Real-time monocular 3D reconstruction of a secondary passive target."));
  parser.addHelpOption();
  parser.addVersionOption();
  QCommandLineOption source({QStringLiteral("s"), QStringLiteral("source")},
                            QStringLiteral("Input source to start with: virtual, file or camera."), QStringLiteral("kind"));
  QCommandLineOption config({QStringLiteral("c"), QStringLiteral("config")}, QStringLiteral("Settings JSON file to load."),
                            QStringLiteral("file"));
  parser.addOption(source);
  parser.addOption(config);
  parser.addPositionalArgument(QStringLiteral("files"), QStringLiteral("Images or folders to process (File source)."),
                               QStringLiteral("[file|folder...]"));
  parser.process(app);

  using imagepro::app::SourceKind;
  SourceKind kind = SourceKind::Virtual;
  if (parser.isSet(source) && !imagepro::app::parseSourceKind(parser.value(source), kind)) {
    std::fprintf(stderr, "imagepro: --source must be virtual, file or camera, not '%s'\n",
                 qPrintable(parser.value(source)));
    return 2;
  }
  const QStringList files = parser.positionalArguments();
  if (!files.isEmpty()) kind = SourceKind::File;

  imagepro::app::MainWindow window;
  window.show();
  // A bad settings file is shown in the window; the defaults stay in force.
  if (parser.isSet(config)) window.loadSettingsFile(parser.value(config));
  window.selectSource(kind);
  if (!files.isEmpty()) window.openPaths(files);
  else if (parser.isSet(source) && kind != SourceKind::File) window.startSource();
  return app.exec();
}
