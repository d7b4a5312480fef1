#include "app/worker/worker.h"

#include <QMetaObject>
#include <QTimer>

#include <algorithm>
#include <ctime>
#include <filesystem>

#include "app/worker/packet_builder.h"
#include "app/worker/source_factory.h"

namespace imagepro::app {

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kMaxDisplayHz = 60.0;

// Holds at most this many undisplayed pose samples (the GUI may be hidden).
constexpr std::size_t kMaxHistory = 20000;

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

bool isFatalSourceError(Status s) {
  switch (s) {
    case Status::FileNotFound:
    case Status::FileUnreadable:
    case Status::FileTruncated:
    case Status::ImageTooLarge:
    case Status::CameraNotFound:
    case Status::CameraPermissionDenied:
    case Status::CameraBusy:
    case Status::CameraNoSupportedFormat:
    case Status::CameraFormatRefused:
    case Status::CameraDisconnected:
      return true;
    default:
      return false;
  }
}

bool isSourceError(Status s) { return isFatalSourceError(s) || s == Status::EmptyFrame || s == Status::CameraTimeout; }

}  // namespace

Worker::Worker(const Settings& settings, QObject* parent)
    : QObject(parent), engine_(settings), applied_(settings) {
  qRegisterMetaType<DisplayPacketPtr>("imagepro::app::DisplayPacketPtr");
  qRegisterMetaType<cv::Mat>("cv::Mat");
  timer_ = new QTimer(this);  // a child, so it moves to the worker thread with us
  timer_->setSingleShot(true);
  timer_->setTimerType(Qt::PreciseTimer);
  connect(timer_, &QTimer::timeout, this, &Worker::tick);
  history_.reserve(256);
  applyStream(settings.stream);
}

Worker::~Worker() = default;

// ---- thread-safe entry points ------------------------------------------------

void Worker::setSettings(const Settings& settings) {
  {
    std::lock_guard lock(pending_mutex_);
    pending_settings_ = settings;
  }
  QMetaObject::invokeMethod(this, &Worker::onIdleUpdate, Qt::QueuedConnection);
}

void Worker::pressKey(VirtualKey key) {
  {
    std::lock_guard lock(pending_mutex_);
    pending_keys_.push_back(key);
  }
  QMetaObject::invokeMethod(this, &Worker::onIdleUpdate, Qt::QueuedConnection);
}

void Worker::markDisplayed() {
  packet_in_flight_.store(false);
  // If a frame was skipped while the GUI was busy and nothing new is coming, send it now.
  QMetaObject::invokeMethod(this, [this] {
    if (display_dirty_ && !running_.load()) publish();
  }, Qt::QueuedConnection);
}

void Worker::selectSource(SourceKind kind) {
  QMetaObject::invokeMethod(this, [this, kind] { doSelect(kind); }, Qt::QueuedConnection);
}

void Worker::start(SourceKind kind) {
  QMetaObject::invokeMethod(this, [this, kind] { doStart(kind); }, Qt::QueuedConnection);
}

void Worker::openFiles(const QStringList& paths) {
  QMetaObject::invokeMethod(this, [this, paths] { doOpenFiles(paths); }, Qt::QueuedConnection);
}

void Worker::stepFile(FileStep step) {
  QMetaObject::invokeMethod(this, [this, step] { doStepFile(step); }, Qt::QueuedConnection);
}

void Worker::stop() {
  QMetaObject::invokeMethod(this, &Worker::doStop, Qt::QueuedConnection);
}

void Worker::setDataOut(const QString& path, ExistingFile existing, bool replace) {
  QMetaObject::invokeMethod(this, [this, path, existing, replace] { doSetDataOut(path, existing, replace); },
                            Qt::QueuedConnection);
}

void Worker::setCameraControl(const QString& device, const QString& key, qint64 value) {
  QMetaObject::invokeMethod(this, [this, device, key, value] {
    std::string error;
    if (!ok(imagepro::app::setCameraControl(source_.get(), kind_, device.toStdString(), key.toStdString(), value, error)))
      emit errorOccurred(QString::fromStdString(error));
  }, Qt::QueuedConnection);
}

void Worker::closeDataOut() {
  QMetaObject::invokeMethod(this, [this] {
    data_out_.close();
    emit dataOutChanged(QString());
  }, Qt::QueuedConnection);
}

void Worker::captureFrame(quint64 request) {
  QMetaObject::invokeMethod(this, [this, request] {
    cv::Mat copy;
    if (kind_ == SourceKind::File) {
      if (have_file_frame_) copy = file_frame_.image.clone();
    } else if (source_ && have_result_) {  // a stopped camera's frame was a view of its buffers
      copy = engine_.lastFrame().image.clone();
    }
    const QString source = source_ ? QString::fromStdString(source_->describe()) : QString();
    emit frameCaptured(request, copy, source, running_.load());
  }, Qt::QueuedConnection);
}

