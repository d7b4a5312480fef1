// Feature extraction, first step: the crop about the detected target and its own threshold.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/reconstruction/features.h"
#include "core/segmentation/threshold.h"

namespace imagepro {

namespace {

// Mean grey level of the classes [0, t] and [t+1, 255] of a histogram.
void classMeans(const Histogram& h, int t, double& dark, double& bright) {
  // Integer sums (exact, as the double sums of integers below 2^53 were), then one division.
  std::uint64_t n0 = 0, s0 = 0, n1 = 0, s1 = 0;
  const int split = std::clamp(t + 1, 0, 256);
  for (int g = 0; g < split; ++g) {
    n0 += h[g];
    s0 += static_cast<std::uint64_t>(g) * h[g];
  }
  for (int g = split; g < 256; ++g) {
    n1 += h[g];
    s1 += static_cast<std::uint64_t>(g) * h[g];
  }
  dark = n0 > 0 ? static_cast<double>(s0) / static_cast<double>(n0) : 0.0;
  bright = n1 > 0 ? static_cast<double>(s1) / static_cast<double>(n1) : 255.0;
}

}  // namespace

Status targetCrop(const Ellipse& e, int marginPx, cv::Size imageSize, cv::Rect& crop) {
  if (!(e.a > 0.0) || !(e.b > 0.0) || !std::isfinite(e.cx) || !std::isfinite(e.cy) ||
      !std::isfinite(e.a) || !std::isfinite(e.b) || !std::isfinite(e.angle_deg))
    return Status::OutOfImage;
  const double t = e.angle_deg * M_PI / 180.0;
  const double c = std::cos(t), s = std::sin(t);
  const double hx = std::sqrt(e.a * e.a * c * c + e.b * e.b * s * s);
  const double hy = std::sqrt(e.a * e.a * s * s + e.b * e.b * c * c);
  const double m = std::max(marginPx, 0);
  const double x0 = std::floor(e.cx - hx - m), x1 = std::ceil(e.cx + hx + m);
  const double y0 = std::floor(e.cy - hy - m), y1 = std::ceil(e.cy + hy + m);
  const double W = imageSize.width, H = imageSize.height;
  if (x1 < 0 || y1 < 0 || x0 >= W || y0 >= H) return Status::OutOfImage;
  const int ix0 = static_cast<int>(std::max(x0, 0.0)), iy0 = static_cast<int>(std::max(y0, 0.0));
  const int ix1 = static_cast<int>(std::min(x1, W - 1)), iy1 = static_cast<int>(std::min(y1, H - 1));
  crop = cv::Rect(ix0, iy0, ix1 - ix0 + 1, iy1 - iy0 + 1);
  return crop.area() > 0 ? Status::Ok : Status::OutOfImage;
}

Status rethresholdCrop(const cv::Mat& grey, const cv::Rect& crop, const ThresholdOptions& rethreshold,
                       int frameThreshold, FeatureWorkspace& ws, int& threshold, bool sampleRows) {
  if (grey.empty() || grey.type() != CV_8UC1) return Status::EmptyFrame;
  if ((crop & cv::Rect(0, 0, grey.cols, grey.rows)) != crop || crop.area() == 0)
    return Status::OutOfImage;
  // A near target's crop is large; its grey-level distribution, all the threshold and the
  // class means depend on, is the same on a regular subset of its rows: every k-th row,
  // at least kCropHistogramPixels pixels in all. (A view with a k times larger row step.)
  const int rowStep = sampleRows ? std::max(1, crop.area() / kCropHistogramPixels) : 1;
  const cv::Mat region = grey(crop);
  const cv::Mat sampled((crop.height + rowStep - 1) / rowStep, crop.width, CV_8UC1, region.data,
                        region.step[0] * static_cast<std::size_t>(rowStep));
  computeHistogram(sampled, ws.histogram);
  if (rethreshold.method == ThresholdMethod::None) {
    if (frameThreshold < 0 || frameThreshold > 255) return Status::InvalidSettings;
    threshold = frameThreshold;
  } else if (const Status s = computeThreshold(rethreshold, ws.histogram, threshold); !ok(s)) {
    return s;
  }
  ws.crop = crop;
  ws.threshold = threshold;
  classMeans(ws.histogram, threshold, ws.dark_mean, ws.bright_mean);
  return Status::Ok;
}

}  // namespace imagepro
