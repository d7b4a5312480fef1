#pragma once
// The frame loop of the application (thesis 5.2.2): an Engine and a FrameSource
// living in their own thread. Options changed in the GUI land in a pending slot and
// are applied at the next frame boundary, so methods switch without stopping.
// Results go to the GUI as small display packets; latest frame wins: while the GUI
// has not painted the previous packet no new one is sent, so it never falls behind.
// Every public function is safe to call from any thread.
#include <QObject>
#include <QStringList>

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "app/worker/display_packet.h"
#include "app/worker/image_list_source.h"
#include "app/worker/packet_builder.h"
#include "app/worker/source_kind.h"
#include "app/main_window/virtual_keys.h"
#include "core/pipeline/data_out.h"
#include "core/pipeline/engine.h"
#include "core/pipeline/pose_stream.h"
#include "core/settings/settings.h"
#include "core/source/source.h"

class QTimer;

namespace imagepro::app {

class Worker : public QObject {
  Q_OBJECT

 public:
  explicit Worker(const Settings& settings, QObject* parent = nullptr);
  ~Worker() override;

  // Pending-slot updates, applied at the next frame boundary (or at once when idle,
  // reprocessing the current file frame).
  void setSettings(const Settings& settings);
  void pressKey(VirtualKey key);
  // The GUI has shown the last packet: the next frame may send another.
  void markDisplayed();

  // The source the Input Source panel selects. The one before stops and its results are
  // dropped (resultsCleared); the Virtual source is made at once, a camera only when it is
  // started. An open image list is kept aside and comes back, at the image it showed,
  // when File is selected again.
  void selectSource(SourceKind kind);
  // Starts (or resumes) a source. Virtual or Camera: frames at the source's rate. File: the
  // open image list plays on from the image shown to its last one (from its first when the
  // last is shown); a video plays on (from its start once it has ended).
  void start(SourceKind kind);
  // Opens the given images (files, folders or lists): the first image is processed and
  // shown, and stays, reprocessed whenever the settings change, until stepped or played
  // on. A video file plays at its own rate.
  void openFiles(const QStringList& paths);
  // Shows another image of the open list (a play in progress stops).
  void stepFile(FileStep step);
  void stop();
  // Data Out to `path`. `existing` says what to do with a file already there; with
  // `replace` (the user agreed) it is deleted first.
  void setDataOut(const QString& path, ExistingFile existing, bool replace = false);
  void closeDataOut();
  // Sets a camera control now: on the streaming camera when it streams from `device`,
  // else on the device directly. A refusal comes back as errorOccurred.
  void setCameraControl(const QString& device, const QString& key, qint64 value);
  // A copy of the frame last taken from the source (for File input, the still image shown),
  // answered with frameCaptured(request, ...): empty when there is none (nothing started or
  // opened yet, or a camera that was stopped and gave its buffers back).
  void captureFrame(quint64 request);

  // For tests and the status bar.
  Settings appliedSettings() const;
  bool isRunning() const { return running_.load(); }
  std::int64_t framesProcessed() const { return frames_processed_.load(); }

 signals:
  void packetReady(imagepro::app::DisplayPacketPtr packet);
  void runningChanged(bool running);
  void sourceChanged(const QString& description);
  void errorOccurred(const QString& message);
  void warningOccurred(const QString& message);  // the source goes on (a camera control not set)
  void dataOutChanged(const QString& path);  // empty when closed
  // The selected source has no frame to show (yet): `why` says what the user can do.
  void resultsCleared(const QString& why);
  // openFiles' `paths` opened as a list of `images` images (0 for a video), or could not be opened.
  void filesOpened(const QStringList& paths, int images);
  void filesFailed(const QStringList& paths);
  // One image of the open list could not be read (its whole path).
  void imageFailed(const QString& path);
  void frameCaptured(quint64 request, cv::Mat grey, QString source, bool running);

 private:
  // All below run in the worker thread.
  void doSelect(SourceKind kind);
  void doStart(SourceKind kind);
  void doOpenFiles(const QStringList& paths);
  void doStepFile(FileStep step);
  // The open image list, or null (no list: nothing open, a video, another source).
  ImageListSource* imageList() const;
  // Reads, processes and shows image `index` of the open list, the worker stopped.
  void showImage(int index);
  // Drops the shown frame and its results; the GUI is told why.
  void clearResults(const QString& why);
  void doStop();
  void doSetDataOut(const QString& path, ExistingFile existing, bool replace);
  void onIdleUpdate();
  void tick();
  void scheduleNext();
  bool applyPending();
  bool processFrame(bool from_source);  // false at the end of a stream
  void afterFrame();
  void publish();
  void setRunning(bool running);
  bool ensureSource(SourceKind kind, const QStringList& paths);
  void reportSourceError(Status status);
  // The selected source in words: its own description, or what is chosen but not open.
  QString description() const;
  // What the user can do to get frames from the selected source.
  QString waitingHint() const;
  // The engine reconstructs with the camera model of the source that runs (kind_).
  void useSourceCamera();
  // Opens, reopens or closes the live stream when its settings section changed.
  void applyStream(const StreamOptions& options);

  Engine engine_;
  std::unique_ptr<FrameSource> source_;
  SourceKind kind_ = SourceKind::Virtual;
  std::unique_ptr<FrameSource> parked_files_;  // the File input while another source is selected
  QStringList file_paths_;                     // what openFiles was given last (a video is opened anew)
  Frame file_frame_;           // the last file frame, reprocessed on option changes
  bool have_file_frame_ = false;
  bool file_ended_ = false;    // a video played to its end
  FrameResult result_;       // the last processed frame
  FrameResult step_result_;  // scratch for the next one
  bool have_result_ = false;
  DataOut data_out_;
  PoseStream stream_;
  QTimer* timer_ = nullptr;
  std::chrono::steady_clock::time_point next_due_{};

  // Rate and CPU meters.
  std::chrono::steady_clock::time_point last_frame_time_{};
  double frame_period_s_ = 0.0;
  std::chrono::steady_clock::time_point cpu_wall_mark_{};
  double cpu_time_mark_s_ = 0.0;
  double cpu_percent_ = 0.0;

  std::vector<PoseSample> history_;
  PacketWorkspace packet_ws_;
  bool display_dirty_ = false;
  std::chrono::steady_clock::time_point last_publish_{};

  std::atomic<bool> running_{false};
  std::atomic<bool> packet_in_flight_{false};
  std::atomic<std::int64_t> frames_processed_{0};

  mutable std::mutex pending_mutex_;
  std::optional<Settings> pending_settings_;
  std::vector<VirtualKey> pending_keys_;
  Settings applied_;  // copy of the engine's settings for appliedSettings()
};

}  // namespace imagepro::app

Q_DECLARE_METATYPE(cv::Mat)
