#include "core/calibration/pattern_document.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <climits>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "core/calibration/pattern.h"

namespace imagepro {
namespace {

constexpr double kTextBandMm = 16.0;  // below the pattern: three lines of text and the scale bar
constexpr double kTextSizeMm = 2.6;
constexpr double kScaleBarMm = 100.0;
constexpr double kPointsPerMm = 72.0 / 25.4;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4f", v);
  std::string s = buf;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

std::string g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string xmlEscape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

std::string pdfEscape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '(' || c == ')' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

std::uint32_t crc32(const std::uint8_t* data, std::size_t n) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) c = table[(c ^ data[i]) & 0xFFu] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

void putBigEndian(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(v >> shift));
}

// Three lines of text on the left of the band below the pattern, the scale bar on its right.
void addTextBand(PatternPage& page, const std::array<std::string, 3>& lines) {
  const double x0 = kPageMarginMm, x1 = page.width_mm - kPageMarginMm;
  const double y1 = page.height_mm - kPageMarginMm - kTextBandMm;
  const double line = 1.5 * kTextSizeMm;
  const double ty = y1 + 0.5 * kTextBandMm - line + 0.35 * kTextSizeMm;
  for (int i = 0; i < 3; ++i) page.texts.push_back({x0, ty + i * line, kTextSizeMm, lines[i]});
  const double barX = x1 - kScaleBarMm, barY = y1 + 0.5 * kTextBandMm + 1.0;
  page.rects.push_back({barX, barY, kScaleBarMm, 0.8});
  page.rects.push_back({barX, barY - 2.5, 0.4, 3.3});
  page.rects.push_back({x1 - 0.4, barY - 2.5, 0.4, 3.3});
  page.texts.push_back({barX + 0.5 * kScaleBarMm - 4.0, barY - 1.5, kTextSizeMm, g(kScaleBarMm) + " mm"});
}

}  // namespace

void paperSizeMm(Paper paper, double& width_mm, double& height_mm) {
  if (paper == Paper::A3) {
    width_mm = 420.0;
    height_mm = 297.0;
  } else if (paper == Paper::Letter) {
    width_mm = 279.4;
    height_mm = 215.9;
  } else {
    width_mm = 297.0;
    height_mm = 210.0;
  }
}

const char* paperName(Paper paper) {
  return paper == Paper::A3 ? "A3" : paper == Paper::Letter ? "Letter" : "A4";
}

bool parsePaper(const std::string& name, Paper& paper) {
  std::string lower;
  for (const char c : name) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const Paper p : {Paper::A4, Paper::A3, Paper::Letter}) {
    std::string n = paperName(p);
    for (char& c : n) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (n == lower) {
      paper = p;
      return true;
    }
  }
  return false;
}

void layoutPatternPage(const PatternGeometry& pattern, const TargetGeometry& target, Paper paper, PatternPage& page) {
  page = {};
  paperSizeMm(paper, page.width_mm, page.height_mm);
  const double x0 = kPageMarginMm, x1 = page.width_mm - kPageMarginMm;
  const double y0 = kPageMarginMm, y1 = page.height_mm - kPageMarginMm - kTextBandMm;
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  page.origin_x_mm = cx;
  page.origin_y_mm = cy;

  const double half = patternCardHalfMm(pattern, target);
  page.rects.push_back({cx - half, cy - half, 2 * half, 2 * half});
  page.circles.push_back({cx, cy, target.radius_mm, false});
  page.circles.push_back({cx, cy, target.spot_radius_mm, true});
  page.circles.push_back({cx + target.spot_offset_mm, cy, target.spot_radius_mm, true});

  std::vector<PatternSpot> spots;
  patternSpots(pattern, target, spots);
  const double r = patternSpotRadiusMm(pattern);
  int cMin = INT_MAX, cMax = INT_MIN, rMin = INT_MAX, rMax = INT_MIN;
  for (const PatternSpot& s : spots) {
    const double x = cx + s.position_mm.x(), y = cy + s.position_mm.y();
    if (x - r < x0 || x + r > x1 || y - r < y0 || y + r > y1) continue;
    page.circles.push_back({x, y, r, true});
    ++page.grid_spots;
    cMin = std::min(cMin, s.column);
    cMax = std::max(cMax, s.column);
    rMin = std::min(rMin, s.row);
    rMax = std::max(rMax, s.row);
  }
  if (page.grid_spots > 0) {
    page.grid_columns = cMax - cMin + 1;
    page.grid_rows = rMax - rMin + 1;
  }

  addTextBand(page, {"ImagePro calibration pattern. Print at actual size (100 %, no fitting): the bar measures " +
                         g(kScaleBarMm) + " mm.",
                     "Spots " + g(2 * r) + " mm diameter, " + g(pattern.spot_spacing_mm) + " mm apart. Card " +
                         g(2 * half) + " mm square. Disk " + g(2 * target.radius_mm) + " mm, its spots " +
                         g(2 * target.spot_radius_mm) + " mm, " + g(target.spot_offset_mm) + " mm apart.",
                     "Settings pattern: spot_spacing_mm " + g(pattern.spot_spacing_mm) + ", spot_radius_mm " +
                         g(pattern.spot_radius_mm) + ", card_size_mm " + g(pattern.card_size_mm) + ". This " +
                         paperName(paper) + " page: " + std::to_string(page.grid_columns) + " x " +
                         std::to_string(page.grid_rows) + " of its " + std::to_string(pattern.columns) + " x " +
                         std::to_string(pattern.rows) + " grid."});
}

