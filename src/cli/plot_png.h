#pragma once
// Line charts as PNG files for the study commands (tracking, pendulum), drawn with
// OpenCV so the CLI needs no GUI library: axes with ticks, a legend, one polyline
// (or a dot per point) per series.
#include <opencv2/core.hpp>

#include <string>
#include <vector>

namespace imagepro::cli {

struct PlotSeries {
  std::string name;
  cv::Scalar colour;  // BGR
  std::vector<double> x, y;
  bool dots = false;  // a dot at each point instead of a line through them (values per item)
};

struct Plot {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
};

// Writes the chart; false with `error` naming the file when it cannot be written.
bool writePlotPng(const std::string& path, const Plot& plot, std::string& error, cv::Size size = {900, 420});

}  // namespace imagepro::cli
