#include "app/packet_builder.h"

namespace imagepro::app {

QImage greyImage(const cv::Mat& grey) {
  if (grey.empty() || grey.type() != CV_8UC1) return {};
  return QImage(grey.data, grey.cols, grey.rows, static_cast<qsizetype>(grey.step), QImage::Format_Grayscale8)
      .copy();
}

namespace {

// The part of `image` (whose top-left is at `origin` in the frame) under `region`.
QImage cropAt(const cv::Mat& image, cv::Point origin, cv::Rect region, QPoint& crop_origin) {
  if (image.empty()) return {};
  const cv::Rect local = (region - origin) & cv::Rect(0, 0, image.cols, image.rows);
  if (local.empty()) return {};
  crop_origin = QPoint(local.x + origin.x, local.y + origin.y);
  return greyImage(image(local));
}

}  // namespace

void buildPacket(const Engine& engine, const FrameResult& result, const PacketMeters& meters,
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

  if (display.background == Bg::Source) packet.background = greyImage(frame.image);
  if (display.background == Bg::Binary && binary.size() == result.search_region.size()) {
    packet.binary = greyImage(binary);
    packet.binary_origin = QPoint(binary_origin.x, binary_origin.y);
  }
  if (!result.detected_region.empty()) {
    if (display.target == Tg::Source)
      packet.target = cropAt(frame.image, {0, 0}, result.detected_region, packet.target_origin);
    else if (display.target == Tg::Binary && binary.size() == result.search_region.size())
      packet.target = cropAt(binary, binary_origin, result.detected_region, packet.target_origin);
  }
  if (display.edges == Ed::EdgePixels && ran(ApplicationLevel::Edges)) packet.edges = engine.edges();
  if (display.edges == Ed::ConnectedPaths && ran(ApplicationLevel::Connectivity)) packet.paths = engine.paths();
}

}  // namespace imagepro::app
