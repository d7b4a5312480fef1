#include "app/main_window/main_window.h"

#include <QApplication>
#include <QCloseEvent>
#include <QDir>
#include <QDockWidget>
#include <QFileInfo>
#include <QFontDatabase>
#include <QFontMetrics>
#include <QIcon>
#include <QImageReader>
#include <QLabel>
#include <QScrollArea>
#include <QSettings>
#include <QSplitter>
#include <QStatusBar>
#include <QTabWidget>
#include <QTimer>
#include <QVBoxLayout>

#include "app/panels/calibration_panel.h"
#include "app/calibration_wizard/calibration_wizard.h"
#include "app/calibration_wizard/d0_dialog.h"
#include "app/panels/control_panel.h"
#include "app/main_window/frame_view.h"
#include "app/plots/histogram_chart.h"
#include "app/main_window/message_banner.h"
#include "app/panels/output_panel.h"
#include "app/plots/pose_plots.h"
#include "app/main_window/recent_files.h"
#include "app/main_window/results_text.h"
#include "app/settings/settings_binder.h"
#include "app/panels/source_panel.h"
#include "app/plots/stage_time_chart.h"
#include "app/worker/worker.h"
#include "app/main_window/dialog_folder.h"

// The resources live in the imagepro_app static library: make sure they are linked in.
static void initImageProResources() { Q_INIT_RESOURCE(imagepro); }

