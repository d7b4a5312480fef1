// imagepro-cli pattern: the printable calibration pattern (thesis 4.3) at true scale,
// as PDF, SVG or PNG, with its dimensions printed on it (calibration/pattern_document.h).
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string>

#include "cli/command.h"
#include "core/calibration/pattern_document.h"
#include "core/common/atomic_file.h"

namespace imagepro::cli {
namespace {

std::string lowerExtension(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

int run(const Args& args) {
  args.rejectUnknown({"out", "paper", "dpi"});
  if (!args.positionals().empty()) throw UsageError("unexpected argument \"" + args.positionals().front() + "\"");
  const auto out = args.value("out");
  if (!out) throw UsageError("--out FILE is required (.pdf, .svg or .png)");
  const std::string ext = lowerExtension(*out);
  if (ext != "pdf" && ext != "svg" && ext != "png")
    throw UsageError("--out: \"" + *out + "\" does not end in .pdf, .svg or .png");
  const std::string paperArg = args.valueOr("paper", "A4");
  Paper paper = Paper::A4;
  if (paperArg == "A4" || paperArg == "a4") paper = Paper::A4;
  else if (paperArg == "A3" || paperArg == "a3") paper = Paper::A3;
  else throw UsageError("--paper: \"" + paperArg + "\" is not A4 or A3");
  if (args.has("dpi") && ext != "png") throw UsageError("--dpi applies to PNG output only");
  const double dpi = args.number("dpi", 300.0);
  if (!(dpi >= 25.0 && dpi <= 2400.0)) throw UsageError("--dpi must be 25..2400");

  const Settings settings = loadConfig(args);
  PatternPage page;
  layoutPatternPage(settings.pattern, settings.target, paper, page);
  std::string content;
  if (ext == "svg") {
    content = patternPageSvg(page);
  } else if (ext == "pdf") {
    content = patternPagePdf(page);
  } else {
    const auto png = patternPagePng(page, dpi);
    content.assign(png.begin(), png.end());
  }
  std::string error;
  if (!writeFileAtomically(*out, content, error)) throw InputError(error);
  std::printf("wrote %s: %s landscape, %d x %d grid spots (%d drawn) %g mm apart, card %g mm", out->c_str(),
              paperName(paper), page.grid_columns, page.grid_rows, page.grid_spots, settings.pattern.spot_spacing_mm,
              settings.pattern.card_size_mm);
  if (ext == "png") std::printf(", %g dpi", dpi);
  std::printf("\nprint it at actual size (100 %%, no fitting to the page) and check the 100 mm bar\n");
  return 0;
}

const CommandRegistration kRegistration{{
    "pattern",
    "write the printable calibration pattern (PDF, SVG or PNG) at true scale",
    "usage: imagepro-cli pattern --out FILE.pdf|FILE.svg|FILE.png [--paper A4|A3] [--dpi N] [--config FILE]\n\n"
    "Writes the calibration pattern of thesis 4.3 for the settings' \"pattern\" and \"target\":\n"
    "the target on its black card at the centre of a landscape page, and every grid spot that\n"
    "fits inside a 10 mm margin, with the dimensions and a 100 mm scale bar printed below.\n"
    "  --out FILE    .pdf (vector), .svg (vector, mm units) or .png; written atomically\n"
    "  --paper P     A4 (default) or A3\n"
    "  --dpi N       PNG resolution, stored in the file (default 300)",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