bool layoutTargetSheet(const std::vector<TargetSpec>& members, double card_size_mm, Paper paper, PatternPage& page,
                       std::string& error) {
  page = {};
  paperSizeMm(paper, page.width_mm, page.height_mm);
  if (members.empty()) {
    error = "no target to print";
    return false;
  }
  double card = card_size_mm;
  for (const TargetSpec& m : members) card = std::max(card, 2.0 * m.geometry.radius_mm + 4.0);
  constexpr double kLabelMm = 9.0;  // under each card: its id, name and dimensions
  constexpr double kGapMm = 4.0;
  const double x0 = kPageMarginMm, x1 = page.width_mm - kPageMarginMm;
  const double y0 = kPageMarginMm, y1 = page.height_mm - kPageMarginMm - kTextBandMm;
  const int columns = static_cast<int>((x1 - x0 + kGapMm) / (card + kGapMm));
  const int rows = static_cast<int>((y1 - y0 + kGapMm) / (card + kLabelMm + kGapMm));
  if (columns * rows < static_cast<int>(members.size())) {
    error = std::to_string(members.size()) + " cards of " + g(card) + " mm do not fit on a " + paperName(paper) +
            " page (" + std::to_string(std::max(0, columns * rows)) + " do): print each target on its own page "
            "(--target ID), or on a larger paper";
    return false;
  }
  const int n = static_cast<int>(members.size());
  const int usedColumns = std::min(columns, n);
  const int usedRows = (n + usedColumns - 1) / usedColumns;
  const double blockW = usedColumns * card + (usedColumns - 1) * kGapMm;
  const double blockH = usedRows * (card + kLabelMm) + (usedRows - 1) * kGapMm;
  const double left = 0.5 * (x0 + x1 - blockW), top = 0.5 * (y0 + y1 - blockH);
  page.cards = members.size();
  for (int i = 0; i < n; ++i) {
    const double cardX = left + (i % usedColumns) * (card + kGapMm);
    const double cardY = top + (i / usedColumns) * (card + kLabelMm + kGapMm);
    page.rects.push_back({cardX, cardY, card, card});
  }
  for (int i = 0; i < n; ++i) {
    const TargetGeometry& t = members[static_cast<std::size_t>(i)].geometry;
    const PageRect& r = page.rects[static_cast<std::size_t>(i)];
    const double cx = r.x_mm + 0.5 * card, cy = r.y_mm + 0.5 * card;
    page.circles.push_back({cx, cy, t.radius_mm, false});
    page.circles.push_back({cx, cy, t.spot_radius_mm, true});
    page.circles.push_back({cx + t.spot_offset_mm, cy, t.spot_radius_mm, true});
    const TargetSpec& m = members[static_cast<std::size_t>(i)];
    page.texts.push_back({r.x_mm, r.y_mm + card + 4.5, kTextSizeMm,
                          "id " + std::to_string(m.id) + (m.name.empty() ? "" : " " + m.name) + ": offset spot " +
                              g(t.spot_offset_mm) + " mm (" + g(t.spot_offset_mm / t.radius_mm) + " R)"});
    page.texts.push_back({r.x_mm, r.y_mm + card + 8.0, kTextSizeMm,
                          "disk " + g(2 * t.radius_mm) + " mm, spots " + g(2 * t.spot_radius_mm) + " mm"});
  }
  addTextBand(page, {"ImagePro target set. Print at actual size (100 %, no fitting): the bar measures " +
                         g(kScaleBarMm) + " mm.",
                     std::to_string(n) + (n == 1 ? " target" : " targets") + " on black cards of " + g(card) +
                         " mm; each is told by where its offset spot sits (settings \"targets\").",
                     "Cut each card out and fix it flat; keep the cards' spots and rims clear of clamps and tape."});
  return true;
}