Settings Worker::appliedSettings() const {
  std::lock_guard lock(pending_mutex_);
  return applied_;
}

// ---- worker thread -------------------------------------------------------------

QString Worker::description() const {
  if (source_) return QString::fromStdString(source_->describe());
  switch (kind_) {
    case SourceKind::File: return QStringLiteral("file: none open");
    case SourceKind::Camera:
      return QStringLiteral("camera %1 (not started)").arg(QString::fromStdString(engine_.settings().camera_source.device));
    case SourceKind::Virtual: break;
  }
  return QStringLiteral("virtual (not started)");
}

QString Worker::waitingHint() const {
  switch (kind_) {
    case SourceKind::File:
      return QStringLiteral("No image open: Open File... (Ctrl+O), or drop images on the window");
    case SourceKind::Camera:
      return QStringLiteral("Camera %1: press Start (F5)").arg(QString::fromStdString(engine_.settings().camera_source.device));
    case SourceKind::Virtual: break;
  }
  return QStringLiteral("Virtual source: press Start (F5)");
}

bool Worker::ensureSource(SourceKind kind, const QStringList& paths) {
  std::string error;
  std::vector<std::string> warnings;
  source_.reset();  // a camera frees its device before it is opened again
  source_ = createSource(kind, engine_.settings(), paths, error, warnings);
  kind_ = kind;
  useSourceCamera();
  have_file_frame_ = false;
  file_ended_ = false;
  if (!source_) {
    const QString why = QString::fromStdString(error);
    emit errorOccurred(why);
    // Nothing of an earlier source or file stays on screen as if it were this one's.
    clearResults(QStringLiteral("%1 not opened: %2").arg(sourceKindLabel(kind), why));
    emit sourceChanged(kind == SourceKind::Camera
                           ? QStringLiteral("camera %1 (unavailable)")
                                 .arg(QString::fromStdString(engine_.settings().camera_source.device))
                           : QStringLiteral("file: none open"));
    return false;
  }
  for (const std::string& w : warnings) emit warningOccurred(QString::fromStdString(w));
  emit sourceChanged(QString::fromStdString(source_->describe()));
  return true;
}

void Worker::clearResults(const QString& why) {
  have_result_ = false;
  display_dirty_ = false;
  history_.clear();
  // A packet of the old source the GUI will now never paint must not hold back the next one.
  packet_in_flight_.store(false);
  emit resultsCleared(why);
}

ImageListSource* Worker::imageList() const {
  return kind_ == SourceKind::File ? dynamic_cast<ImageListSource*>(source_.get()) : nullptr;
}

void Worker::doSelect(SourceKind kind) {
  applyPending();
  if (kind == kind_ && (source_ || kind != SourceKind::Virtual)) {
    emit sourceChanged(description());
    return;
  }
  doStop();
  // An image list waits aside for File to be selected again; a video is opened anew.
  if (imageList()) parked_files_ = std::move(source_);
  source_.reset();
  kind_ = kind;
  useSourceCamera();
  have_file_frame_ = false;
  clearResults(waitingHint());
  if (kind == SourceKind::Virtual) {
    ensureSource(kind, {});
  } else if (kind == SourceKind::File && parked_files_) {
    source_ = std::move(parked_files_);
    emit sourceChanged(description());
    showImage(std::max(imageList()->shown(), 0));
  } else {
    emit sourceChanged(description());
  }
}

void Worker::doStart(SourceKind kind) {
  applyPending();
  if (kind != kind_) doSelect(kind);
  if (kind == SourceKind::File) {
    if (ImageListSource* list = imageList()) {
      if (list->atEnd()) list->seek(0);  // played to its end: again from the first image
    } else if (!source_ || file_ended_) {
      // Nothing open (the window asks for files first), or a video played to its end.
      if (file_paths_.isEmpty() || !ensureSource(SourceKind::File, file_paths_)) return;
    }
  } else if (!source_) {
    if (!ensureSource(kind, {})) {
      setRunning(false);
      return;
    }
  }
  engine_.resetTracking();
  next_due_ = Clock::now();
  setRunning(true);
  timer_->start(0);
}

void Worker::doOpenFiles(const QStringList& paths) {
  doStop();
  applyPending();
  parked_files_.reset();
  file_paths_ = paths;
  if (!ensureSource(SourceKind::File, paths)) {
    emit filesFailed(paths);
    return;
  }
  ImageListSource* list = imageList();
  emit filesOpened(paths, list ? list->count() : 0);
  if (list) {
    showImage(0);
    return;
  }
  engine_.resetTracking();  // a video plays at its own rate
  next_due_ = Clock::now();
  setRunning(true);
  timer_->start(0);
}

