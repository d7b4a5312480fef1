#pragma once
// Fills a DisplayPacket from the engine's last frame: the frame result plus copies
// of only what the current display options draw (source, binary, target crop,
// edge pixels or paths). Runs in the worker thread.
#include <QString>

#include "app/display_packet.h"
#include "core/pipeline/engine.h"

namespace imagepro::app {

struct PacketMeters {
  double hz = 0.0;
  double cpu_percent = 0.0;
  QString source;
};

void buildPacket(const Engine& engine, const FrameResult& result, const PacketMeters& meters,
                 DisplayPacket& packet);

// A deep copy of a CV_8UC1 image (empty QImage for an empty or non-grey Mat).
QImage greyImage(const cv::Mat& grey);

}  // namespace imagepro::app