bool layoutDotGridPage(const DotGridSpec& spec, Paper paper, PatternPage& page, std::string& error) {
  page = {};
  error = dotGridSpecError(spec);
  if (!error.empty()) return false;
  if (spec.kind == DotGridKind::Thesis) {
    layoutPatternPage(thesisPatternOf(spec), spec.target, paper, page);
    return true;
  }
  paperSizeMm(paper, page.width_mm, page.height_mm);
  const double x0 = kPageMarginMm, x1 = page.width_mm - kPageMarginMm;
  const double y0 = kPageMarginMm, y1 = page.height_mm - kPageMarginMm - kTextBandMm;
  const double d = dotDiameterMm(spec), s = spec.spacing_mm;
  const bool asym = spec.kind == DotGridKind::AsymmetricCircles;
  const double w = (asym ? 2 * (spec.columns - 1) + 1 : spec.columns - 1) * s + d;
  const double h = (spec.rows - 1) * s + d;
  if (w > x1 - x0 || h > y1 - y0) {
    error = "the grid is " + g(w) + " x " + g(h) + " mm, the " + paperName(paper) + " page holds " + g(x1 - x0) +
            " x " + g(y1 - y0) + " mm: take a larger paper, a smaller spacing or fewer dots";
    return false;
  }
  page.origin_x_mm = 0.5 * (x0 + x1 - w) + 0.5 * d;
  page.origin_y_mm = 0.5 * (y0 + y1 - h) + 0.5 * d;
  for (int i = 0; i < spec.rows; ++i)
    for (int j = 0; j < spec.columns; ++j) {
      const Eigen::Vector2d p = dotGridPointMm(spec, j, i);
      page.circles.push_back({page.origin_x_mm + p.x(), page.origin_y_mm + p.y(), 0.5 * d, true});
    }
  page.grid_spots = spec.columns * spec.rows;
  page.grid_columns = spec.columns;
  page.grid_rows = spec.rows;
  const std::string kind(dotGridKindName(spec.kind));
  addTextBand(page, {"ImagePro calibration pattern: OpenCV " + std::string(asym ? "asymmetric" : "symmetric") +
                         " circle grid. Print at actual size (100 %, no fitting): the bar measures " +
                         g(kScaleBarMm) + " mm.",
                     std::to_string(spec.columns) + " x " + std::to_string(spec.rows) +
                         " dots (points per row x rows, OpenCV's pattern size), spacing " + g(s) +
                         " mm, dot diameter " + g(d) + " mm. Glue it flat.",
                     "imagepro-cli calibrate --intrinsics --pattern " + kind + " --columns " +
                         std::to_string(spec.columns) + " --rows " + std::to_string(spec.rows) + " --spacing-mm " +
                         g(s) + " --dot-diameter-mm " + g(d)});
  return true;
}

std::string patternPageSvg(const PatternPage& page) {
  std::string s = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  s += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(page.width_mm) + "mm\" height=\"" +
       num(page.height_mm) + "mm\" viewBox=\"0 0 " + num(page.width_mm) + " " + num(page.height_mm) + "\">\n";
  s += "<rect x=\"0\" y=\"0\" width=\"" + num(page.width_mm) + "\" height=\"" + num(page.height_mm) +
       "\" fill=\"#ffffff\"/>\n";
  // The cards first, then the disks and every spot over them, then the bar.
  auto rect = [&](const PageRect& r) {
    s += "<rect x=\"" + num(r.x_mm) + "\" y=\"" + num(r.y_mm) + "\" width=\"" + num(r.w_mm) + "\" height=\"" +
         num(r.h_mm) + "\" fill=\"#000000\"/>\n";
  };
  const std::size_t cards = std::min(page.cards, page.rects.size());
  for (std::size_t i = 0; i < cards; ++i) rect(page.rects[i]);
  for (const PageCircle& c : page.circles)
    s += "<circle cx=\"" + num(c.x_mm) + "\" cy=\"" + num(c.y_mm) + "\" r=\"" + num(c.r_mm) + "\" fill=\"" +
         (c.black ? "#000000" : "#ffffff") + "\"/>\n";
  for (std::size_t i = cards; i < page.rects.size(); ++i) rect(page.rects[i]);
  for (const PageText& t : page.texts)
    s += "<text x=\"" + num(t.x_mm) + "\" y=\"" + num(t.y_mm) + "\" font-family=\"Helvetica, Arial, sans-serif\" "
         "font-size=\"" + num(t.size_mm) + "\" fill=\"#000000\">" + xmlEscape(t.text) + "</text>\n";
  s += "</svg>\n";
  return s;
}

