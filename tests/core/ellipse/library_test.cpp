// The synthetic image library of thesis appendix B and the classification of thesis
// 2.6: direct fit every ellipse and no rectangle; Bennett at least as good as the
// thesis's 9 missed ellipses and 7 accepted rectangles; the grey, blurred and noisy
// versions at the levels docs/ellipse-detection.md reports.
#include "core/ellipse/synthetic_library.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scenes.h"

namespace imagepro {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(SyntheticLibrary, TablesB1AndB2) {
  const auto lib = syntheticLibrary();
  ASSERT_EQ(lib.size(), 137u);
  int rectangles = 0, ellipses = 0;
  for (const auto& e : lib) (e.shape == LibraryShape::Rectangle ? rectangles : ellipses)++;
  EXPECT_EQ(rectangles, 67);
  EXPECT_EQ(ellipses, 70);
  const LibraryEntry& r35 = lib[34];
  EXPECT_EQ(r35.shape, LibraryShape::Rectangle);
  EXPECT_EQ(r35.number, 35);
  EXPECT_EQ(r35.length_px, 70);
  EXPECT_EQ(r35.rotation_deg, 50);
  EXPECT_EQ(r35.aspect, 4);
  const LibraryEntry& e59 = lib[67 + 58];
  EXPECT_EQ(e59.shape, LibraryShape::Ellipse);
  EXPECT_EQ(e59.number, 59);
  EXPECT_EQ(e59.length_px, 89);
  EXPECT_EQ(e59.aspect, 2);
  EXPECT_EQ(lib.back().number, 70);
  EXPECT_EQ(lib.back().rotation_deg, 80);
  EXPECT_EQ(libraryFileName(lib[0]), "rectangle_01.png");
  EXPECT_EQ(libraryFileName(lib.back()), "ellipse_70.png");
}

TEST(SyntheticLibrary, ImagesAreExactCentredShapes) {
  cv::Mat img;
  for (const auto& e : syntheticLibrary()) {
    renderLibraryImage(e, img);
    ASSERT_EQ(img.size(), cv::Size(640, 480));
    ASSERT_EQ(img.type(), CV_8UC1);
    // Binary, point-symmetric about the image centre.
    cv::Mat flipped;
    cv::flip(img, flipped, -1);
    EXPECT_EQ(cv::countNonZero(img != flipped), 0) << libraryFileName(e);
    EXPECT_EQ(cv::countNonZero((img != 0) & (img != 255)), 0);
    // The white area matches the shape's area to within its boundary pixels.
    const double a = e.semiMajor(), b = e.semiMinor();
    const double area = e.shape == LibraryShape::Rectangle ? 4 * a * b : kPi * a * b;
    const double perimeter = e.shape == LibraryShape::Rectangle ? 4 * (a + b) : 2 * kPi * std::sqrt(0.5 * (a * a + b * b));
    EXPECT_NEAR(cv::countNonZero(img), area, 0.5 * perimeter) << libraryFileName(e);
  }
}

// The classification as `imagepro-cli detect` makes it with the default settings (or
// a manual threshold): threshold (AT-Mod unless `threshold` >= 0), Laplace edges, CN1
// paths, detectTarget; an image counts as an ellipse when the status is Ok.
struct Tally {
  int ellipses_missed = 0, rectangles_accepted = 0;
  std::vector<int> missed, accepted;  // the images' numbers in their tables
  // Worst values of the largest path's direct fit and trace over the library: the
  // ellipses' largest errors and smallest traced share, the rectangles' smallest errors
  // and largest traced share.
  double ellipse_erel = 0.0, ellipse_sampson = 0.0, ellipse_traced = 1.0;
  double rectangle_erel = 1e9, rectangle_sampson = 1e9, rectangle_traced = 0.0;
};

void addLargestPath(const LibraryEntry& e, const Paths& paths, cv::Size image, double inlier_px, Tally& t) {
  std::size_t largest = 0;
  for (std::size_t i = 1; i < paths.pathCount(); ++i)
    if (paths.path(i).size() > paths.path(largest).size()) largest = i;
  EllipseFit fit;
  EllipseTrace trace;
  if (paths.pathCount() == 0 || !ok(fitEllipseDirect(paths.path(largest), fit))) return;
  traceEllipse(fit, paths.path(largest), inlier_px, image, trace);
  if (e.shape == LibraryShape::Ellipse) {
    t.ellipse_erel = std::max(t.ellipse_erel, fit.relative_error);
    t.ellipse_sampson = std::max(t.ellipse_sampson, fit.sampson_px);
    t.ellipse_traced = std::min(t.ellipse_traced, trace.traced);
  } else {
    t.rectangle_erel = std::min(t.rectangle_erel, fit.relative_error);
    t.rectangle_sampson = std::min(t.rectangle_sampson, fit.sampson_px);
    t.rectangle_traced = std::max(t.rectangle_traced, trace.traced);
  }
}

Tally classify(const EllipseOptions& o, const LibraryGreyOptions* grey, int threshold = -1) {
  Tally t;
  test::PathPipeline p;
  EllipseWorkspace ws;
  std::vector<TargetDetection> found;
  cv::Mat img;
  for (const auto& e : syntheticLibrary()) {
    if (grey) renderLibraryImageGrey(e, *grey, img);
    else renderLibraryImage(e, img);
    EXPECT_EQ(p.run(img, threshold), Status::Ok);
    const bool accepted = ok(detectTarget(o, TargetGeometry{}, p.paths, img.size(), ws, found));
    addLargestPath(e, p.paths, img.size(), o.trace_inlier_px, t);
    if (e.shape == LibraryShape::Ellipse && !accepted) ++t.ellipses_missed, t.missed.push_back(e.number);
    if (e.shape == LibraryShape::Rectangle && accepted) ++t.rectangles_accepted, t.accepted.push_back(e.number);
    if (e.shape == LibraryShape::Ellipse && accepted && o.method == EllipseMethod::DirectFit && e.aspect <= 4 &&
        !grey) {
      // The fit follows the edge pixels, the white pixels just inside the boundary.
      const Ellipse truth = e.ellipse(img.size());
      const Ellipse& got = found[0].ellipse;
      EXPECT_NEAR(got.cx, truth.cx, 0.25) << libraryFileName(e);
      EXPECT_NEAR(got.cy, truth.cy, 0.25) << libraryFileName(e);
      EXPECT_NEAR(got.a, truth.a - 0.5, 0.8) << libraryFileName(e);
      EXPECT_NEAR(got.b, truth.b - 0.5, 0.8) << libraryFileName(e);
      if (e.aspect > 1) {
        EXPECT_NEAR(test::angleDiffDeg(got.angle_deg, truth.angle_deg), 0.0, 2.0) << libraryFileName(e);
      }
    }
  }
  return t;
}

std::string numbers(const std::vector<int>& v) {
  std::string s;
  for (const int n : v) s += (s.empty() ? "" : " ") + std::to_string(n);
  return s;
}

// The library measures the classification of shapes, not views of the target: its
// thinnest ellipses are no view of a circle tilted 80 deg or less, so the target's view
// check is off (docs/ellipse-detection.md, shapes.json).
EllipseOptions shapes() {
  EllipseOptions o;
  o.target_max_tilt_deg = 90.0;
  return o;
}

EllipseOptions withRule(FitAcceptRule rule) {
  EllipseOptions o = shapes();
  o.accept_rule = rule;
  return o;
}

EllipseOptions bennett() {
  EllipseOptions o = shapes();
  o.method = EllipseMethod::Bennett;
  return o;
}

// The grey library as `imagepro-cli library` writes it: 8 x 8 samples per pixel, seed 1.
LibraryGreyOptions greyLibrary(double blur, double noise) {
  LibraryGreyOptions g;
  g.blur_sigma_px = blur;
  g.noise_sigma = noise;
  return g;
}

// The row of the accept-rule table of docs/ellipse-detection.md, and the margin it
// claims for the default: every library ellipse at least 3.3 times below the E_rel limit.
void reportMargins(const char* name, const Tally& t) {
  std::printf("| %s | %.4f | %.4f | %.2f | %.2f | %.3f | %.3f |\n", name, t.ellipse_erel, t.rectangle_erel,
              t.ellipse_sampson, t.rectangle_sampson, t.ellipse_traced, t.rectangle_traced);
  EXPECT_LT(t.ellipse_erel, EllipseOptions{}.max_relative_error / 3.3);
}

TEST(LibraryClassification, DirectFitBothAcceptRules) {
  for (const FitAcceptRule rule : {FitAcceptRule::RelativeError, FitAcceptRule::SampsonDistance}) {
    const Tally t = classify(withRule(rule), nullptr);
    EXPECT_EQ(t.ellipses_missed, 0) << numbers(t.missed);
    EXPECT_EQ(t.rectangles_accepted, 0) << numbers(t.accepted);
    if (rule == FitAcceptRule::RelativeError) reportMargins("binary", t);
  }
}

TEST(LibraryClassification, TheTraceNotTheErrorLimitDecides) {
  // Every library path's E_rel is far below 0.02: without the limit the classification
  // is the same; without the trace the thin rectangles pass.
  EllipseOptions no_limit = shapes();
  no_limit.max_relative_error = 1e9;
  const Tally a = classify(no_limit, nullptr);
  EXPECT_EQ(a.ellipses_missed, 0);
  EXPECT_EQ(a.rectangles_accepted, 0);
  EllipseOptions no_trace = shapes();
  no_trace.min_traced_fraction = 0.0;
  no_trace.min_arc_fraction = 0.0;
  const Tally b = classify(no_trace, nullptr);
  EXPECT_EQ(b.ellipses_missed, 0);
  EXPECT_GE(b.rectangles_accepted, 25) << numbers(b.accepted);
}

TEST(LibraryClassification, BennettAtLeastAsGoodAsTheThesis) {
  const Tally t = classify(bennett(), nullptr);
  EXPECT_LE(t.ellipses_missed, 9);      // thesis: 9 of 72
  EXPECT_LE(t.rectangles_accepted, 7);  // thesis: 7 of 66
  // The level docs/ellipse-detection.md reports: the 8 thin ellipses missed, no rectangle.
  EXPECT_LE(t.ellipses_missed, 8) << numbers(t.missed);
  EXPECT_EQ(t.rectangles_accepted, 0) << numbers(t.accepted);
}

// The grey versions of docs/ellipse-detection.md, at the levels reported there: at
// most that many ellipses missed and rectangles accepted, for both accept rules of the
// direct fit and for Bennett.
struct GreyCase {
  const char* name;
  double blur, noise;
  int threshold;  // -1: AT-Mod
  int fit_missed, fit_accepted, sampson_missed, sampson_accepted, bennett_missed, bennett_accepted;
};

class GreyLibrary : public ::testing::TestWithParam<GreyCase> {};

TEST_P(GreyLibrary, AtTheDocumentedLevels) {
  const GreyCase& c = GetParam();
  const LibraryGreyOptions g = greyLibrary(c.blur, c.noise);
  const Tally fit = classify(withRule(FitAcceptRule::RelativeError), &g, c.threshold);
  const Tally sampson = classify(withRule(FitAcceptRule::SampsonDistance), &g, c.threshold);
  const Tally ben = classify(bennett(), &g, c.threshold);
  std::printf("%s: E_rel %d missed (%s), %d accepted (%s); Sampson %d (%s), %d (%s); Bennett %d (%s), %d (%s)\n",
              c.name, fit.ellipses_missed, numbers(fit.missed).c_str(), fit.rectangles_accepted,
              numbers(fit.accepted).c_str(), sampson.ellipses_missed, numbers(sampson.missed).c_str(),
              sampson.rectangles_accepted, numbers(sampson.accepted).c_str(), ben.ellipses_missed,
              numbers(ben.missed).c_str(), ben.rectangles_accepted, numbers(ben.accepted).c_str());
  reportMargins(c.name, fit);
  EXPECT_LE(fit.ellipses_missed, c.fit_missed);
  EXPECT_LE(fit.rectangles_accepted, c.fit_accepted);
  EXPECT_LE(sampson.ellipses_missed, c.sampson_missed);
  EXPECT_LE(sampson.rectangles_accepted, c.sampson_accepted);
  EXPECT_LE(ben.ellipses_missed, c.bennett_missed);
  EXPECT_LE(ben.rectangles_accepted, c.bennett_accepted);
}

std::string caseName(const ::testing::TestParamInfo<GreyCase>& info) {
  static const char* const kNames[] = {"Grey", "Blur", "Noise", "BlurNoise"};
  return kNames[info.index];
}

INSTANTIATE_TEST_SUITE_P(Versions, GreyLibrary,
                         ::testing::Values(GreyCase{"grey", 0.0, 0.0, -1, 0, 0, 0, 0, 8, 0},
                                           GreyCase{"blur 1.5, threshold 125", 1.5, 0.0, 125, 0, 0, 0, 0, 6, 2},
                                           GreyCase{"noise 10", 0.0, 10.0, -1, 0, 0, 0, 0, 8, 0},
                                           GreyCase{"blur 1.5 + noise 5", 1.5, 5.0, -1, 5, 0, 5, 0, 13, 0}),
                         caseName);

}  // namespace
}  // namespace imagepro
