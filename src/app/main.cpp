// imagepro: the desktop application (thesis appendix A).
//   imagepro [--source virtual|file|camera] [--config FILE] [FILE|FOLDER ...]
//            [--camera /dev/videoN [--size WxH] [--fps F]]  (start the Camera source on that device)
//            [--screenshot PNG [--after SECONDS]]   (for the documentation: save the window, quit)
//            [--measure-responsiveness SECONDS]     (GUI stalls with the Virtual source unpaced: print, quit)
#include <QApplication>
#include <QCommandLineParser>
#include <QCoreApplication>
#include <QTimer>

#include <cstdio>
#include <cstring>

#include "app/worker/camera_arguments.h"
#include "app/main_window/main_window.h"
#include "app/main_window/responsiveness_probe.h"
#include "app/plots/pose_plots.h"
#include "app/worker/source_kind.h"
#include "core/common/version.h"

namespace {

void nameApplication() {
  QCoreApplication::setOrganizationName(QStringLiteral("ImagePro"));
  QCoreApplication::setApplicationName(QStringLiteral("ImagePro"));
  QCoreApplication::setApplicationVersion(QString::fromLatin1(imagepro::kVersion));
}

// --help and --version print and quit; they need no display, which QApplication would
// insist on (without one it aborts).
bool asksForHelpOrVersion(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--") == 0) break;
    for (const char* option : {"-h", "--help", "-?", "--help-all", "-v", "--version"})
      if (std::strcmp(argv[i], option) == 0) return true;
  }
  return false;
}

// Every option of the command line, for the help text and the run alike.
struct Options {
  QCommandLineOption source = QCommandLineOption(
      {QStringLiteral("s"), QStringLiteral("source")}, QStringLiteral("Input source to start with: virtual, file or camera."),
      QStringLiteral("kind"));
  QCommandLineOption config = QCommandLineOption({QStringLiteral("c"), QStringLiteral("config")},
                                                 QStringLiteral("Settings JSON file to load."), QStringLiteral("file"));
  QCommandLineOption screenshot = QCommandLineOption(
      QStringLiteral("screenshot"), QStringLiteral("Save a picture of the whole window to this PNG file, then quit."),
      QStringLiteral("png"));
  QCommandLineOption after =
      QCommandLineOption(QStringLiteral("after"), QStringLiteral("Seconds to run before --screenshot (default 5)."),
                         QStringLiteral("seconds"), QStringLiteral("5"));
  QCommandLineOption measure = QCommandLineOption(
      QStringLiteral("measure-responsiveness"),
      QStringLiteral("Run the Virtual source unpaced for this many seconds while timing the GUI thread; print the "
                     "stalls and the frames processed and shown, then quit."),
      QStringLiteral("seconds"));
  QCommandLineOption camera = QCommandLineOption(
      QStringLiteral("camera"), QStringLiteral("Start the Camera source on this V4L2 device (e.g. /dev/video0)."),
      QStringLiteral("device"));
  QCommandLineOption size = QCommandLineOption(
      QStringLiteral("size"), QStringLiteral("With --camera: the frame size to ask for, e.g. 640x480."),
      QStringLiteral("WxH"));
  QCommandLineOption fps = QCommandLineOption(
      QStringLiteral("fps"), QStringLiteral("With --camera: the frame rate to ask for."), QStringLiteral("rate"));

