#pragma once
// Printable calibration pattern (thesis 4.3, fig. 4.6): the pattern of pattern.h, or one of
// OpenCV's circle grids (dot_grid.h), at true scale on an A4, Letter or A3 landscape page, as SVG, PDF or PNG, with its dimensions and a
// 100 mm scale bar printed along the bottom so a print can be checked with a ruler.
// The page is the white sheet: the target on its card at the centre of the area above the
// text, and every grid spot that lies wholly inside that area (kPageMarginMm from the
// paper's edges, which printers cannot reach).
//
// The page is laid out once (layoutPatternPage) in millimetres, y down, and each format
// draws that layout: SVG in millimetre user units; PDF as a minimal PDF 1.4 written here
// (circles as four cubic Bezier arcs, text in the standard Type 1 font Helvetica); PNG by
// OpenCV at a stated resolution, with the resolution recorded in the file (pHYs chunk).
#include <cstdint>
#include <string>
#include <vector>

#include "core/calibration/dot_grid.h"
#include "core/common/geometry.h"
#include "core/settings/target_set.h"

namespace imagepro {

enum class Paper : std::uint8_t { A4, A3, Letter };

inline constexpr double kPageMarginMm = 10.0;

struct PageCircle {
  double x_mm = 0, y_mm = 0, r_mm = 0;
  bool black = true;
};
struct PageRect {
  double x_mm = 0, y_mm = 0, w_mm = 0, h_mm = 0;  // top-left corner, size
};
struct PageText {
  double x_mm = 0, y_mm = 0;  // baseline start
  double size_mm = 3.0;       // font size (em height)
  std::string text;           // ASCII
};

struct PatternPage {
  double width_mm = 0, height_mm = 0;
  std::vector<PageRect> rects;      // black: the card and the scale bar
  std::vector<PageCircle> circles;  // in drawing order: the disk (white), its spots, the grid spots
  std::vector<PageText> texts;
  int grid_spots = 0;               // grid spots on the page
  int grid_columns = 0, grid_rows = 0;  // extent of the grid on the page
  double origin_x_mm = 0, origin_y_mm = 0;  // where the pattern's (0, 0) lies on the page
  std::size_t cards = 1;            // the first this many rects are cards, drawn under the circles
};

// Landscape page size in mm (A4 297 x 210, A3 420 x 297, Letter 279.4 x 215.9).
void paperSizeMm(Paper paper, double& width_mm, double& height_mm);
const char* paperName(Paper paper);
// "A4", "A3", "Letter" (any case).
bool parsePaper(const std::string& name, Paper& paper);

void layoutPatternPage(const PatternGeometry& pattern, const TargetGeometry& target, Paper paper, PatternPage& page);
// Any dot grid: the thesis pattern as layoutPatternPage (what fits of it), an OpenCV grid
// whole, centred, with its description and the calibrate command that takes it printed
// below. False with `error` when the description is wrong or the grid does not fit.
bool layoutDotGridPage(const DotGridSpec& spec, Paper paper, PatternPage& page, std::string& error);

// Targets of a set (settings "targets") at true scale, each on its black card (at least
// `card_size_mm`) with its id, name and dimensions printed below it, in rows on one page.
// False with `error` when they do not fit the paper.
bool layoutTargetSheet(const std::vector<TargetSpec>& members, double card_size_mm, Paper paper, PatternPage& page,
                       std::string& error);

std::string patternPageSvg(const PatternPage& page);
std::string patternPagePdf(const PatternPage& page);
// PNG file bytes at `dpi` dots per inch (resolution stored in the file).
std::vector<std::uint8_t> patternPagePng(const PatternPage& page, double dpi);

}  // namespace imagepro
