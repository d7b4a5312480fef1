#include "core/ellipse/synthetic_library.h"

#include <array>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

namespace imagepro {

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Row {
  double length, rotation, aspect;
};

// Table B.1, images 1-67.
constexpr std::array<Row, 67> kRectangles{{
    {30, 0, 1},  {30, 0, 2},  {30, 45, 2}, {30, 80, 2}, {50, 0, 1},  {50, 0, 2},  {50, 45, 2},
    {50, 80, 2}, {70, 0, 1},  {70, 0, 2},  {70, 10, 2}, {70, 30, 2}, {70, 40, 2}, {70, 45, 2},
    {70, 50, 2}, {70, 60, 2}, {70, 70, 2}, {70, 80, 2}, {70, 90, 2}, {70, 0, 3},  {70, 10, 3},
    {70, 20, 3}, {70, 30, 3}, {70, 40, 3}, {70, 50, 3}, {70, 60, 3}, {70, 70, 3}, {70, 80, 3},
    {70, 90, 3}, {70, 0, 4},  {70, 10, 4}, {70, 20, 4}, {70, 30, 4}, {70, 40, 4}, {70, 50, 4},
    {70, 60, 4}, {70, 70, 4}, {70, 80, 4}, {70, 90, 4}, {70, 0, 8},  {70, 10, 8}, {70, 20, 8},
    {70, 30, 8}, {70, 40, 8}, {70, 50, 8}, {70, 60, 8}, {70, 70, 8}, {70, 80, 8}, {70, 90, 8},
    {70, 0, 16}, {70, 10, 16}, {70, 20, 16}, {70, 30, 16}, {70, 40, 16}, {70, 50, 16},
    {70, 60, 16}, {70, 70, 16}, {70, 80, 16}, {70, 90, 16}, {90, 0, 1},  {90, 0, 2},
    {90, 45, 2}, {90, 80, 2}, {110, 0, 1}, {110, 0, 2}, {110, 45, 2}, {110, 80, 2},
}};

// Table B.2, images 1-70.
constexpr std::array<Row, 70> kEllipses{{
    {30, 0, 1},  {30, 0, 2},  {30, 10, 2}, {30, 10, 2}, {30, 45, 2}, {30, 80, 2}, {50, 0, 1},
    {50, 0, 2},  {50, 10, 2}, {50, 10, 2}, {50, 45, 2}, {50, 80, 2}, {70, 0, 1},  {70, 0, 2},
    {70, 10, 2}, {70, 45, 2}, {70, 80, 2}, {70, 0, 3},  {70, 10, 3}, {70, 20, 3}, {70, 30, 3},
    {70, 40, 3}, {70, 50, 3}, {70, 60, 3}, {70, 70, 3}, {70, 80, 3}, {70, 90, 3}, {70, 0, 4},
    {70, 10, 4}, {70, 20, 4}, {70, 30, 4}, {70, 40, 4}, {70, 50, 4}, {70, 60, 4}, {70, 70, 4},
    {70, 80, 4}, {70, 90, 4}, {70, 0, 5},  {70, 0, 8},  {70, 10, 8}, {70, 20, 8}, {70, 30, 8},
    {70, 40, 8}, {70, 50, 8}, {70, 60, 8}, {70, 70, 8}, {70, 80, 8}, {70, 90, 8}, {70, 0, 16},
    {70, 10, 16}, {70, 20, 16}, {70, 30, 16}, {70, 40, 16}, {70, 50, 16}, {70, 60, 16},
    {70, 70, 16}, {70, 80, 16}, {70, 90, 16}, {89, 0, 2},  {90, 0, 1},  {90, 10, 2},
    {90, 10, 2}, {90, 45, 2}, {90, 80, 2}, {110, 0, 1}, {110, 0, 2}, {110, 10, 2},
    {110, 10, 2}, {110, 45, 2}, {110, 80, 2},
}};

std::array<LibraryEntry, kRectangles.size() + kEllipses.size()> buildLibrary() {
  std::array<LibraryEntry, kRectangles.size() + kEllipses.size()> lib{};
  std::size_t k = 0;
  for (std::size_t i = 0; i < kRectangles.size(); ++i, ++k)
    lib[k] = {LibraryShape::Rectangle, static_cast<int>(i + 1), kRectangles[i].length,
              kRectangles[i].rotation, kRectangles[i].aspect};
  for (std::size_t i = 0; i < kEllipses.size(); ++i, ++k)
    lib[k] = {LibraryShape::Ellipse, static_cast<int>(i + 1), kEllipses[i].length,
              kEllipses[i].rotation, kEllipses[i].aspect};
  return lib;
}

const auto kLibrary = buildLibrary();

}  // namespace