std::string patternPagePdf(const PatternPage& page) {
  // Content in millimetres with y down: scale to points and flip once in the CTM.
  std::string c = num(kPointsPerMm) + " 0 0 " + num(-kPointsPerMm) + " 0 " + num(page.height_mm * kPointsPerMm) +
                  " cm\n";
  auto rect = [&](const PageRect& r) {
    c += "0 g " + num(r.x_mm) + " " + num(r.y_mm) + " " + num(r.w_mm) + " " + num(r.h_mm) + " re f\n";
  };
  const std::size_t cards = std::min(page.cards, page.rects.size());
  for (std::size_t i = 0; i < cards; ++i) rect(page.rects[i]);
  constexpr double k = 0.5522847498307936;  // 4/3 (sqrt 2 - 1): a quarter circle as one cubic
  for (const PageCircle& e : page.circles) {
    const double x = e.x_mm, y = e.y_mm, r = e.r_mm, d = k * r;
    c += e.black ? "0 g " : "1 g ";
    c += num(x + r) + " " + num(y) + " m ";
    c += num(x + r) + " " + num(y + d) + " " + num(x + d) + " " + num(y + r) + " " + num(x) + " " + num(y + r) + " c ";
    c += num(x - d) + " " + num(y + r) + " " + num(x - r) + " " + num(y + d) + " " + num(x - r) + " " + num(y) + " c ";
    c += num(x - r) + " " + num(y - d) + " " + num(x - d) + " " + num(y - r) + " " + num(x) + " " + num(y - r) + " c ";
    c += num(x + d) + " " + num(y - r) + " " + num(x + r) + " " + num(y - d) + " " + num(x + r) + " " + num(y) + " c f\n";
  }
  for (std::size_t i = cards; i < page.rects.size(); ++i) rect(page.rects[i]);
  for (const PageText& t : page.texts)  // the text matrix flips y back, so glyphs stand upright
    c += "0 g BT /F1 " + num(t.size_mm) + " Tf 1 0 0 -1 " + num(t.x_mm) + " " + num(t.y_mm) + " Tm (" +
         pdfEscape(t.text) + ") Tj ET\n";

  std::string pdf = "%PDF-1.4\n%\xE2\xE3\xCF\xD3\n";
  std::vector<std::size_t> offsets;
  auto object = [&](const std::string& body) {
    offsets.push_back(pdf.size());
    pdf += std::to_string(offsets.size()) + " 0 obj\n" + body + "\nendobj\n";
  };
  object("<< /Type /Catalog /Pages 2 0 R >>");
  object("<< /Type /Pages /Kids [3 0 R] /Count 1 >>");
  object("<< /Type /Page /Parent 2 0 R /MediaBox [0 0 " + num(page.width_mm * kPointsPerMm) + " " +
         num(page.height_mm * kPointsPerMm) + "] /Contents 4 0 R /Resources << /Font << /F1 5 0 R >> >> >>");
  object("<< /Length " + std::to_string(c.size()) + " >>\nstream\n" + c + "endstream");
  object("<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica /Encoding /WinAnsiEncoding >>");
  const std::size_t xref = pdf.size();
  pdf += "xref\n0 " + std::to_string(offsets.size() + 1) + "\n0000000000 65535 f \n";
  for (const std::size_t o : offsets) {
    char entry[24];
    std::snprintf(entry, sizeof entry, "%010zu 00000 n \n", o);
    pdf += entry;
  }
  pdf += "trailer\n<< /Size " + std::to_string(offsets.size() + 1) + " /Root 1 0 R >>\nstartxref\n" +
         std::to_string(xref) + "\n%%EOF\n";
  return pdf;
}

