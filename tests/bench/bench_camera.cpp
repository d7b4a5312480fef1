// Camera frames to grey (thesis 2.2, 5.2.1: one 640 x 480 frame every 40 ms at 25
// frames/s): what each V4L2 pixel format costs per frame, one core. The frame is the
// Virtual source's grey target, packed into each format with a padded line stride
// as a driver delivers it; Motion-JPEG at quality 80, as UVC cameras send it.
//   build/tests/bench/bench_camera --benchmark_min_time=0.5
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "core/camera/pixel_format.h"
#include "core/source/virtual_renderer.h"

namespace imagepro {
namespace {

const cv::Mat& sceneGrey() {
  static const cv::Mat grey = [] {
    cv::setNumThreads(1);
    VirtualSceneOptions scene;
    scene.mode = RenderMode::Grey;
    scene.clutter = 6;
    scene.noise_sigma = 2.0;
    cv::Mat out;
    renderTarget(CameraModel{}, TargetGeometry{}, scene, Pose{10, -15, 30, 40, -20, 900}, out, 1);
    return out;
  }();
  return grey;
}

struct Captured {
  BufferLayout layout;
  std::vector<std::uint8_t> bytes;
};

Captured capture(PixelFormat format) {
  const cv::Mat& g = sceneGrey();
  Captured c;
  if (format == PixelFormat::Mjpeg) {
    cv::imencode(".jpg", g, c.bytes, {cv::IMWRITE_JPEG_QUALITY, 80});
    c.layout = {format, g.cols, g.rows, 0};
    return c;
  }
  const std::size_t bpl = minimumBytesPerLine(format, g.cols) + 64;
  c.layout = {format, g.cols, g.rows, bpl};
  c.bytes.assign(bpl * static_cast<std::size_t>(g.rows) * 2, 0x80);
  const std::size_t per_pixel = minimumBytesPerLine(format, 1);
  const std::size_t luma_at = format == PixelFormat::Uyvy ? 1 : 0;
  for (int y = 0; y < g.rows; ++y)
    for (int x = 0; x < g.cols; ++x) {
      std::uint8_t* p = c.bytes.data() + static_cast<std::size_t>(y) * bpl + static_cast<std::size_t>(x) * per_pixel;
      const std::uint8_t v = g.at<std::uint8_t>(y, x);
      if (per_pixel == 3)
        p[0] = p[1] = p[2] = v;
      else
        p[luma_at] = v;
    }
  return c;
}

void BM_BufferToGrey(benchmark::State& state) {
  const auto format = static_cast<PixelFormat>(state.range(0));
  const Captured c = capture(format);
  cv::Mat scratch, grey;
  std::string error;
  for (auto _ : state) {
    const Status s = bufferToGrey(c.layout, c.bytes.data(), c.bytes.size(), scratch, grey, error);
    benchmark::DoNotOptimize(s);
    benchmark::DoNotOptimize(grey.data);
  }
  state.SetLabel(std::string(pixelFormatName(format)));
}
BENCHMARK(BM_BufferToGrey)
    ->Arg(static_cast<int>(PixelFormat::Grey))
    ->Arg(static_cast<int>(PixelFormat::Nv12))
    ->Arg(static_cast<int>(PixelFormat::Yuyv))
    ->Arg(static_cast<int>(PixelFormat::Uyvy))
    ->Arg(static_cast<int>(PixelFormat::Rgb24))
    ->Arg(static_cast<int>(PixelFormat::Mjpeg))
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace imagepro

BENCHMARK_MAIN();