void Worker::showImage(int index) {
  ImageListSource* list = imageList();
  if (!list) return;
  timer_->stop();
  setRunning(false);
  list->seek(index);
  engine_.resetTracking();  // still images are searched whole
  if (!processFrame(true)) return;
  if (isFatalSourceError(result_.status)) reportSourceError(result_.status);
  publish();
}

void Worker::doStepFile(FileStep step) {
  ImageListSource* list = imageList();
  if (!list) return;
  applyPending();
  const int shown = list->shown();
  int target = shown;
  switch (step) {
    case FileStep::First: target = 0; break;
    case FileStep::Previous: target = shown - 1; break;
    case FileStep::Next: target = shown + 1; break;
    case FileStep::Last: target = list->count() - 1; break;
  }
  target = std::clamp(target, 0, list->count() - 1);
  if (target == shown && have_result_) {  // at an end of the list: a play still stops
    doStop();
    return;
  }
  showImage(target);
}

void Worker::doStop() {
  timer_->stop();
  if (kind_ == SourceKind::Camera) source_.reset();  // frees the device for other programs
  setRunning(false);
  // Frames processed while the GUI drew the previous packet are sent now (or, if it is
  // still drawing, when it is done: markDisplayed), so their history reaches the window.
  if (display_dirty_) publish();
}

void Worker::doSetDataOut(const QString& path, ExistingFile existing, bool replace) {
  data_out_.close();
  const std::string file = path.toStdString();
  std::error_code ec;
  if (replace) std::filesystem::remove(file, ec);
  std::string error;
  if (!ok(data_out_.open(file, existing, error))) {
    emit errorOccurred(QStringLiteral("Data Out: ") + QString::fromStdString(error));
    emit dataOutChanged(QString());
    return;
  }
  emit dataOutChanged(QString::fromStdString(data_out_.path()));
  if (!data_out_.notice().empty()) emit warningOccurred(QStringLiteral("Data Out: ") + QString::fromStdString(data_out_.notice()));
}

void Worker::setRunning(bool running) {
  if (running_.exchange(running) != running) emit runningChanged(running);
}

bool Worker::applyPending() {
  std::optional<Settings> settings;
  std::vector<VirtualKey> keys;
  {
    std::lock_guard lock(pending_mutex_);
    settings.swap(pending_settings_);
    keys.swap(pending_keys_);
    if (settings) applied_ = *settings;
  }
  if (settings) {
    engine_.setSettings(*settings);
    useSourceCamera();
    applyStream(settings->stream);
    if (source_ && !updateSource(*source_, kind_, *settings)) {
      // A camera asked for another device, size or rate: opened anew, or stopped with the error.
      if (!ensureSource(kind_, {})) {
        timer_->stop();
        setRunning(false);
      }
    } else {
      emit sourceChanged(description());  // a camera not started names the device chosen
    }
  }
  if (source_)
    for (VirtualKey key : keys) pressSourceKey(*source_, kind_, key);
  return settings.has_value();
}

void Worker::useSourceCamera() {
  if (engine_.settings().source == kind_) return;
  Settings s = engine_.settings();
  s.source = kind_;
  engine_.setSettings(s);
}

void Worker::applyStream(const StreamOptions& options) {
  if (!options.enabled) {
    stream_.close();
    return;
  }
  if (stream_.isActive() && stream_.options() == options) return;
  std::string error;
  if (!ok(stream_.open(options, error))) emit errorOccurred(QStringLiteral("Stream: ") + QString::fromStdString(error));
}

void Worker::onIdleUpdate() {
  if (running_.load()) return;  // the next tick applies it
  const bool changed = applyPending();
  if (changed && kind_ == SourceKind::File && have_file_frame_) {
    processFrame(false);
    publish();
  }
}

void Worker::tick() {
  if (!running_.load() || !source_) return;
  const bool changed = applyPending();
  if (!source_) return;  // a camera that could not be opened anew
  if (!processFrame(true)) {
    file_ended_ = kind_ == SourceKind::File;
    doStop();
    // Options that came with the end of a file list apply to its last frame, still shown.
    if (changed && kind_ == SourceKind::File && have_file_frame_) {
      processFrame(false);
      publish();
    }
    return;
  }
  if (isFatalSourceError(result_.status)) {
    reportSourceError(result_.status);
    if (kind_ != SourceKind::File) {  // a file list goes on with the next file
      doStop();
      return;
    }
  } else if (isSourceError(result_.status)) {
    reportSourceError(result_.status);
  }
  publish();
  scheduleNext();
}

