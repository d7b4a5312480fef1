#include "app/analysis/analysis_window.h"

#include <QButtonGroup>
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QRadioButton>
#include <QSpinBox>
#include <QSplitter>
#include <QStackedWidget>
#include <QTableWidget>
#include <QThread>
#include <QTimer>
#include <QVBoxLayout>

#include "app/analysis/analysis_live.h"
#include "app/plots/analysis_plots.h"
#include "app/main_window/main_window.h"
#include "app/settings/settings_binder.h"
#include "app/main_window/dialog_folder.h"

namespace imagepro::app {

namespace {

// A browse button starts at the file already named in its field, else where the user last was.
QString startIn(const QString& named) {
  const QFileInfo info(named);
  return !named.isEmpty() && info.absoluteDir().exists() ? info.absoluteFilePath() : dialogFolder();
}

constexpr int kPollMs = 50;          // progress bar and live counts
constexpr int kLiveRedrawEvery = 10;  // polls between live redraws of the two-target charts

QDoubleSpinBox* doubleSpin(double lo, double hi, double value, int decimals, const QString& suffix) {
  auto* box = new QDoubleSpinBox;
  box->setRange(lo, hi);
  box->setDecimals(decimals);
  box->setValue(value);
  box->setSuffix(suffix);
  return box;
}

QSpinBox* intSpin(int lo, int hi, int value) {
  auto* box = new QSpinBox;
  box->setRange(lo, hi);
  box->setValue(value);
  return box;
}

}  // namespace

AnalysisWindow::AnalysisWindow(MainWindow& main, QWidget* parent) : QWidget(parent, Qt::Window), main_(main) {
  setObjectName(QStringLiteral("analysisWindow"));
  setWindowTitle(tr("ImagePro - Analysis"));

  summary_ = new QTableWidget;
  summary_->setObjectName(QStringLiteral("analysisSummary"));
  summary_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  summary_->verticalHeader()->hide();
  summary_->verticalHeader()->setDefaultSectionSize(summary_->fontMetrics().height() + 6);
  summary_->setMinimumHeight(120);
  pendulum_chart_ = new PendulumChart;
  two_target_charts_ = new TwoTargetCharts;
  plots_ = new QStackedWidget;
  plots_->addWidget(pendulum_chart_);
  plots_->addWidget(two_target_charts_);
  auto* results = new QSplitter(Qt::Vertical);
  results->addWidget(summary_);
  results->addWidget(plots_);
  results->setStretchFactor(0, 1);
  results->setStretchFactor(1, 2);
  results->setSizes({280, 440});  // the pendulum's table whole, the charts below

  auto* layout = new QHBoxLayout(this);
  layout->addWidget(buildControls());
  layout->addWidget(results, 1);

  poll_ = new QTimer(this);
  poll_->setInterval(kPollMs);
  connect(poll_, &QTimer::timeout, this, &AnalysisWindow::pollProgress);
  updateControls();
  resize(1180, 720);
}

AnalysisWindow::~AnalysisWindow() {
  // Not a word to main_ here: as its child this window goes after its members. The
  // connection to its worker ends with either of them.
  live_two_.reset();  // joins its thread
  if (task_) {
    progress_.cancel.store(true);
    task_->wait();
    delete task_;
  }
}

QWidget* AnalysisWindow::buildControls() {
  auto* study_box = new QGroupBox(tr("Study"));
  study_ = new QComboBox;
  study_->setObjectName(QStringLiteral("analysisStudy"));
  study_->addItem(tr("Pendulum (g)"), static_cast<int>(AnalysisStudy::Pendulum));
  study_->addItem(tr("Two targets (distance and angle)"), static_cast<int>(AnalysisStudy::TwoTargets));
  (new QVBoxLayout(study_box))->addWidget(study_);

  auto* input_box = new QGroupBox(tr("Input"));
  input_virtual_ = new QRadioButton(tr("Virtual scene"));
  input_file_ = new QRadioButton(tr("Recorded data-out file..."));
  input_live_ = new QRadioButton(tr("Live stream"));
  input_virtual_->setToolTip(tr("Render the virtual pendulum or two-target object with the current settings, as "
                                "imagepro-cli does, with its exact ground truth"));
  input_file_->setToolTip(tr("A CSV written by Data Out or imagepro-cli reconstruct --data-out; with a still "
                             "recording also a video or images"));
  input_live_->setToolTip(tr("Collect the frames the main window's source produces"));
  auto* inputs = new QButtonGroup(this);
  for (QRadioButton* b : {input_virtual_, input_file_, input_live_}) inputs->addButton(b);
  input_virtual_->setChecked(true);
  file_ = new QLineEdit;
  file_->setObjectName(QStringLiteral("analysisFile"));
  file_->setPlaceholderText(tr("dataout.csv"));
  browse_ = new QPushButton(tr("Browse..."));
  auto* file_row = new QHBoxLayout;
  file_row->addWidget(file_, 1);
  file_row->addWidget(browse_);
  still_file_ = new QLineEdit;
  still_file_->setObjectName(QStringLiteral("analysisStillFile"));
  still_file_->setPlaceholderText(tr("still recording (optional)"));
  still_file_->setToolTip(tr("Pendulum, as the thesis ran it: frames of the target held still at a few places on "
                             "its arc (a pose CSV, a video or images). The length comes from these and the period "
                             "from the file above, the swing. Empty: both from the swing"));
  still_browse_ = new QPushButton(tr("Browse..."));
  auto* still_row = new QHBoxLayout;
  still_row->addWidget(still_file_, 1);
  still_row->addWidget(still_browse_);
  note_ = new QLabel;
  note_->setObjectName(QStringLiteral("analysisNote"));
  note_->setWordWrap(true);
  note_->setStyleSheet(QStringLiteral("color: #555;"));
  auto* input_layout = new QVBoxLayout(input_box);
  input_layout->addWidget(input_virtual_);
  input_layout->addWidget(input_file_);
  input_layout->addLayout(file_row);
  input_layout->addLayout(still_row);
  input_layout->addWidget(input_live_);
  input_layout->addWidget(note_);

  auto* params_box = new QGroupBox(tr("Parameters"));
  params_ = new QStackedWidget;
  params_->addWidget(buildPendulumParams());
  params_->addWidget(buildTwoTargetParams());
  (new QVBoxLayout(params_box))->addWidget(params_);

  run_ = new QPushButton;
  run_->setObjectName(QStringLiteral("analysisRun"));
  run_->setDefault(true);
  progress_bar_ = new QProgressBar;
  progress_bar_->setObjectName(QStringLiteral("analysisProgress"));
  progress_bar_->setRange(0, 1);
  progress_bar_->setValue(0);
  count_ = new QLabel;
  count_->setObjectName(QStringLiteral("analysisCount"));
  message_ = new QLabel;
  message_->setObjectName(QStringLiteral("analysisMessage"));
  message_->setWordWrap(true);
  message_->setTextInteractionFlags(Qt::TextSelectableByMouse);

  auto* panel = new QWidget;
  panel->setFixedWidth(330);
  auto* v = new QVBoxLayout(panel);
  v->setContentsMargins(0, 0, 0, 0);
  v->addWidget(study_box);
  v->addWidget(input_box);
  v->addWidget(params_box);
  v->addWidget(run_);
  v->addWidget(progress_bar_);
  v->addWidget(count_);
  v->addWidget(message_);
  v->addStretch(1);

  connect(study_, &QComboBox::currentIndexChanged, this, &AnalysisWindow::updateControls);
  connect(inputs, &QButtonGroup::buttonToggled, this, [this] { updateControls(); });
  connect(browse_, &QPushButton::clicked, this, [this] {
    const QString path = QFileDialog::getOpenFileName(this, tr("Recorded data-out file"), startIn(file_->text()),
                                                      tr("CSV files (*.csv *.txt);;All files (*)"));
    if (path.isEmpty()) return;
    rememberDialogFolder(path);
    file_->setText(path);
  });
  connect(still_browse_, &QPushButton::clicked, this, [this] {
    const QString path = QFileDialog::getOpenFileName(this, tr("Still recording"), startIn(still_file_->text()),
                                                      tr("Recordings (*.csv *.avi *.mp4 *.mkv *.mov *.png *.pgm *.bmp "
                                                         "*.jpg *.tif *.txt);;All files (*)"));
    if (path.isEmpty()) return;
    rememberDialogFolder(path);
    still_file_->setText(path);
  });
  connect(run_, &QPushButton::clicked, this, [this] {
    if (isBusy()) cancel();
    else run();
  });
  return panel;
}

QWidget* AnalysisWindow::buildPendulumParams() {
  auto* page = new QWidget;
  auto* form = new QFormLayout(page);
  form->setContentsMargins(0, 0, 0, 0);
  const VirtualPendulumParams defaults;
  pendulum_frames_ = intSpin(10, 100000, defaults.frames);
  pendulum_frames_->setToolTip(tr("Virtual scene: frames rendered at the settings' frame rate"));
  pendulum_noise_ = doubleSpin(0.0, 50.0, defaults.noise_sigma, 1, tr(" grey levels"));
  pendulum_noise_->setToolTip(tr("Virtual scene: image noise (standard deviation)"));
  // The settings' frame rate, so its range is the settings table's.
  const Settings& settings = main_.settings();
  rate_ = new QDoubleSpinBox;
  if (const SettingKey* key = settingKeyOf(settings, &settings.virtual_scene.frame_rate_hz))
    setTableRange(rate_, *key, 2);
  rate_->setValue(settings.virtual_scene.frame_rate_hz);
  rate_->setSuffix(tr(" Hz"));
  rate_->setToolTip(tr("File or live input: the frame rate that times frames without timestamps (image files, a "
                       "CSV without timestamp_s)"));
  amplitude_correction_ = new QCheckBox(tr("Amplitude correction"));
  amplitude_correction_->setChecked(defaults.options.amplitude_correction);
  amplitude_correction_->setToolTip(tr("g from the small-swing period (exact pendulum); off: eq. 5.1 with the measured "
                                       "period, as in the thesis"));
  period_method_ = new QComboBox;
  period_method_->setObjectName(QStringLiteral("analysisPeriodMethod"));
  period_method_->addItem(tr("Mid-swing crossings"), static_cast<int>(PeriodMethod::Crossings));
  period_method_->addItem(tr("Thesis: first to last maximum"), static_cast<int>(PeriodMethod::Maxima));
  period_method_->setToolTip(tr("The period g is computed from; the summary shows both. The thesis divided the time "
                                "between the first and last maximum by the cycles, averaged over Tx, Ty and Tz"));
  interlaced_ = new QCheckBox(tr("Interlaced frames"));
  interlaced_->setObjectName(QStringLiteral("analysisInterlaced"));
  interlaced_->setChecked(defaults.interlaced);
  interlaced_->setToolTip(tr("Virtual scene: two fields a frame, the even rows half a frame time before the odd ones, "
                             "as the thesis's camera (fig. 5.11)"));
  still_positions_ = intSpin(0, 50, defaults.still_recording ? defaults.still.positions : 0);
  still_positions_->setObjectName(QStringLiteral("analysisStillPositions"));
  still_positions_->setSpecialValueText(tr("none: length from the swing"));
  still_positions_->setToolTip(tr("Virtual scene: the length from a still recording first, the pendulum held at this "
                                  "many angles over +-%1 deg, %2 frames each (thesis 5.3.2)")
                                   .arg(defaults.still.span_deg)
                                   .arg(defaults.still.frames_per_position));
  form->addRow(tr("Frames"), pendulum_frames_);
  form->addRow(tr("Noise"), pendulum_noise_);
  form->addRow(tr("Still positions"), still_positions_);
  form->addRow(interlaced_);
  form->addRow(tr("Rate for untimed frames"), rate_);
  form->addRow(tr("Period for g"), period_method_);
  form->addRow(amplitude_correction_);
  return page;
}

QWidget* AnalysisWindow::buildTwoTargetParams() {
  auto* page = new QWidget;
  auto* form = new QFormLayout(page);
  form->setContentsMargins(0, 0, 0, 0);
  const VirtualTwoTargetParams defaults;
  spacing_ = doubleSpin(1.0, 5000.0, defaults.object.spacing_mm, 1, tr(" mm"));
  spacing_->setToolTip(tr("Known distance between the two target centres"));
  angle_ = doubleSpin(1.0, 179.0, defaults.object.angle_deg, 1, tr(" deg"));
  angle_->setToolTip(tr("Known angle between the two target normals"));
  two_frames_ = intSpin(2, 10000, defaults.frames_per_position);
  two_frames_->setToolTip(tr("Virtual scene: frames per object position, the first half in natural light"));
  position_ = new QComboBox;
  position_->addItem(tr("All three"), 0);
  for (int p = 1; p <= 3; ++p) position_->addItem(tr("Position %1").arg(p), p);
  two_noise_ = doubleSpin(0.0, 50.0, defaults.noise_sigma, 1, tr(" grey levels"));
  thesis_lens_ = new QCheckBox(tr("Thesis camera's lens distortion"));
  thesis_lens_->setChecked(defaults.thesis_lens);
  thesis_lens_->setToolTip(tr("Virtual scene: render and correct with the thesis camera's distortion; off: the "
                              "settings' camera"));
  form->addRow(tr("Known distance"), spacing_);
  form->addRow(tr("Known angle"), angle_);
  form->addRow(tr("Frames per position"), two_frames_);
  form->addRow(tr("Positions"), position_);
  form->addRow(tr("Noise"), two_noise_);
  form->addRow(thesis_lens_);
  return page;
}

void AnalysisWindow::setStudy(AnalysisStudy study) { study_->setCurrentIndex(study_->findData(static_cast<int>(study))); }

AnalysisStudy AnalysisWindow::study() const { return static_cast<AnalysisStudy>(study_->currentData().toInt()); }

void AnalysisWindow::setInput(AnalysisInput input) {
  (input == AnalysisInput::VirtualScene ? input_virtual_ : input == AnalysisInput::DataOutFile ? input_file_ : input_live_)
      ->setChecked(true);
}

AnalysisInput AnalysisWindow::input() const {
  if (input_file_->isChecked()) return AnalysisInput::DataOutFile;
  if (input_live_->isChecked()) return AnalysisInput::LiveStream;
  return AnalysisInput::VirtualScene;
}

void AnalysisWindow::setFilePath(const QString& path) { file_->setText(path); }

void AnalysisWindow::setStillPath(const QString& path) { still_file_->setText(path); }

void AnalysisWindow::setPendulumParams(const VirtualPendulumParams& p) {
  pendulum_frames_->setValue(p.frames);
  pendulum_noise_->setValue(p.noise_sigma);
  amplitude_correction_->setChecked(p.options.amplitude_correction);
  period_method_->setCurrentIndex(period_method_->findData(static_cast<int>(p.options.period_method)));
  interlaced_->setChecked(p.interlaced);
  still_positions_->setValue(p.still_recording ? p.still.positions : 0);
}

void AnalysisWindow::setTwoTargetParams(const VirtualTwoTargetParams& p) {
  spacing_->setValue(p.object.spacing_mm);
  angle_->setValue(p.object.angle_deg);
  two_frames_->setValue(p.frames_per_position);
  position_->setCurrentIndex(position_->findData(p.position >= 1 && p.position <= 3 ? p.position : 0));
  two_noise_->setValue(p.noise_sigma);
  thesis_lens_->setChecked(p.thesis_lens);
}

VirtualPendulumParams AnalysisWindow::pendulumParams() const {
  VirtualPendulumParams p;
  p.frames = pendulum_frames_->value();
  p.noise_sigma = pendulum_noise_->value();
  p.options = pendulumOptions();
  p.interlaced = interlaced_->isChecked();
  p.still_recording = still_positions_->value() > 0;
  if (p.still_recording) p.still.positions = still_positions_->value();
  return p;
}

PendulumAnalysisOptions AnalysisWindow::pendulumOptions() const {
  PendulumAnalysisOptions o;
  o.amplitude_correction = amplitude_correction_->isChecked();
  o.period_method = static_cast<PeriodMethod>(period_method_->currentData().toInt());
  return o;
}

VirtualTwoTargetParams AnalysisWindow::twoTargetParams() const {
  VirtualTwoTargetParams p;
  p.object.spacing_mm = spacing_->value();
  p.object.angle_deg = angle_->value();
  p.frames_per_position = two_frames_->value();
  p.position = position_->currentData().toInt();
  p.noise_sigma = two_noise_->value();
  p.thesis_lens = thesis_lens_->isChecked();
  return p;
}

void AnalysisWindow::updateControls() {
  const AnalysisStudy s = collecting_ ? collecting_study_ : study();
  const AnalysisInput in = input();
  const bool idle = !isBusy() && !collecting_;
  study_->setEnabled(idle);
  for (QRadioButton* b : {input_virtual_, input_file_, input_live_}) b->setEnabled(idle);
  file_->setEnabled(idle && in == AnalysisInput::DataOutFile);
  browse_->setEnabled(idle && in == AnalysisInput::DataOutFile);
  const bool still = idle && in == AnalysisInput::DataOutFile && s == AnalysisStudy::Pendulum;
  still_file_->setEnabled(still);
  still_browse_->setEnabled(still);
  params_->setCurrentIndex(s == AnalysisStudy::Pendulum ? 0 : 1);
  params_->setEnabled(idle);
  plots_->setCurrentIndex(s == AnalysisStudy::Pendulum ? 0 : 1);
  const bool virtual_scene = in == AnalysisInput::VirtualScene;
  pendulum_frames_->setEnabled(virtual_scene);
  pendulum_noise_->setEnabled(virtual_scene);
  rate_->setEnabled(!virtual_scene);
  for (QWidget* w : std::initializer_list<QWidget*>{two_frames_, position_, two_noise_, thesis_lens_})
    w->setEnabled(virtual_scene);

  QString note;
  bool runnable = true;
  if (s == AnalysisStudy::TwoTargets && in == AnalysisInput::DataOutFile) {
    note = tr("A data-out file holds one pose per frame; the distance and angle need both targets of the same "
              "frame. Open the recorded images in the main window and analyse them as the live stream, or run "
              "imagepro-cli two-targets on them.");
    runnable = false;
  } else if (s == AnalysisStudy::TwoTargets && in == AnalysisInput::LiveStream) {
    note = tr("The frames the main window shows are measured on a thread of their own (latest frame wins), so its "
              "Display background must be Source. The Virtual source shows one target: use a camera or image files "
              "showing the two-target object.");
  } else if (in == AnalysisInput::LiveStream) {
    note = tr("Every frame the main window's source produces is collected (start its source, e.g. the Virtual source "
              "with the Pendulum motion); Stop analyses them.");
  } else if (in == AnalysisInput::DataOutFile) {
    note = tr("Rows without timestamp_s are timed by the rate below.");
  }
  note_->setText(note);
  note_->setVisible(!note.isEmpty());

  if (isBusy()) run_->setText(tr("Cancel"));
  else if (collecting_) run_->setText(tr("Stop collecting"));
  else if (in == AnalysisInput::LiveStream) run_->setText(tr("Start collecting"));
  else run_->setText(tr("Run"));
  run_->setEnabled(isBusy() || collecting_ || runnable);
}

void AnalysisWindow::setMessage(const QString& text, bool error) {
  message_->setText(text);
  message_->setStyleSheet(error ? QStringLiteral("color: #b00020;") : QString());
}

QString AnalysisWindow::message() const { return message_->text(); }

std::int64_t AnalysisWindow::collectedFrames() const {
  return collecting_study_ == AnalysisStudy::Pendulum ? static_cast<std::int64_t>(live_samples_.size())
                                                      : static_cast<std::int64_t>(two_targets_.frames.size());
}

// ---- running ------------------------------------------------------------------------

void AnalysisWindow::startTask(std::function<void()> work, std::function<void()> done) {
  progress_.done.store(0);
  progress_.total.store(0);
  progress_.cancel.store(false);
  task_ = QThread::create(std::move(work));
  connect(task_, &QThread::finished, this, [this, done = std::move(done)] {
    task_->deleteLater();
    task_ = nullptr;
    poll_->stop();
    progress_bar_->setRange(0, 1);
    progress_bar_->setValue(progress_.cancel.load() ? 0 : 1);
    done();
    updateControls();
    emit finished();
  });
  progress_bar_->setRange(0, 0);  // busy until the work tells its size
  task_->start();
  poll_->start();
  updateControls();
}

void AnalysisWindow::pollProgress() {
  if (isBusy()) {
    const int total = progress_.total.load();
    if (total > 0) {
      progress_bar_->setRange(0, total);
      progress_bar_->setValue(progress_.done.load());
    }
    return;
  }
  if (!collecting_) return;
  if (collecting_study_ == AnalysisStudy::Pendulum) {
    count_->setText(tr("%1 frames collected").arg(live_samples_.size()));
  } else {
    takeLiveTwoTargetFrames(++live_polls_ % kLiveRedrawEvery == 0);
  }
}

void AnalysisWindow::cancel() {
  if (task_) progress_.cancel.store(true);
}

void AnalysisWindow::run() {
  if (isBusy()) return;
  if (input() == AnalysisInput::LiveStream) {
    if (collecting_) stopCollecting();
    else startCollecting();
    return;
  }
  const Settings settings = main_.settings();
  setMessage(tr("Running..."), false);
  count_->clear();
  if (study() == AnalysisStudy::Pendulum) {
    pendulum_chart_->clear();
    summary_->clear();
    auto out = std::make_shared<PendulumStudyResult>();
    if (input() == AnalysisInput::VirtualScene) {
      const VirtualPendulumParams params = pendulumParams();
      startTask([out, settings, params, this] { *out = runVirtualPendulum(settings, params, progress_.callbacks()); },
                [out, this] {
                  pendulum_ = std::move(*out);
                  showPendulum();
                });
    } else {
      const std::string path = file_->text().trimmed().toStdString();
      if (path.empty()) {
        pendulum_ = PendulumStudyResult{};
        pendulum_.status = Status::FileNotFound;
        pendulum_.error = "FileNotFound: choose a data-out file first";
        showPendulum();
        emit finished();
        return;
      }
      const double rate = rate_->value();
      const PendulumAnalysisOptions options = pendulumOptions();
      const std::string still = still_file_->text().trimmed().toStdString();
      auto work = still.empty() ? std::function<void()>([out, path, rate, options] {
        *out = runPendulumFile(path, rate, options);
      })
                                : std::function<void()>([out, still, path, settings, rate, options, this] {
                                    *out = runPendulumStillSwing(still, path, settings, rate, options,
                                                                 progress_.callbacks());
                                  });
      startTask(std::move(work), [out, this] {
        pendulum_ = std::move(*out);
        showPendulum();
      });
    }
    return;
  }
  if (input() == AnalysisInput::DataOutFile) return;  // not possible: the note says why
  two_target_charts_->clear();
  summary_->clear();
  auto out = std::make_shared<TwoTargetStudyResult>();
  const VirtualTwoTargetParams params = twoTargetParams();
  startTask([out, settings, params, this] { *out = runVirtualTwoTargets(settings, params, progress_.callbacks()); },
            [out, this] {
              two_targets_ = std::move(*out);
              showTwoTargets();
            });
}

}  // namespace imagepro::app