namespace imagepro::app {

namespace {


QIcon applicationIcon() {
  // The SVG is the drawing; the PNG rendering of it serves where Qt has no SVG plugin.
  if (QImageReader::supportedImageFormats().contains("svg")) return QIcon(QStringLiteral(":/icons/imagepro.svg"));
  return QIcon(QStringLiteral(":/icons/imagepro.png"));
}

}  // namespace

MainWindow::MainWindow(QWidget* parent)
    : QMainWindow(parent), binder_(new SettingsBinder(settings_, this)), worker_(new Worker(settings_)) {
  initImageProResources();
  setObjectName(QStringLiteral("mainWindow"));
  setWindowTitle(tr("ImagePro"));
  setWindowIcon(applicationIcon());
  setAcceptDrops(true);
  setDockOptions(QMainWindow::AnimatedDocks | QMainWindow::AllowTabbedDocks);

  buildResultsArea();
  buildDocks();
  buildStatusBar();
  buildMenus();
  connectWorker();

  readout_timer_ = new QTimer(this);
  connect(readout_timer_, &QTimer::timeout, this, &MainWindow::refreshReadouts);
  readout_timer_->start(kReadoutMs);

  connect(binder_, &SettingsBinder::changed, this, &MainWindow::onSettingsEdited);
  qApp->installEventFilter(this);
  worker_->selectSource(control_panel_->sourcePanel()->kind());
  worker_->moveToThread(&thread_);
  connect(&thread_, &QThread::finished, worker_, &QObject::deleteLater);
  thread_.setObjectName(QStringLiteral("imagepro-worker"));
  thread_.start();
  restoreLayout();
}

MainWindow::~MainWindow() {
  qApp->removeEventFilter(this);
  worker_->stop();
  thread_.quit();
  thread_.wait();
}

void MainWindow::buildResultsArea() {
  view_ = new FrameView;
  view_->setObjectName(QStringLiteral("frameView"));
  results_text_ = new QLabel;
  results_text_->setObjectName(QStringLiteral("resultsText"));
  results_text_->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
  results_text_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  results_text_->setAlignment(Qt::AlignTop | Qt::AlignLeft);
  results_text_->setMargin(6);
  results_text_->setText(tr("No results yet."));
  auto* text_scroll = new QScrollArea;
  text_scroll->setWidget(results_text_);
  text_scroll->setWidgetResizable(true);
  // Wide enough for the longest line of the results text.
  text_scroll->setMinimumWidth(
      QFontMetrics(results_text_->font()).horizontalAdvance(QString(kResultsColumns, QLatin1Char('0'))) + 30);

  results_area_ = new QWidget;
  results_area_->setObjectName(QStringLiteral("resultsArea"));
  // The two parts of the thesis's results area side by side: the frame, then the numbers.
  auto* splitter = new QSplitter(Qt::Horizontal);
  splitter->setObjectName(QStringLiteral("resultsSplitter"));
  splitter->addWidget(view_);
  splitter->addWidget(text_scroll);
  splitter->setStretchFactor(0, 3);
  splitter->setStretchFactor(1, 1);
  splitter->setSizes({900, 380});
  auto* results_layout = new QVBoxLayout(results_area_);
  results_layout->setContentsMargins(0, 0, 0, 0);
  results_layout->addWidget(splitter);

  banner_ = new MessageBanner;
  auto* central = new QWidget;
  auto* layout = new QVBoxLayout(central);
  layout->setContentsMargins(2, 2, 2, 2);
  layout->setSpacing(2);
  layout->addWidget(banner_);
  layout->addWidget(results_area_, 1);
  setCentralWidget(central);
  connect(view_, &FrameView::painted, this, [this] { worker_->markDisplayed(); });
}

void MainWindow::buildDocks() {
  control_panel_ = new ControlPanel(*binder_);
  auto* controls = new QDockWidget(tr("Control Panel"), this);
  controls->setObjectName(QStringLiteral("controlDock"));
  controls->setWidget(control_panel_);
  controls->setMinimumWidth(280);
  addDockWidget(Qt::LeftDockWidgetArea, controls);

  plots_ = new PosePlots;
  plots_->setObjectName(QStringLiteral("posePlots"));
  histogram_ = new HistogramChart;
  histogram_->setObjectName(QStringLiteral("histogramChart"));
  stage_times_ = new StageTimeChart;
  stage_times_->setObjectName(QStringLiteral("stageTimeChart"));
  auto* tabs = new QTabWidget;
  tabs->setObjectName(QStringLiteral("plotTabs"));
  tabs->addTab(plots_, tr("Parameters"));
  tabs->addTab(histogram_, tr("Histogram"));
  tabs->addTab(stage_times_, tr("Stage times"));
  auto* plots = new QDockWidget(tr("Plots"), this);
  plots->setObjectName(QStringLiteral("plotDock"));
  plots->setWidget(tabs);
  addDockWidget(Qt::BottomDockWidgetArea, plots);
  connect(plots_, &PosePlots::message, this, &MainWindow::showInfo);
  connect(plots_, &PosePlots::error, this, &MainWindow::showError);
  connect(tabs, &QTabWidget::currentChanged, this, [this] {
    readouts_dirty_ = true;
    refreshReadouts();
  });

  SourcePanel* source = control_panel_->sourcePanel();
  connect(source, &SourcePanel::openFileRequested, this, [this] { openDialog(false); });
  connect(source, &SourcePanel::startRequested, this, [this] { startSource(); });
  connect(source, &SourcePanel::stopRequested, this, &MainWindow::stopSource);
  connect(source, &SourcePanel::stepRequested, this, &MainWindow::stepFile);
  // The source chosen is the source in use: its camera model is the one shown and calibrated.
  connect(source, &SourcePanel::kindChanged, this, [this](SourceKind kind) {
    settings_.source = kind;
    binder_->refresh();
    worker_->setSettings(settings_);
    banner_->clearError();  // an earlier source's problem is not this one's
    if (!opening_paths_) worker_->selectSource(kind);
  });
  OutputPanel* output = control_panel_->outputPanel();
  connect(output, &OutputPanel::dataOutToggled, this, &MainWindow::dataOutDialog);
  connect(output, &OutputPanel::screenshotRequested, this, &MainWindow::screenshotDialog);
  connect(output, &OutputPanel::freezeOnScreenshotToggled, this, &MainWindow::setFreezeOnScreenshot);
  connect(output, &OutputPanel::settingsDialogRequested, this, &MainWindow::settingsDialog);
  connect(output, &OutputPanel::saveSettingsRequested, this, &MainWindow::saveSettingsDialog);
  connect(output, &OutputPanel::loadSettingsRequested, this, &MainWindow::loadSettingsDialog);
  connect(output, &OutputPanel::restoreDefaultsRequested, this, &MainWindow::restoreDefaults);
  connect(control_panel_->calibrationPanel(), &CalibrationPanel::wizardRequested, this,
          [this] { showCalibrationWizard(*this); });
  connect(control_panel_->calibrationPanel(), &CalibrationPanel::d0Requested, this, [this] { showD0Dialog(*this); });
}

void MainWindow::buildStatusBar() {
  status_source_ = new QLabel(tr("no source"));
  status_rate_ = new QLabel;
  status_state_ = new QLabel;
  status_source_->setObjectName(QStringLiteral("statusSource"));
  status_rate_->setObjectName(QStringLiteral("statusRate"));
  status_state_->setObjectName(QStringLiteral("statusState"));
  status_stream_ = new QLabel;
  status_stream_->setObjectName(QStringLiteral("statusStream"));
  status_stream_->setVisible(false);
  status_data_out_ = new QLabel;
  status_data_out_->setObjectName(QStringLiteral("statusDataOut"));
  status_data_out_->setStyleSheet(QStringLiteral("color: #1b7a2f; font-weight: bold;"));
  status_data_out_->setVisible(false);
  // A normal widget, so a message (an error, a warning) takes its place for a while.
  statusBar()->addWidget(status_state_, 1);
  statusBar()->addPermanentWidget(status_data_out_);
  statusBar()->addPermanentWidget(status_stream_);
  statusBar()->addPermanentWidget(status_rate_);
  statusBar()->addPermanentWidget(status_source_);
}

void MainWindow::connectWorker() {
  connect(worker_, &Worker::packetReady, this, &MainWindow::onPacket);
  connect(worker_, &Worker::runningChanged, this, [this](bool running) {
    control_panel_->sourcePanel()->setRunning(running);
    if (!running) status_rate_->setText(tr("stopped"));
  });
  connect(worker_, &Worker::runningChanged, this, [this](bool running) {
    if (running) banner_->clearError();  // the source runs: an earlier problem is over
  });
  connect(worker_, &Worker::sourceChanged, this, &MainWindow::showSource);
  connect(worker_, &Worker::resultsCleared, this, &MainWindow::clearShownResults);
  // The recent list holds what opened; what fails to load leaves it.
  connect(worker_, &Worker::filesOpened, this, [this](const QStringList& paths, int images) {
    for (const QString& p : paths) recent_->add(p);
    control_panel_->sourcePanel()->setFileCount(images);
    banner_->clearError();
    plots_->clear();  // other images: their numbers are not the list's before
  });
  connect(worker_, &Worker::filesFailed, this, [this](const QStringList& paths) {
    for (const QString& p : paths) recent_->remove(p);
    control_panel_->sourcePanel()->setFileCount(-1);
  });
  connect(worker_, &Worker::imageFailed, this, [this](const QString& path) { recent_->remove(path); });
  connect(worker_, &Worker::errorOccurred, this, &MainWindow::showError);
  connect(worker_, &Worker::warningOccurred, this,
          [this](const QString& message) { statusBar()->showMessage(tr("Warning: %1").arg(message), 15000); });
  connect(worker_, &Worker::dataOutChanged, this, [this](const QString& path) {
    // Said, so that "writing to" does not stay in the status bar after it stopped.
    if (path.isEmpty() && !data_out_path_.isEmpty()) showInfo(tr("Data Out stopped: %1 closed").arg(data_out_path_));
    data_out_path_ = path;
    control_panel_->outputPanel()->setDataOutPath(path);
    if (data_out_action_) data_out_action_->setChecked(!path.isEmpty());
    status_data_out_->setVisible(!path.isEmpty());
    status_data_out_->setText(tr("\u25cf Data Out %1").arg(QFileInfo(path).fileName()));
    status_data_out_->setToolTip(tr("Every frame's parameters are written to %1 (Ctrl+D stops)").arg(path));
    updateTitle();
    if (!path.isEmpty()) showInfo(tr("Data Out writing to %1").arg(path));
  });
}

void MainWindow::onPacket(const DisplayPacketPtr& packet) {
  ++packets_shown_;
  latest_ = packet;
  readouts_dirty_ = true;
  view_->setPacket(packet);
  if (packet->file_count > 0) control_panel_->sourcePanel()->setFileIndex(packet->file_index);
  plots_->append(packet->history);
  // A hidden view will not paint: let the worker send the next packet anyway.
  if (!view_->isVisible() || view_->size().isEmpty()) worker_->markDisplayed();
  // The first frame after a pause is shown at once; while running, text and charts
  // follow at the readout rate (nobody reads numbers changing faster).
  if (!readout_clock_.isValid() || readout_clock_.elapsed() >= kReadoutMs) refreshReadouts();
  emit packetShown();
}

void MainWindow::refreshReadouts() {
  if (!readouts_dirty_ || !latest_) return;
  readouts_dirty_ = false;
  readout_clock_.start();
  const DisplayPacket& packet = *latest_;
  const FrameResult& r = packet.result;
  results_text_->setText(formatResults(packet));
  status_rate_->setText(tr("%1 Hz  CPU %2 %").arg(packet.hz, 0, 'f', 1).arg(packet.cpu_percent, 0, 'f', 0));
  status_state_->setText(statusInWords(r.status));
  status_state_->setStyleSheet(r.status == Status::Ok || r.status == Status::Stopped ? QString()
                                                                                     : QStringLiteral("color: #b00020;"));
  if (!packet.source.isEmpty()) showSource(packet.source);
  status_stream_->setVisible(!packet.stream.isEmpty());
  status_stream_->setText(tr("Stream %1").arg(packet.stream));
  status_stream_->setStyleSheet(packet.stream_ok ? QString() : QStringLiteral("color: #b00020;"));
  if (histogram_->isVisible()) histogram_->setHistogram(r.histogram, r.threshold);
  if (stage_times_->isVisible()) stage_times_->setTimes(r.times);
}

void MainWindow::onSettingsEdited() {
  worker_->setSettings(settings_);
  updateTitle();  // the stream may have been switched
}

void MainWindow::setSettings(const Settings& settings) {
  settings_ = settings;
  settings_.source = control_panel_->sourcePanel()->kind();  // the panel's, never a file's
  binder_->refresh();
  worker_->setSettings(settings_);
  updateTitle();
}

void MainWindow::showSource(const QString& description) {
  if (description == source_description_) return;
  source_description_ = description;
  status_source_->setText(description);
  control_panel_->sourcePanel()->setDescription(description);
  updateTitle();
}

void MainWindow::updateTitle() {
  QStringList parts{tr("ImagePro")};
  if (!source_description_.isEmpty()) parts << source_description_;
  if (!data_out_path_.isEmpty()) parts << tr("Data Out %1").arg(QFileInfo(data_out_path_).fileName());
  if (settings_.stream.enabled)
    parts << tr("Stream %1:%2").arg(QString::fromStdString(settings_.stream.host)).arg(settings_.stream.port);
  const QString title = parts.join(QStringLiteral(" \u2014 "));
  if (title != windowTitle()) setWindowTitle(title);
}

void MainWindow::clearShownResults(const QString& why) {
  latest_.reset();
  readouts_dirty_ = false;
  view_->clear(why);
  results_text_->setText(tr("No results yet."));
  status_state_->setText(why);
  status_state_->setStyleSheet(QString());
  status_rate_->setText(worker_->isRunning() ? QString() : tr("stopped"));
  status_stream_->setVisible(false);
  histogram_->setHistogram(Histogram{}, -1);
  stage_times_->setTimes(StageTimes{});
  plots_->clear();  // one source run's plots, not two runs on one axis
}

void MainWindow::restoreDefaults() {
  const Settings defaults;
  if (!mayLoseCalibration(tr("restoring the defaults"), &defaults)) return;
  setSettings(defaults);
  showInfo(tr("Every option restored to its default"));
}

void MainWindow::selectSource(SourceKind kind) { control_panel_->sourcePanel()->setKind(kind); }

void MainWindow::startSource() {
  const SourcePanel* panel = control_panel_->sourcePanel();
  if (!panel->canStart()) {  // File with nothing to play: the files first
    openDialog(false);
    return;
  }
  worker_->start(panel->kind());
}

void MainWindow::stopSource() { worker_->stop(); }

void MainWindow::openPaths(const QStringList& paths) {
  if (paths.isEmpty()) return;
  opening_paths_ = true;
  selectSource(SourceKind::File);
  opening_paths_ = false;
  worker_->openFiles(paths);
}

void MainWindow::stepFile(FileStep step) {
  if (control_panel_->sourcePanel()->kind() == SourceKind::File) worker_->stepFile(step);
}

QString MainWindow::dialogDirectory() const { return dialogFolder(); }

QString MainWindow::bannerText() const { return banner_->text(); }

QString MainWindow::resultsText() const { return results_text_->text(); }

QStringList MainWindow::recentPaths() const { return recent_->paths(); }

void MainWindow::showError(const QString& message) {
  last_error_ = message;
  banner_->showError(message);
  statusBar()->showMessage(message, 15000);
}

void MainWindow::showInfo(const QString& message) { statusBar()->showMessage(message, 5000); }

void MainWindow::restoreLayout() {
  QSettings store;
  if (!restoreGeometry(store.value(QStringLiteral("window/geometry")).toByteArray())) resize(1280, 860);
  if (!restoreState(store.value(QStringLiteral("window/state")).toByteArray())) {
    // First run: the frame gets most of the room (once the window has its size).
    QTimer::singleShot(0, this, [this] {
      resizeDocks({findChild<QDockWidget*>(QStringLiteral("controlDock"))}, {300}, Qt::Horizontal);
      resizeDocks({findChild<QDockWidget*>(QStringLiteral("plotDock"))}, {250}, Qt::Vertical);
    });
  }
  control_panel_->restoreState(store);
  setFreezeOnScreenshot(store.value(QStringLiteral("screenshot/freeze"), false).toBool());
}

void MainWindow::closeEvent(QCloseEvent* event) {
  if (!mayLoseCalibration(tr("quitting"))) {
    event->ignore();
    return;
  }
  QSettings store;
  store.setValue(QStringLiteral("window/geometry"), saveGeometry());
  store.setValue(QStringLiteral("window/state"), saveState());
  control_panel_->saveState(store);
  worker_->stop();
  QMainWindow::closeEvent(event);
}

}  // namespace imagepro::app