void Worker::reportSourceError(Status status) {
  QString text = QString::fromStdString(source_ ? source_->lastError() : std::string());
  if (text.isEmpty()) text = QString::fromUtf8(statusMessage(status).data(), statusMessage(status).size());
  emit errorOccurred(text);
  if (const ImageListSource* list = imageList(); list && list->shown() >= 0)
    emit imageFailed(QString::fromStdString(list->path(list->shown())));
}

void Worker::scheduleNext() {
  const double hz = source_->frameRateHz();
  if (hz <= 0.0) {
    timer_->start(0);  // unpaced: as fast as possible, but queued calls still get in
    return;
  }
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / hz));
  const auto now = Clock::now();
  next_due_ += period;
  if (next_due_ + period < now) next_due_ = now;  // fell behind: do not try to catch up
  const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(next_due_ - now).count();
  timer_->start(static_cast<int>(std::max<std::int64_t>(0, wait)));
}

bool Worker::processFrame(bool from_source) {
  if (from_source) {
    // A finished stream leaves the last real frame's result in place.
    if (engine_.step(*source_, step_result_) == Status::EndOfStream) return false;
    std::swap(result_, step_result_);
    if (kind_ == SourceKind::File) {
      // An image that could not be read leaves nothing to reprocess: not the one before it.
      have_file_frame_ = !engine_.lastFrame().image.empty();
      if (have_file_frame_) {
        const Frame& f = engine_.lastFrame();
        f.image.copyTo(file_frame_.image);
        file_frame_.index = f.index;
        file_frame_.timestamp_s = f.timestamp_s;
        file_frame_.name = f.name;
        file_frame_.truth = f.truth;
      }
    }
  } else {
    engine_.resetTracking();  // the same still image again: no history to track from
    engine_.process(file_frame_, result_);
  }
  have_result_ = true;
  afterFrame();
  return true;
}

void Worker::afterFrame() {
  frames_processed_.fetch_add(1);
  const auto now = Clock::now();
  if (last_frame_time_ != Clock::time_point{}) {
    const double dt = std::chrono::duration<double>(now - last_frame_time_).count();
    frame_period_s_ = frame_period_s_ == 0.0 ? dt : 0.9 * frame_period_s_ + 0.1 * dt;
  }
  last_frame_time_ = now;
  const double wall = std::chrono::duration<double>(now - cpu_wall_mark_).count();
  if (wall >= 0.5) {
    const double cpu = threadCpuSeconds();
    if (cpu_wall_mark_ != Clock::time_point{}) cpu_percent_ = 100.0 * (cpu - cpu_time_mark_s_) / wall;
    cpu_wall_mark_ = now;
    cpu_time_mark_s_ = cpu;
  }

  if (history_.size() >= kMaxHistory) history_.erase(history_.begin(), history_.begin() + kMaxHistory / 2);
  history_.push_back({result_.index, result_.timestamp_s, result_.status, result_.pose, result_.truth,
                      imageList() != nullptr});

  if (data_out_.isOpen()) {
    std::string error;
    if (!data_out_.write(result_, error)) {
      emit errorOccurred(QStringLiteral("Data Out stopped: ") + QString::fromStdString(error));
      emit dataOutChanged(QString());
    }
  }
  stream_.send(result_);  // never waits: a full buffer drops the datagram and counts it
}

void Worker::publish() {
  if (!have_result_) return;
  // A running source faster than a screen refreshes is drawn at most kMaxDisplayHz: the
  // frames between two packets still travel in the next one's history, and the GUI
  // thread keeps time for input (drawing every frame at 200+ Hz stalled it for 50 ms).
  const auto now = Clock::now();
  if (running_.load() && now - last_publish_ < std::chrono::duration<double>(1.0 / kMaxDisplayHz)) {
    display_dirty_ = true;
    return;
  }
  if (packet_in_flight_.exchange(true)) {
    display_dirty_ = true;  // the GUI is still busy with the previous one: latest wins
    return;
  }
  display_dirty_ = false;
  last_publish_ = now;
  auto packet = std::make_shared<DisplayPacket>();
  PacketMeters meters;
  meters.hz = frame_period_s_ > 0.0 && running_.load() ? 1.0 / frame_period_s_ : 0.0;
  meters.cpu_percent = cpu_percent_;
  meters.source = source_ ? QString::fromStdString(source_->describe()) : QString();
  buildPacket(engine_, result_, meters, packet_ws_, *packet);
  if (const ImageListSource* list = imageList()) {
    packet->file_index = list->shown();
    packet->file_count = list->count();
  }
  if (stream_.isActive()) {
    packet->stream = QString::fromStdString(stream_.report());
    packet->stream_ok = ok(stream_.status());
  }
  packet->history.swap(history_);
  history_.clear();
  emit packetReady(std::move(packet));
}

}  // namespace imagepro::app
