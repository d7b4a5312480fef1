#pragma once
// Fills a DisplayPacket from the engine's last frame: the frame result plus copies
// of only what the current display options draw (source, binary, target crop,
// edge pixels or paths), already converted for painting, and with the calibration box
// ticked the live calibration check of the frame. Runs in the worker thread.
#include <QString>

#include "app/worker/display_packet.h"
#include "core/connectivity/paths.h"
#include "core/edges/edge_list.h"
#include "core/pipeline/engine.h"

namespace imagepro::app {

struct PacketMeters {
  double hz = 0.0;
  double cpu_percent = 0.0;
  QString source;
};

// What building packets keeps from one to the next (the worker thread's own).
struct PacketWorkspace {
  CalibrationCheckWorkspace calibration;
};

void buildPacket(const Engine& engine, const FrameResult& result, const PacketMeters& meters, PacketWorkspace& ws,
                 DisplayPacket& packet);

// A CV_8UC1 image as an RGB32 QImage of its own (empty for an empty or non-grey Mat).
QImage displayImage(const cv::Mat& grey);
// Frame-sized ARGB overlay: edge pixels in one colour, or each connected path in its own.
QImage edgeOverlay(cv::Size size, const EdgeList& edges, const Paths& paths);

}  // namespace imagepro::app