std::vector<std::uint8_t> patternPagePng(const PatternPage& page, double dpi) {
  const double pxPerMm = dpi / 25.4;
  cv::Mat img(static_cast<int>(std::lround(page.height_mm * pxPerMm)),
              static_cast<int>(std::lround(page.width_mm * pxPerMm)), CV_8UC1, cv::Scalar(255));
  // Shapes are painted by the fraction of each pixel they cover, so a print has the true
  // sizes: pixel (i, j) spans [i, i + 1) x [j, j + 1) in units of 1 / pxPerMm mm.
  auto paint = [&](int x0, int y0, int x1, int y1, int level, auto coverage) {
    x0 = std::max(x0, 0);
    y0 = std::max(y0, 0);
    x1 = std::min(x1, img.cols - 1);
    y1 = std::min(y1, img.rows - 1);
    for (int y = y0; y <= y1; ++y) {
      unsigned char* row = img.ptr<unsigned char>(y);
      for (int x = x0; x <= x1; ++x) {
        const double c = coverage(x, y);
        if (c > 0.0) row[x] = cv::saturate_cast<unsigned char>(row[x] + c * (level - row[x]));
      }
    }
  };
  auto rect = [&](const PageRect& r) {
    const double l = r.x_mm * pxPerMm, t = r.y_mm * pxPerMm;
    const double rr = (r.x_mm + r.w_mm) * pxPerMm, b = (r.y_mm + r.h_mm) * pxPerMm;
    paint(static_cast<int>(std::floor(l)), static_cast<int>(std::floor(t)), static_cast<int>(std::ceil(rr)),
          static_cast<int>(std::ceil(b)), 0, [&](int x, int y) {
            const double w = std::min(rr, x + 1.0) - std::max(l, static_cast<double>(x));
            const double h = std::min(b, y + 1.0) - std::max(t, static_cast<double>(y));
            return w > 0.0 && h > 0.0 ? w * h : 0.0;
          });
  };
  constexpr int kSub = 8;  // samples per axis on the circle's rim
  auto circle = [&](const PageCircle& c) {
    const double cx = c.x_mm * pxPerMm, cy = c.y_mm * pxPerMm, r = c.r_mm * pxPerMm;
    paint(static_cast<int>(std::floor(cx - r)), static_cast<int>(std::floor(cy - r)),
          static_cast<int>(std::ceil(cx + r)), static_cast<int>(std::ceil(cy + r)), c.black ? 0 : 255,
          [&](int x, int y) {
            const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
            if (d <= r - M_SQRT1_2) return 1.0;
            if (d >= r + M_SQRT1_2) return 0.0;
            int in = 0;
            for (int j = 0; j < kSub; ++j)
              for (int i = 0; i < kSub; ++i)
                in += std::hypot(x + (i + 0.5) / kSub - cx, y + (j + 0.5) / kSub - cy) < r;
            return in / double(kSub * kSub);
          });
  };
  const std::size_t cards = std::min(page.cards, page.rects.size());
  for (std::size_t i = 0; i < cards; ++i) rect(page.rects[i]);
  for (const PageCircle& c : page.circles) circle(c);
  for (std::size_t i = cards; i < page.rects.size(); ++i) rect(page.rects[i]);
  for (const PageText& t : page.texts) {
    int base = 0;
    const cv::Size unit = cv::getTextSize("H", cv::FONT_HERSHEY_SIMPLEX, 1.0, 1, &base);
    const double scale = 0.72 * t.size_mm * pxPerMm / unit.height;  // cap height of the font size
    cv::putText(img, t.text, cv::Point(static_cast<int>(std::lround(t.x_mm * pxPerMm)),
                                       static_cast<int>(std::lround(t.y_mm * pxPerMm))),
                cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0), std::max(1, static_cast<int>(std::lround(scale * 1.5))),
                cv::LINE_AA);
  }

  std::vector<std::uint8_t> png;
  cv::imencode(".png", img, png);
  // pHYs after IHDR (8-byte signature + 25-byte IHDR chunk): pixels per metre, unit metre.
  std::vector<std::uint8_t> chunk;
  putBigEndian(chunk, 9);
  const std::size_t typeAt = chunk.size();
  for (const char ch : {'p', 'H', 'Y', 's'}) chunk.push_back(static_cast<std::uint8_t>(ch));
  const auto perMetre = static_cast<std::uint32_t>(std::lround(dpi / 0.0254));
  putBigEndian(chunk, perMetre);
  putBigEndian(chunk, perMetre);
  chunk.push_back(1);
  putBigEndian(chunk, crc32(chunk.data() + typeAt, chunk.size() - typeAt));
  if (png.size() > 33) png.insert(png.begin() + 33, chunk.begin(), chunk.end());
  return png;
}

}  // namespace imagepro
