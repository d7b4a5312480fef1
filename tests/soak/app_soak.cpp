// Soak of the application: ImagePro on the Virtual source at 100 frames/s, writing
// data out, while every few seconds the next method list of the control panel (each
// combo box of the window whose name ends in "Method" or "Mode") moves to its next entry. Resident
// memory is sampled every second (DIR/rss.txt: minutes, resident KB, KB held by the pose
// plots' recording). At the end: the memory's slope after the warm-up (least squares),
// with and without the recording, and the worker's frame counter against the data-out rows.
// The recording keeps every frame's pose up to PosePlots::kMaxRecorded, so it grows by
// design until then; the bound applies to what is left, which a leak would make grow.
//
//   app_soak [--seconds N] [--switch-ms M] [--max-slope-kb-per-min K] [--out DIR]
//
// Exit 0 when the counter and the rows agree and memory besides the recording grows by
// at most K KB/min (default 64); 1 otherwise. Runs on the offscreen platform unless QT_QPA_PLATFORM
// says otherwise (Xvfb: QT_QPA_PLATFORM=xcb with DISPLAY set).
#include <QApplication>
#include <QComboBox>
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QStandardPaths>
#include <QTextStream>
#include <QThread>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "app/main_window/main_window.h"
#include "app/plots/pose_plots.h"
#include "app/worker/source_kind.h"
#include "app/worker/worker.h"
#include "core/pipeline/data_out.h"
#include "core/settings/settings.h"

using namespace imagepro;
using namespace imagepro::app;

namespace {

long residentKb() {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

// Least-squares slope of y against x.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
  const double d = n * sxx - sx * sx;
  return x.size() > 2 && d > 0 ? (n * sxy - sx * sy) / d : 0.0;
}

void pump(int ms) {
  QElapsedTimer t;
  t.start();
  while (t.elapsed() < ms) {
    QApplication::processEvents(QEventLoop::AllEvents, 20);
    QThread::msleep(2);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  double seconds = 60, max_slope = 64;
  int switch_ms = 3000;
  QString out = QStringLiteral(IMAGEPRO_TEST_TMP "/app_soak");
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--seconds") seconds = std::stod(argv[i + 1]);
    else if (a == "--switch-ms") switch_ms = std::stoi(argv[i + 1]);
    else if (a == "--max-slope-kb-per-min") max_slope = std::stod(argv[i + 1]);
    else if (a == "--out") out = QString::fromLocal8Bit(argv[i + 1]);
    else {
      std::fprintf(stderr, "usage: app_soak [--seconds N] [--switch-ms M] [--max-slope-kb-per-min K] [--out DIR]\n");
      return 2;
    }
  }
  QDir(out).removeRecursively();
  QDir().mkpath(out + QStringLiteral("/config"));
  qputenv("XDG_CONFIG_HOME", (out + QStringLiteral("/config")).toUtf8());  // not the user's layout
  QStandardPaths::setTestModeEnabled(true);
  QApplication app(argc, argv);
  QApplication::setOrganizationName(QStringLiteral("ImageProSoak"));
  QApplication::setApplicationName(QStringLiteral("ImageProSoak"));

  MainWindow w;
  Settings settings;
  settings.virtual_scene.frame_rate_hz = 100.0;
  w.setSettings(settings);
  w.resize(1200, 800);
  w.show();
  const QString data_out = out + QStringLiteral("/dataout.csv");
  w.startDataOut(data_out, ExistingFile::Fail, false);
  pump(200);
  if (w.dataOutPath() != data_out) {
    std::fprintf(stderr, "data out did not start: %s\n", qPrintable(w.lastError()));
    return 1;
  }
  std::vector<QComboBox*> lists;
  for (QComboBox* box : w.findChildren<QComboBox*>())
    if ((box->objectName().endsWith(QStringLiteral("Method")) || box->objectName().endsWith(QStringLiteral("Mode"))) &&
        box->count() > 1)
      lists.push_back(box);
  std::printf("switching %zu method lists every %d ms:", lists.size(), switch_ms);
  for (QComboBox* box : lists) std::printf(" %s", qPrintable(box->objectName()));
  std::printf("\n");

  w.selectSource(SourceKind::Virtual);
  w.startSource();
  QElapsedTimer clock;
  clock.start();
  std::vector<double> t_min, rss_kb, recording_kb;
  std::size_t next = 0;
  int switches = 0;
  qint64 last_switch = 0;
  while (clock.elapsed() < seconds * 1000) {
    pump(1000);
    t_min.push_back(clock.elapsed() / 60000.0);
    rss_kb.push_back(static_cast<double>(residentKb()));
    recording_kb.push_back(static_cast<double>(w.posePlots()->recorded().size() * sizeof(PoseSample)) / 1024.0);
    if (!lists.empty() && clock.elapsed() - last_switch >= switch_ms) {
      QComboBox* box = lists[next++ % lists.size()];
      if (box->isEnabled()) box->setCurrentIndex((box->currentIndex() + 1) % box->count());
      ++switches;
      last_switch = clock.elapsed();
    }
  }
  w.stopSource();
  for (int i = 0; i < 500 && w.worker()->isRunning(); ++i) pump(10);
  w.stopDataOut();
  for (int i = 0; i < 500 && !w.dataOutPath().isEmpty(); ++i) pump(10);
  const long long frames = w.worker()->framesProcessed();

  long long rows = -1;
  QFile f(data_out);
  if (f.open(QIODevice::ReadOnly)) {
    rows = 0;
    while (!f.atEnd()) rows += !f.readLine().isEmpty();
    --rows;  // the header
  }
  {
    std::ofstream samples((out + QStringLiteral("/rss.txt")).toStdString());  // for a plot
    for (std::size_t i = 0; i < t_min.size(); ++i)
      samples << t_min[i] << ' ' << rss_kb[i] << ' ' << recording_kb[i] << '\n';
  }
  // After the warm-up: the first 30 s or the first tenth, the longer.
  const double warm = std::max(0.5, t_min.empty() ? 0.0 : t_min.back() / 10);
  std::vector<double> x, y, rest;
  for (std::size_t i = 0; i < t_min.size(); ++i)
    if (t_min[i] >= warm) x.push_back(t_min[i]), y.push_back(rss_kb[i]), rest.push_back(rss_kb[i] - recording_kb[i]);
  const double s = slope(x, y), s_rest = slope(x, rest);
  std::printf("%.1f min, %d switches, frames counted %lld, data-out rows %lld\n", clock.elapsed() / 60000.0, switches,
              frames, rows);
  std::printf("resident memory %.0f KB after warm-up, %.0f KB at the end, slope %.1f KB/min\n", y.empty() ? 0 : y.front(),
              y.empty() ? 0 : y.back(), s);
  std::printf("pose recording %zu samples, %.0f KB; slope besides it %.1f KB/min\n", w.posePlots()->recorded().size(),
              recording_kb.empty() ? 0 : recording_kb.back(), s_rest);
  int failed = 0;
  if (frames <= 0 || frames != rows) {
    std::fprintf(stderr, "error: the frame counter and the data-out rows disagree\n");
    failed = 1;
  }
  if (s_rest > max_slope) {
    std::fprintf(stderr, "error: memory besides the pose recording grows by more than %.0f KB/min\n", max_slope);
    failed = 1;
  }
  return failed;
}