Ellipse LibraryEntry::ellipse(cv::Size image) const {
  return {0.5 * (image.width - 1), 0.5 * (image.height - 1), semiMajor(), semiMinor(), rotation_deg};
}

std::span<const LibraryEntry> syntheticLibrary() { return kLibrary; }

namespace {

// Whether the point (dx, dy) relative to the shape's centre lies inside the shape.
struct ShapeTest {
  LibraryShape shape;
  double cs, sn, ha, hb;
  explicit ShapeTest(const LibraryEntry& e)
      : shape(e.shape),
        cs(std::cos(e.rotation_deg * kPi / 180.0)),
        sn(std::sin(e.rotation_deg * kPi / 180.0)),
        ha(e.semiMajor()),
        hb(e.semiMinor()) {}
  bool inside(double dx, double dy) const {
    // A tiny tolerance keeps points exactly on the boundary inside whatever the rounding
    // of cos/sin; negating (dx, dy) negates both projections exactly, so the image stays
    // point-symmetric about the centre.
    constexpr double eps = 1e-9;
    const double along = dx * cs + dy * sn;    // along the long axis
    const double across = -dx * sn + dy * cs;  // along the short axis
    if (shape == LibraryShape::Rectangle) return std::abs(along) <= ha + eps && std::abs(across) <= hb + eps;
    return (along * along) / (ha * ha) + (across * across) / (hb * hb) <= 1.0 + eps;
  }
  int reach() const { return static_cast<int>(std::ceil(std::hypot(ha, hb))) + 2; }
};

}  // namespace

void renderLibraryImage(const LibraryEntry& entry, cv::Mat& out, cv::Size size) {
  out.create(size, CV_8UC1);
  out.setTo(0);
  const double cx = 0.5 * (size.width - 1), cy = 0.5 * (size.height - 1);
  const ShapeTest shape(entry);
  const int reach = shape.reach();
  const int y0 = std::max(0, static_cast<int>(cy) - reach), y1 = std::min(size.height - 1, static_cast<int>(cy) + reach + 1);
  const int x0 = std::max(0, static_cast<int>(cx) - reach), x1 = std::min(size.width - 1, static_cast<int>(cx) + reach + 1);
  for (int y = y0; y <= y1; ++y) {
    unsigned char* row = out.ptr<unsigned char>(y);
    for (int x = x0; x <= x1; ++x)
      if (shape.inside(x - cx, y - cy)) row[x] = 255;
  }
}

void renderLibraryImageGrey(const LibraryEntry& entry, const LibraryGreyOptions& o, cv::Mat& out, cv::Size size) {
  const int ss = std::max(1, o.supersampling);
  cv::Mat coverage(size, CV_32FC1, cv::Scalar(0.0f));
  const double cx = 0.5 * (size.width - 1), cy = 0.5 * (size.height - 1);
  const ShapeTest shape(entry);
  const int reach = shape.reach();
  const int y0 = std::max(0, static_cast<int>(cy) - reach), y1 = std::min(size.height - 1, static_cast<int>(cy) + reach + 1);
  const int x0 = std::max(0, static_cast<int>(cx) - reach), x1 = std::min(size.width - 1, static_cast<int>(cx) + reach + 1);
  for (int y = y0; y <= y1; ++y) {
    float* row = coverage.ptr<float>(y);
    for (int x = x0; x <= x1; ++x) {
      int hits = 0;
      for (int j = 0; j < ss; ++j)
        for (int i = 0; i < ss; ++i)
          hits += shape.inside(x - cx + (i + 0.5) / ss - 0.5, y - cy + (j + 0.5) / ss - 0.5);
      row[x] = static_cast<float>(hits) / static_cast<float>(ss * ss);
    }
  }
  cv::Mat grey = coverage * (o.white_level - o.black_level) + o.black_level;
  if (o.blur_sigma_px > 0.0) cv::GaussianBlur(grey, grey, cv::Size(), o.blur_sigma_px);
  if (o.noise_sigma > 0.0) {
    cv::Mat noise(size, CV_32FC1);
    cv::RNG rng(o.seed);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, o.noise_sigma);
    grey += noise;
  }
  grey.convertTo(out, CV_8UC1);  // rounds and saturates to 0..255
}

std::string libraryFileName(const LibraryEntry& entry) {
  char name[32];
  std::snprintf(name, sizeof name, "%s_%02d.png",
                entry.shape == LibraryShape::Rectangle ? "rectangle" : "ellipse", entry.number);
  return name;
}

}  // namespace imagepro
