#include "cli/bennett_accumulators.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace imagepro::cli {

namespace {

// The side the enlarged accumulator of one path is brought to, and the largest enlargement.
constexpr int kShownSide = 320;
constexpr int kMaxEnlargement = 8;

// The accumulator of ws (votes, box-sized) scaled to its peak: 8-bit grey.
cv::Mat scaledToPeak(const BennettWorkspace& ws, std::uint32_t peak) {
  cv::Mat out(ws.box.height, ws.box.width, CV_8UC1);
  const double scale = peak > 0 ? 255.0 / peak : 0.0;
  for (int y = 0; y < ws.box.height; ++y) {
    const std::uint32_t* row = ws.accumulator.data() + static_cast<std::size_t>(y) * ws.box.width;
    for (int x = 0; x < ws.box.width; ++x) out.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(row[x] * scale);
  }
  return out;
}

// The first cell of the highest count (as bennettAccumulate takes it): its column and row.
cv::Point peakCell(const BennettWorkspace& ws, std::uint32_t& peak) {
  const auto best = std::max_element(ws.accumulator.begin(), ws.accumulator.end());
  peak = *best;
  const auto i = static_cast<int>(best - ws.accumulator.begin());
  return {i % ws.box.width, i / ws.box.width};
}

cv::Mat annotated(const cv::Mat& grey, cv::Point peak, const BennettWorkspace& ws, const BennettResult& r) {
  const int f = std::clamp(kShownSide / std::max(grey.cols, grey.rows), 1, kMaxEnlargement);
  cv::Mat big, out;
  cv::resize(grey, big, {}, f, f, cv::INTER_NEAREST);
  cv::cvtColor(big, out, cv::COLOR_GRAY2BGR);
  auto at = [f](double cx, double cy) {  // a cell position to the enlarged picture's pixel
    return cv::Point(static_cast<int>(std::lround((cx + 0.5) * f)), static_cast<int>(std::lround((cy + 0.5) * f)));
  };
  const cv::Point p = at(peak.x, peak.y);
  cv::circle(out, p, std::max(1, static_cast<int>(std::lround(r.half_radius_px * f))), cv::Scalar(255, 60, 0), 1,
             cv::LINE_AA);
  if (r.symmetry_px <= r.border_distance_px)
    cv::circle(out, p, static_cast<int>(std::lround(r.symmetry_px * f)), cv::Scalar(0, 140, 255), 1, cv::LINE_AA);
  cv::circle(out, at(r.cx - ws.box.x0, r.cy - ws.box.y0), std::max(2, f / 2), cv::Scalar(0, 0, 255), cv::FILLED);
  return out;
}

}  // namespace

void drawBennettAccumulators(const EllipseOptions& options, const Paths& paths, cv::Size image, EllipseWorkspace& ws,
                             BennettAccumulators& out) {
  out.all = cv::Mat::zeros(image, CV_8UC1);
  out.shown.clear();
  EllipseOptions bennett = options;
  bennett.method = EllipseMethod::Bennett;
  std::vector<TargetDetection> accepted;
  if (paths.pathCount() > 0) detectEllipses(bennett, paths, image, ws, accepted);
  auto isAccepted = [&](std::size_t i) {
    return std::any_of(accepted.begin(), accepted.end(), [i](const TargetDetection& d) { return d.path_index == i; });
  };

  const std::size_t min_pixels = static_cast<std::size_t>(std::max(options.min_path_pixels, 6));
  BennettWorkspace acc;
  PathAccumulator best;
  bool have_best = false;
  for (std::size_t i = 0; i < paths.pathCount(); ++i) {
    const auto path = paths.path(i);
    if (path.size() < min_pixels) continue;
    BennettResult r;
    if (!ok(bennettAccumulate(path, options.bennett_max_points, acc, r))) continue;
    std::uint32_t peak = 0;
    const cv::Point cell = peakCell(acc, peak);
    const cv::Mat grey = scaledToPeak(acc, peak);
    // The box may reach past the image by its margin: only the part inside is drawn.
    const cv::Rect box(acc.box.x0, acc.box.y0, acc.box.width, acc.box.height);
    const cv::Rect inside = box & cv::Rect({0, 0}, image);
    if (!inside.empty()) {
      cv::Mat dst = out.all(inside);
      cv::max(dst, grey(inside - box.tl()), dst);
    }
    const bool pass = isAccepted(i);
    if (pass) out.shown.push_back({i, true, r, annotated(grey, cell, acc, r)});
    if (!pass && (!have_best || r.score > best.result.score)) {
      best = {i, false, r, {}};
      best.image = annotated(grey, cell, acc, r);
      have_best = true;
    }
  }
  if (out.shown.empty() && have_best) out.shown.push_back(std::move(best));
}

}  // namespace imagepro::cli
