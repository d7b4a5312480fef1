#include "app/worker/packet_builder.h"

#include <QColor>

#include <cmath>

namespace imagepro::app {

QImage displayImage(const cv::Mat& grey) {
  if (grey.empty() || grey.type() != CV_8UC1) return {};
  // Converting here spares the GUI thread a conversion on every paint.
  return QImage(grey.data, grey.cols, grey.rows, static_cast<qsizetype>(grey.step), QImage::Format_Grayscale8)
      .convertToFormat(QImage::Format_RGB32);
}

namespace {

QRgb pathColour(std::size_t i) {
  // Golden-ratio hue steps: neighbouring paths get clearly different colours.
  const double turn = std::fmod(static_cast<double>(i) * 0.618033988749895, 1.0);
  return QColor::fromHsv(static_cast<int>(turn * 359.0), 230, 255).rgba();
}

// The part of `image` (whose top-left is at `origin` in the frame) under `region`.
QImage cropAt(const cv::Mat& image, cv::Point origin, cv::Rect region, QPoint& crop_origin) {
  if (image.empty()) return {};
  const cv::Rect local = (region - origin) & cv::Rect(0, 0, image.cols, image.rows);
  if (local.empty()) return {};
  crop_origin = QPoint(local.x + origin.x, local.y + origin.y);
  return displayImage(image(local));
}

}  // namespace

void buildPacket(const Engine& engine, const FrameResult& result, const PacketMeters& meters, PacketWorkspace& ws,
                 DisplayPacket& packet) {
  const Settings& settings = engine.settings();
  const DisplayOptions& display = settings.pipeline.display;
  packet.result = result;
  packet.display = display;
  packet.ellipse_method = settings.pipeline.ellipse.method;
  packet.hz = meters.hz;
  packet.cpu_percent = meters.cpu_percent;
  packet.source = meters.source;

  // After a failed grab the engine still holds the previous frame: show nothing of it.
  const Frame& frame = engine.lastFrame();
  if (frame.image.empty() || frame.index != result.index || frame.image.size() != result.image_size) return;

  // Stages after `reached` did not run on this frame: their buffers are not this frame's.
  const auto ran = [&](ApplicationLevel level) { return result.reached >= level; };
  static const cv::Mat kNone;
  const cv::Mat& binary = ran(ApplicationLevel::Threshold) ? engine.binaryImage() : kNone;
  const cv::Point binary_origin = result.search_region.tl();
  using Bg = DisplayOptions::Background;
  using Tg = DisplayOptions::Target;
  using Ed = DisplayOptions::Edges;

  if (display.background == Bg::Source) packet.background = displayImage(frame.image);
  if (display.background == Bg::Binary && binary.size() == result.search_region.size()) {
    packet.binary = displayImage(binary);
    packet.binary_origin = QPoint(binary_origin.x, binary_origin.y);
  }
  if (!result.detected_region.empty()) {
    if (display.target == Tg::Source)
      packet.target = cropAt(frame.image, {0, 0}, result.detected_region, packet.target_origin);
    else if (display.target == Tg::Binary && binary.size() == result.search_region.size())
      packet.target = cropAt(binary, binary_origin, result.detected_region, packet.target_origin);
  }
  static const EdgeList kNoEdges;
  static const Paths kNoPaths;
  const bool edges = display.edges == Ed::EdgePixels && ran(ApplicationLevel::Edges);
  const bool paths = display.edges == Ed::ConnectedPaths && ran(ApplicationLevel::Connectivity);
  if (edges || paths)
    packet.edge_overlay = edgeOverlay(result.image_size, edges ? engine.edges() : kNoEdges, paths ? engine.paths() : kNoPaths);
  if (display.calibration_check) {
    // The pattern plane's pose is its target's (thesis 4.6 step 3): without one, nothing to place.
    if (result.pose && ok(result.status))
      checkCalibrationView(settings, frame.image, *result.pose, ws.calibration, packet.calibration);
    else
      packet.calibration.status = ok(result.status) ? Status::NoTarget : result.status;
  }
}

QImage edgeOverlay(cv::Size size, const EdgeList& edges, const Paths& paths) {
  if (size.empty() || (edges.empty() && paths.pixels.empty())) return {};
  QImage overlay(size.width, size.height, QImage::Format_ARGB32_Premultiplied);
  overlay.fill(Qt::transparent);
  const auto put = [&](const EdgePixel& p, QRgb colour) {
    if (p.x >= 0 && p.y >= 0 && p.x < size.width && p.y < size.height)
      reinterpret_cast<QRgb*>(overlay.scanLine(p.y))[p.x] = colour;
  };
  const QRgb edge_colour = qRgb(255, 80, 80);
  for (const EdgePixel& p : edges) put(p, edge_colour);
  for (std::size_t i = 0; i < paths.pathCount(); ++i)
    for (const EdgePixel& p : paths.path(i)) put(p, pathColour(i));
  return overlay;
}

}  // namespace imagepro::app
