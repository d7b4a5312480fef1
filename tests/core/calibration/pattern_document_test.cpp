#include "core/calibration/pattern_document.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <string>

#include "core/calibration/pattern.h"

namespace imagepro {
namespace {

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(PatternPage, OnlyTheSpotsThatFitInsideTheMargins) {
  const PatternGeometry p;
  const TargetGeometry t;
  PatternPage page;
  layoutPatternPage(p, t, Paper::A4, page);
  EXPECT_EQ(page.width_mm, 297.0);
  EXPECT_EQ(page.height_mm, 210.0);
  // Pattern area 277 x 174 mm around (148.5, 97): nodes within +-125 mm by +-75 mm.
  EXPECT_EQ(page.grid_columns, 11);
  EXPECT_EQ(page.grid_rows, 7);
  EXPECT_EQ(page.grid_spots, 11 * 7 - 25);
  ASSERT_EQ(page.circles.size(), 3u + page.grid_spots);
  EXPECT_FALSE(page.circles[0].black);  // the disk over the card
  EXPECT_EQ(page.circles[0].r_mm, t.radius_mm);
  EXPECT_EQ(page.circles[2].x_mm - page.circles[1].x_mm, t.spot_offset_mm);  // offset spot to the right
  for (size_t i = 3; i < page.circles.size(); ++i) {
    const PageCircle& c = page.circles[i];
    EXPECT_EQ(c.r_mm, p.spot_radius_mm);
    EXPECT_GE(c.x_mm - c.r_mm, kPageMarginMm);
    EXPECT_LE(c.x_mm + c.r_mm, page.width_mm - kPageMarginMm);
    EXPECT_GE(c.y_mm - c.r_mm, kPageMarginMm);
    // On the grid, 25 mm from the target's centre in whole spacings.
    const double gx = (c.x_mm - page.circles[0].x_mm) / 25.0, gy = (c.y_mm - page.circles[0].y_mm) / 25.0;
    EXPECT_NEAR(gx, std::round(gx), 1e-12);
    EXPECT_NEAR(gy, std::round(gy), 1e-12);
  }
  const PageRect& card = page.rects.front();
  EXPECT_EQ(card.w_mm, p.card_size_mm);
  EXPECT_EQ(card.x_mm + 0.5 * card.w_mm, page.circles[0].x_mm);

  layoutPatternPage(p, t, Paper::A3, page);
  EXPECT_EQ(page.grid_columns, 15);  // 400 x 261 mm: +-175 by +-125 mm
  EXPECT_EQ(page.grid_rows, 11);
  EXPECT_EQ(page.grid_spots, 15 * 11 - 25);

  PatternGeometry small = p;  // a grid smaller than the page: all of it
  small.columns = 9;
  small.rows = 7;
  layoutPatternPage(small, t, Paper::A3, page);
  EXPECT_EQ(page.grid_spots, 9 * 7 - 25);
}

TEST(PatternPage, SvgIsInMillimetres) {
  PatternPage page;
  layoutPatternPage(PatternGeometry{}, TargetGeometry{}, Paper::A4, page);
  const std::string svg = patternPageSvg(page);
  EXPECT_NE(svg.find("width=\"297mm\" height=\"210mm\" viewBox=\"0 0 297 210\""), std::string::npos);
  EXPECT_EQ(count(svg, "<circle "), static_cast<int>(page.circles.size()));
  EXPECT_EQ(count(svg, "<text "), static_cast<int>(page.texts.size()));
  EXPECT_NE(svg.find("25 mm apart"), std::string::npos);
  EXPECT_NE(svg.find("r=\"4\""), std::string::npos);
}

TEST(PatternPage, PdfCrossReferenceIsExact) {
  PatternPage page;
  layoutPatternPage(PatternGeometry{}, TargetGeometry{}, Paper::A3, page);
  const std::string pdf = patternPagePdf(page);
  ASSERT_EQ(pdf.rfind("%PDF-1.4", 0), 0u);
  EXPECT_NE(pdf.find("/MediaBox [0 0 1190.5512 841.8898]"), std::string::npos);  // A3 in points
  // startxref points at the table, and every entry at its object.
  const size_t sx = pdf.rfind("startxref\n");
  ASSERT_NE(sx, std::string::npos);
  const size_t xref = std::stoul(pdf.substr(sx + 10));
  ASSERT_EQ(pdf.compare(xref, 5, "xref\n"), 0);
  for (int obj = 1; obj <= 5; ++obj) {
    const size_t entry = xref + 5 + 4 + 20 * obj;  // "xref\n", "0 6\n", 20-byte entries
    const size_t offset = std::stoul(pdf.substr(entry, 10));
    EXPECT_EQ(pdf.compare(offset, std::to_string(obj).size() + 6, std::to_string(obj) + " 0 obj"), 0) << obj;
  }
  // The stream's stated length is its length.
  const size_t len = pdf.find("/Length ");
  const size_t stated = std::stoul(pdf.substr(len + 8));
  const size_t begin = pdf.find("stream\n", len) + 7;
  EXPECT_EQ(pdf.compare(begin + stated, 9, "endstream"), 0);
  // Four Bezier arcs per circle.
  EXPECT_EQ(count(pdf, " c "), 4 * static_cast<int>(page.circles.size()));
  EXPECT_EQ(count(pdf, " Tj ET"), static_cast<int>(page.texts.size()));
}

TEST(PatternPage, PngAtTrueScale) {
  PatternPage page;
  layoutPatternPage(PatternGeometry{}, TargetGeometry{}, Paper::A4, page);
  const double dpi = 150.0;
  const std::vector<std::uint8_t> png = patternPagePng(page, dpi);
  // The resolution is in the file: pHYs right after IHDR, 5906 pixels per metre.
  ASSERT_GT(png.size(), 54u);
  EXPECT_EQ(std::string(png.begin() + 37, png.begin() + 41), "pHYs");
  const std::uint32_t ppm = (png[41] << 24) | (png[42] << 16) | (png[43] << 8) | png[44];
  EXPECT_EQ(ppm, 5906u);
  const cv::Mat img = cv::imdecode(png, cv::IMREAD_GRAYSCALE);  // decoding checks every CRC
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, static_cast<int>(std::lround(297 / 25.4 * dpi)));
  EXPECT_EQ(img.rows, static_cast<int>(std::lround(210 / 25.4 * dpi)));
  // Every grid spot is where the layout puts it: darkness centroid within 0.1 px.
  const double pxPerMm = dpi / 25.4;
  for (size_t i = 3; i < page.circles.size(); ++i) {
    const PageCircle& c = page.circles[i];
    const double u = c.x_mm * pxPerMm - 0.5, v = c.y_mm * pxPerMm - 0.5;
    const int half = static_cast<int>(c.r_mm * pxPerMm) + 3;
    double sw = 0, su = 0, sv = 0;
    for (int y = static_cast<int>(v) - half; y <= static_cast<int>(v) + half + 1; ++y)
      for (int x = static_cast<int>(u) - half; x <= static_cast<int>(u) + half + 1; ++x) {
        const double w = 255.0 - img.at<unsigned char>(y, x);
        sw += w;
        su += w * x;
        sv += w * y;
      }
    EXPECT_NEAR(su / sw, u, 0.1);
    EXPECT_NEAR(sv / sw, v, 0.1);
    EXPECT_NEAR(sw / 255.0, M_PI * std::pow(c.r_mm * pxPerMm, 2), 0.002 * sw / 255.0);  // its area
  }
}

}  // namespace
}  // namespace imagepro
