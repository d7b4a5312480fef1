#pragma once
// Views of the printable dot grids (pattern_document.h's pages) for the full intrinsic
// calibration's tests: the page drawn as PNG, photographed (sheet_photo.h) by a camera of
// known intrinsics and lens from tilts up to 60 deg, optionally under uneven light.
#include <opencv2/imgcodecs.hpp>

#include <string>
#include <vector>

#include "core/calibration/dot_grid.h"
#include "core/calibration/pattern_document.h"
#include "sheet_photo.h"

namespace imagepro::testing {

inline DotGridSpec gridSpec(DotGridKind kind, int columns, int rows, double spacing_mm, double dot_diameter_mm) {
  DotGridSpec s;
  s.kind = kind;
  s.columns = columns;
  s.rows = rows;
  s.spacing_mm = spacing_mm;
  s.dot_diameter_mm = dot_diameter_mm;
  return s;
}

// A 640x480 camera, fx = fy = 800 px, principal point off the image centre.
inline CameraModel intrinsicTruthCamera(const Distortion& lens) {
  CameraModel c;
  c.principal_point_px = {324.3, 236.8};
  c.distortion = lens;
  return c;
}

// A webcam's strong barrel distortion: OpenCV's k1 = -0.28, k2 = 0.1 at f = 800 px (the
// corners move by about 25 px).
inline constexpr Distortion kWebcamLens{-0.28 / (800.0 * 800.0), 0.1 / (800.0 * 800.0 * 800.0 * 800.0), 0.0, 0.0};

struct GridView {
  double rx_deg, ry_deg, rz_deg;
  double cx_mm, cy_mm, z_mm;  // where the grid's middle lies in the camera frame
};

// Ten views: face on, tilted 30-60 deg about x, y and both, the grid moved towards the
// image's sides and corners; `distance_mm` is the face-on distance.
inline std::vector<GridView> intrinsicViews(double distance_mm) {
  const double z = distance_mm, e = 0.13 * z, f = 0.1 * z;
  return {{0, 0, 0, 0, 0, z},
          {35, 0, 5, 0, -0.06 * z, z},
          {-45, 0, -5, 0, 0.06 * z, z},
          {0, 40, 10, -0.1 * z, 0, z},
          {0, -50, -10, 0.1 * z, 0, z},
          {60, 0, 0, 0, 0, 0.9 * z},
          {25, 25, 15, -e, -f, 1.15 * z},
          {-25, 25, -15, -e, f, 1.15 * z},
          {25, -25, -15, e, -f, 1.15 * z},
          {-25, -25, 15, e, f, 1.15 * z}};
}

struct RenderedGrid {
  std::vector<cv::Mat> images;
  PatternPage page;
};

inline bool renderGridViews(const DotGridSpec& spec, Paper paper, const CameraModel& camera,
                            const std::vector<GridView>& views, PhotoConditions conditions, RenderedGrid& out,
                            std::string& error, double dpi = 200.0) {
  out = {};
  if (!layoutDotGridPage(spec, paper, out.page, error)) return false;
  const cv::Mat sheet = cv::imdecode(patternPagePng(out.page, dpi), cv::IMREAD_GRAYSCALE);
  const double pxPerMm = dpi / 25.4;
  const SheetFrame frame{out.page.origin_x_mm * pxPerMm - 0.5, out.page.origin_y_mm * pxPerMm - 0.5, pxPerMm};
  // The grid's middle on the pattern's plane.
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const PageCircle& c : out.page.circles) {
    if (!c.black) continue;
    lo = lo.cwiseMin(Eigen::Vector2d(c.x_mm, c.y_mm));
    hi = hi.cwiseMax(Eigen::Vector2d(c.x_mm, c.y_mm));
  }
  const Eigen::Vector3d middle(0.5 * (lo.x() + hi.x()) - out.page.origin_x_mm,
                               0.5 * (lo.y() + hi.y()) - out.page.origin_y_mm, 0.0);
  for (const GridView& v : views) {
    Pose p;
    p.rx_deg = v.rx_deg;
    p.ry_deg = v.ry_deg;
    p.rz_deg = v.rz_deg;
    const Eigen::Vector3d T = Eigen::Vector3d(v.cx_mm, v.cy_mm, v.z_mm) - rotationMatrix(p) * middle;
    p.tx_mm = T.x();
    p.ty_mm = T.y();
    p.tz_mm = T.z();
    out.images.push_back(photograph(sheet, frame, camera, p, conditions));
    ++conditions.seed;
  }
  return true;
}

}  // namespace imagepro::testing