  void addTo(QCommandLineParser& parser) const {
    parser.setApplicationDescription(
        QStringLiteral("Real-time monocular 3D reconstruction of a secondary passive target."));
    parser.addHelpOption();
    parser.addVersionOption();
    parser.addOption(source);
    parser.addOption(camera);
    parser.addOption(size);
    parser.addOption(fps);
    parser.addOption(measure);
    parser.addOption(config);
    parser.addOption(screenshot);
    parser.addOption(after);
    parser.addPositionalArgument(QStringLiteral("files"), QStringLiteral("Images or folders to process (File source)."),
                                 QStringLiteral("[file|folder...]"));
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (asksForHelpOrVersion(argc, argv)) {
    QCoreApplication app(argc, argv);
    nameApplication();
    QCommandLineParser parser;
    Options().addTo(parser);
    parser.process(app);  // prints the help or the version and exits with 0
    return 0;
  }
  QApplication app(argc, argv);
  nameApplication();
  const Options options;
  const auto& [source, config, screenshot, after, measure, camera, size, fps] = options;
  QCommandLineParser parser;
  options.addTo(parser);
  parser.process(app);

  using imagepro::SourceKind;
  SourceKind kind = SourceKind::Virtual;
  if (parser.isSet(source) && !imagepro::app::parseSourceKind(parser.value(source), kind)) {
    std::fprintf(stderr, "imagepro: --source must be virtual, file or camera, not '%s'\n",
                 qPrintable(parser.value(source)));
    return 2;
  }
  const QStringList files = parser.positionalArguments();
  if (!files.isEmpty()) kind = SourceKind::File;
  if (parser.isSet(camera)) {
    if (!files.isEmpty() || (parser.isSet(source) && kind != SourceKind::Camera)) {
      std::fprintf(stderr, "imagepro: --camera starts the Camera source: no files or other --source with it\n");
      return 2;
    }
    kind = SourceKind::Camera;
    imagepro::CameraSourceOptions check;
    QString error;
    if (!imagepro::app::applyCameraArguments(parser.value(camera), parser.value(size), parser.value(fps), check, error)) {
      std::fprintf(stderr, "imagepro: %s\n", qPrintable(error));
      return 2;
    }
  } else if (parser.isSet(size) || parser.isSet(fps)) {
    std::fprintf(stderr, "imagepro: --size and --fps go with --camera\n");
    return 2;
  }

  imagepro::app::MainWindow window;
  window.show();
  // The source first: a change of source dismisses the error banner, which must keep a
  // bad settings file's error.
  window.selectSource(kind);
  // A bad settings file is shown in the window; the defaults stay in force.
  if (parser.isSet(config)) window.loadSettingsFile(parser.value(config));
  if (parser.isSet(camera)) {  // over the settings file's camera_source (checked above)
    imagepro::Settings settings = window.settings();
    QString unused;
    imagepro::app::applyCameraArguments(parser.value(camera), parser.value(size), parser.value(fps),
                                        settings.camera_source, unused);
    window.setSettings(settings);
  }
  if (parser.isSet(measure)) {
    bool seconds_ok = false;
    const double seconds = parser.value(measure).toDouble(&seconds_ok);
    if (!seconds_ok || !(seconds > 0.0)) {
      std::fprintf(stderr, "imagepro: --measure-responsiveness needs a number of seconds, not '%s'\n",
                   qPrintable(parser.value(measure)));
      return 2;
    }
    auto* measurement = new imagepro::app::ResponsivenessMeasurement(window, seconds, 2, &window);
    QObject::connect(measurement, &imagepro::app::ResponsivenessMeasurement::finished, &window, [&] {
      std::fputs(qPrintable(imagepro::app::formatReport(measurement->report())), stdout);
      std::fflush(stdout);
      window.close();
      app.exit(0);
    });
    measurement->start();
    return app.exec();
  }
  if (!files.isEmpty()) window.openPaths(files);
  else if ((parser.isSet(source) || parser.isSet(camera)) && kind != SourceKind::File) window.startSource();
  if (parser.isSet(screenshot)) {
    bool seconds_ok = false;
    const double seconds = parser.value(after).toDouble(&seconds_ok);
    if (!seconds_ok || seconds < 0.0) {
      std::fprintf(stderr, "imagepro: --after needs a number of seconds, not '%s'\n", qPrintable(parser.value(after)));
      return 2;
    }
    QTimer::singleShot(static_cast<int>(seconds * 1000.0), &window, [&window, &app, path = parser.value(screenshot)] {
      window.posePlots()->redraw();
      if (!window.grab().save(path, "PNG")) {
        std::fprintf(stderr, "imagepro: cannot write %s\n", qPrintable(path));
        app.exit(1);
        return;
      }
      window.close();
      app.exit(0);
    });
  }
  return app.exec();
}
