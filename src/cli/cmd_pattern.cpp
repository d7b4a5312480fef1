// imagepro-cli pattern: the printable calibration pattern (thesis 4.3) at true scale,
// as PDF, SVG or PNG, with its dimensions printed on it (calibration/pattern_document.h).
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string>
#include <vector>

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

void writePage(const PatternPage& page, const std::string& out, const std::string& ext, double dpi) {
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
  if (!writeFileAtomically(out, content, error)) throw InputError(error);
}

// --targets: every target of the settings' set on one page; --target ID: that one alone.
int printTargets(const Args& args, const Settings& settings, const std::string& out, const std::string& ext,
                 Paper paper, double dpi) {
  for (const char* grid : {"pattern", "columns", "rows", "spacing-mm", "dot-diameter-mm"})
    if (args.has(grid)) throw UsageError(std::string("--") + grid + " does not go with --targets or --target");
  std::vector<TargetSpec> members = settings.targets;
  if (members.empty()) members.push_back(TargetSpec{kLoneTargetId, "", settings.target});
  if (const auto id = args.value("target")) {
    const int wanted = args.integer("target", 0);
    std::erase_if(members, [&](const TargetSpec& m) { return m.id != wanted; });
    if (members.empty()) throw UsageError("--target: " + *id + " is not the id of a target in the settings");
  }
  PatternPage page;
  std::string error;
  if (!layoutTargetSheet(members, settings.pattern.card_size_mm, paper, page, error))
    throw UsageError("InvalidPattern: " + error);
  writePage(page, out, ext, dpi);
  std::printf("wrote %s: %zu target%s on %s landscape, cards %g mm", out.c_str(), members.size(),
              members.size() == 1 ? "" : "s", paperName(paper), page.rects.front().w_mm);
  for (const TargetSpec& m : members) std::printf("; id %d offset %g mm", m.id, m.geometry.spot_offset_mm);
  std::printf("\nprint it at actual size (100 %%, no fitting to the page) and check the 100 mm bar\n");
  return 0;
}

int run(const Args& args) {
  args.rejectUnknown({"out", "paper", "dpi", "pattern", "columns", "rows", "spacing-mm", "dot-diameter-mm", "config",
                      "targets", "target"});
  if (!args.positionals().empty()) throw UsageError("unexpected argument \"" + args.positionals().front() + "\"");
  const auto out = args.value("out");
  if (!out) throw UsageError("--out FILE is required (.pdf, .svg or .png)");
  const std::string ext = lowerExtension(*out);
  if (ext != "pdf" && ext != "svg" && ext != "png")
    throw UsageError("--out: \"" + *out + "\" does not end in .pdf, .svg or .png");
  const std::string paperArg = args.valueOr("paper", "A4");
  Paper paper = Paper::A4;
  if (!parsePaper(paperArg, paper)) throw UsageError("--paper: \"" + paperArg + "\" is not A4, Letter or A3");
  if (args.has("dpi") && ext != "png") throw UsageError("--dpi applies to PNG output only");
  const double dpi = args.number("dpi", 300.0);
  if (!(dpi >= 25.0 && dpi <= 2400.0)) throw UsageError("--dpi must be 25..2400");

  Settings settings = loadConfig(args);
  if (args.has("targets") || args.has("target")) return printTargets(args, settings, *out, ext, paper, dpi);
  const std::string kindArg = args.valueOr("pattern", "thesis");
  const auto kind = parseDotGridKind(kindArg);
  if (!kind) throw UsageError("--pattern: \"" + kindArg + "\" is not thesis, symmetric-circles or asymmetric-circles");
  if (*kind != DotGridKind::Thesis)
    for (const char* required : {"columns", "rows", "spacing-mm"})
      if (!args.has(required)) throw UsageError(std::string("--") + required + " is required for --pattern " + kindArg);
  // The thesis pattern: the settings' unless the command line says otherwise.
  DotGridSpec spec;
  spec.kind = *kind;
  spec.columns = args.integer("columns", settings.pattern.columns);
  spec.rows = args.integer("rows", settings.pattern.rows);
  spec.spacing_mm = args.number("spacing-mm", settings.pattern.spot_spacing_mm);
  spec.dot_diameter_mm =
      args.number("dot-diameter-mm", *kind == DotGridKind::Thesis ? 2.0 * settings.pattern.spot_radius_mm : 0.0);
  spec.card_size_mm = settings.pattern.card_size_mm;
  spec.target = settings.target;
  PatternPage page;
  std::string layoutError;
  if (!layoutDotGridPage(spec, paper, page, layoutError)) throw UsageError("InvalidPattern: " + layoutError);
  writePage(page, *out, ext, dpi);
  std::printf("wrote %s: %s, %s landscape, %d x %d grid spots (%d drawn) %g mm apart, dots %g mm", out->c_str(),
              std::string(dotGridKindName(spec.kind)).c_str(), paperName(paper), page.grid_columns, page.grid_rows,
              page.grid_spots, spec.spacing_mm, dotDiameterMm(spec));
  if (spec.kind == DotGridKind::Thesis) std::printf(", card %g mm", spec.card_size_mm);
  if (ext == "png") std::printf(", %g dpi", dpi);
  std::printf("\nprint it at actual size (100 %%, no fitting to the page) and check the 100 mm bar\n");
  return 0;
}

const CommandRegistration kRegistration{{
    "pattern",
    "write the printable calibration pattern (PDF, SVG or PNG) at true scale",
    "usage: imagepro-cli pattern --out FILE.pdf|FILE.svg|FILE.png [--paper A4|Letter|A3] [--dpi N]\n"
    "         [--pattern thesis|symmetric-circles|asymmetric-circles] [--columns C] [--rows R]\n"
    "         [--spacing-mm S] [--dot-diameter-mm D] [--config FILE]\n"
    "       imagepro-cli pattern --out FILE --targets | --target ID [--paper P] [--config FILE]\n\n"
    "Writes a calibration pattern at true scale on a landscape page, with its parameters and a\n"
    "100 mm scale bar printed below. thesis (default): the pattern of thesis 4.3 for the\n"
    "settings' \"pattern\" and \"target\" (the options override its grid), the target on its\n"
    "black card at the centre and every grid spot that fits inside a 10 mm margin.\n"
    "symmetric-circles, asymmetric-circles: OpenCV's circle grids, whole, C x R = points per\n"
    "row x rows (OpenCV's pattern size), dot diameter s/2 unless given; the calibrate command\n"
    "that takes them is printed on the sheet (calibrate --intrinsics).\n"
    "  --out FILE    .pdf (vector), .svg (vector, mm units) or .png; written atomically\n"
    "  --paper P     A4 (default), Letter or A3\n"
    "  --dpi N       PNG resolution, stored in the file (default 300)\n"
    "  --targets     print every target of the settings' \"targets\" set on one page (the one\n"
    "                \"target\" without a set), each on its card with its id and dimensions\n"
    "  --target ID   print that target of the set alone",
    {"targets"},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
