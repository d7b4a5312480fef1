// AnalysisWindow: collecting the live stream from the main window's worker.
#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QProgressBar>
#include <QTableWidget>
#include <QTimer>

#include "app/analysis/analysis_live.h"
#include "app/plots/analysis_plots.h"
#include "app/analysis/analysis_window.h"
#include "app/main_window/main_window.h"
#include "app/worker/worker.h"

namespace imagepro::app {

void AnalysisWindow::startCollecting() {
  collecting_ = true;
  collecting_study_ = study();
  live_samples_.clear();
  live_indices_.clear();
  live_last_index_ = -1;
  live_without_image_ = 0;
  if (collecting_study_ == AnalysisStudy::Pendulum) {
    pendulum_ = PendulumStudyResult{};
    pendulum_chart_->clear();
  } else {
    two_targets_ = TwoTargetStudyResult{};
    two_targets_.object = twoTargetParams().object;
    two_target_charts_->clear();
    live_two_ = std::make_unique<LiveTwoTargetAnalyser>(main_.settings());
  }
  summary_->clear();
  summary_->setRowCount(0);
  connect(main_.worker(), &Worker::packetReady, this, &AnalysisWindow::onLivePacket);
  setMessage(main_.worker()->isRunning() ? tr("Collecting the live stream...")
                                         : tr("Collecting: start the main window's source to send frames."),
             false);
  count_->setText(tr("0 frames collected"));
  progress_bar_->setRange(0, 1);
  progress_bar_->setValue(0);
  poll_->start();
  updateControls();
}

void AnalysisWindow::onLivePacket(const DisplayPacketPtr& packet) {
  if (!collecting_ || !packet) return;
  if (collecting_study_ == AnalysisStudy::Pendulum) {
    // The packet carries every frame processed since the previous one, displayed or not.
    for (const PoseSample& s : packet->history) {
      imagepro::PoseSample sample;
      sample.t_s = s.timestamp_s;
      sample.valid = ok(s.status) && s.pose.has_value();
      if (sample.valid) sample.pose = *s.pose;
      live_samples_.push_back(sample);
      live_indices_.push_back(s.index);
    }
    return;
  }
  if (packet->result.index == live_last_index_) return;  // the same still shown again
  live_last_index_ = packet->result.index;
  if (packet->background.isNull()) {
    ++live_without_image_;
    return;
  }
  live_two_->offer(packet->background, packet->result.index);
}

void AnalysisWindow::takeLiveTwoTargetFrames(bool redraw) {
  if (!live_two_) return;
  const std::size_t before = two_targets_.frames.size();
  live_two_->take(two_targets_.frames);
  if (two_targets_.frames.size() != before) live_dirty_ = true;
  QString text = tr("%1 frames measured").arg(two_targets_.frames.size());
  if (const std::int64_t skipped = live_two_->skipped()) text += tr(", %1 skipped (latest frame wins)").arg(skipped);
  if (live_without_image_ > 0) text += tr(", %1 without the source image").arg(live_without_image_);
  count_->setText(text);
  if (redraw && live_dirty_) {
    live_dirty_ = false;
    summariseTwoTargets(two_targets_);
    showTwoTargets();
  }
}

void AnalysisWindow::stopCollecting() {
  disconnect(main_.worker(), &Worker::packetReady, this, &AnalysisWindow::onLivePacket);
  collecting_ = false;
  poll_->stop();
  if (collecting_study_ == AnalysisStudy::TwoTargets) {
    live_two_->stop();  // after the frame in hand
    takeLiveTwoTargetFrames(false);
    live_two_.reset();
    summariseTwoTargets(two_targets_);
    if (live_without_image_ > 0 && two_targets_.frames.empty())
      two_targets_.error += " - the main window sent no source image: set its Display background to Source";
    showTwoTargets();
    updateControls();
    emit finished();
    return;
  }
  auto out = std::make_shared<PendulumStudyResult>();
  out->samples = std::move(live_samples_);
  out->options = pendulumOptions();
  retimeSamples(out->samples, live_indices_, rate_->value());
  live_samples_.clear();
  live_indices_.clear();
  count_->setText(tr("%1 frames collected").arg(out->samples.size()));
  setMessage(tr("Analysing..."), false);
  startTask([out] { analysePendulumSamples(*out); },
            [out, this] {
              pendulum_ = std::move(*out);
              showPendulum();
            });
}

}  // namespace imagepro::app
