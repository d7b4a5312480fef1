#include "cli/plot_png.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace imagepro::cli {

namespace {

// A "nice" tick step (1, 2 or 5 times a power of ten) giving about `count` ticks.
double tickStep(double span, int count) {
  const double raw = span / std::max(1, count);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10.0 * p;
}

std::string label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

}  // namespace

bool writePlotPng(const std::string& path, const Plot& plot, std::string& error, cv::Size size) {
  cv::Mat img(size, CV_8UC3, cv::Scalar(255, 255, 255));
  const int left = 70, right = 20, top = 52, bottom = 50;
  const cv::Rect area(left, top, size.width - left - right, size.height - top - bottom);

  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;  // y1 may grow for the legend
  for (const auto& s : plot.series)
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      x0 = std::min(x0, s.x[i]);
      x1 = std::max(x1, s.x[i]);
      y0 = std::min(y0, s.y[i]);
      y1 = std::max(y1, s.y[i]);
    }
  if (x0 > x1) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  if (x1 - x0 < 1e-12) x1 = x0 + 1;
  if (y1 - y0 < 1e-12) y0 -= 0.5, y1 += 0.5;
  const double pad = 0.05 * (y1 - y0);
  y0 -= pad;
  y1 += pad;
  auto px = [&](double x, double y) {
    return cv::Point(area.x + static_cast<int>(std::lround((x - x0) / (x1 - x0) * area.width)),
                     area.y + area.height - static_cast<int>(std::lround((y - y0) / (y1 - y0) * area.height)));
  };

  // The series in their colours, or all in white on a mask.
  auto drawSeries = [&](cv::Mat& target, bool mask) {
    for (const PlotSeries& s : plot.series) {
      std::vector<cv::Point> pts;
      for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
        if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) pts.push_back(px(s.x[i], s.y[i]));
      const cv::Scalar colour = mask ? cv::Scalar(255) : s.colour;
      if (s.dots)
        for (const cv::Point& p : pts) cv::circle(target, p, 3, colour, cv::FILLED, cv::LINE_AA);
      else if (pts.size() >= 2)
        cv::polylines(target, pts, false, colour, 1, cv::LINE_AA);
    }
  };

  // The legend, on white, in the corner of the plot area where it covers none of the
  // series (top right first); where every corner would, the y range grows at the top to
  // leave a band for it.
  const cv::Size legend(178, 18 * static_cast<int>(plot.series.size()) + 6);
  const int inset = 4;
  const cv::Point corners[4] = {{area.br().x - legend.width - inset, area.y + inset},
                                {area.x + inset, area.y + inset},
                                {area.br().x - legend.width - inset, area.br().y - legend.height - inset},
                                {area.x + inset, area.br().y - legend.height - inset}};
  cv::Rect box(corners[0], legend);
  if (!plot.series.empty()) {
    cv::Mat covered = cv::Mat::zeros(size, CV_8UC1);
    drawSeries(covered, true);
    bool free = false;
    for (const cv::Point& corner : corners)
      if (cv::countNonZero(covered(cv::Rect(corner, legend) & cv::Rect({0, 0}, size))) == 0) {
        box = cv::Rect(corner, legend);
        free = true;
        break;
      }
    const int band = legend.height + 2 * inset;
    if (!free && band < area.height / 2) y1 += (y1 - y0) * band / (area.height - band);
  }

  const cv::Scalar grid(225, 225, 225), ink(40, 40, 40);
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  const double xs = tickStep(x1 - x0, 8), ys = tickStep(y1 - y0, 6);
  for (double x = std::ceil(x0 / xs) * xs; x <= x1 + 1e-9; x += xs) {
    cv::line(img, px(x, y0), px(x, y1), grid, 1);
    cv::putText(img, label(x), px(x, y0) + cv::Point(-10, 18), font, 0.4, ink, 1, cv::LINE_AA);
  }
  for (double y = std::ceil(y0 / ys) * ys; y <= y1 + 1e-9; y += ys) {
    cv::line(img, px(x0, y), px(x1, y), grid, 1);
    cv::putText(img, label(y), px(x0, y) + cv::Point(-60, 4), font, 0.4, ink, 1, cv::LINE_AA);
  }
  cv::rectangle(img, area, ink, 1);
  cv::putText(img, plot.title, {left, 20}, font, 0.55, ink, 1, cv::LINE_AA);
  cv::putText(img, plot.x_label, {area.x + area.width / 2 - 40, size.height - 12}, font, 0.45, ink, 1, cv::LINE_AA);
  cv::putText(img, plot.y_label, {8, top - 8}, font, 0.45, ink, 1, cv::LINE_AA);
  drawSeries(img, false);

  if (!plot.series.empty()) {
    cv::rectangle(img, box, cv::Scalar(255, 255, 255), cv::FILLED);
    cv::rectangle(img, box, grid, 1);
  }
  int legend_y = box.y + 18;
  for (const PlotSeries& s : plot.series) {
    if (s.dots)
      cv::circle(img, {box.x + 21, legend_y - 4}, 3, s.colour, cv::FILLED, cv::LINE_AA);
    else
      cv::line(img, {box.x + 8, legend_y - 4}, {box.x + 33, legend_y - 4}, s.colour, 2);
    cv::putText(img, s.name, {box.x + 38, legend_y}, font, 0.42, ink, 1, cv::LINE_AA);
    legend_y += 18;
  }
  try {
    if (cv::imwrite(path, img)) return true;
    error = path + ": cannot write the PNG";
  } catch (const cv::Exception& e) {
    error = path + ": " + e.what();
  }
  return false;
}

}  // namespace imagepro::cli
