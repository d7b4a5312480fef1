// imagepro-studies ellipse-library: the synthetic library of thesis appendix B classified
// as `imagepro-cli library DIR` then `imagepro-cli detect DIR` classify it (an image is an
// ellipse when the ellipse stage reports Ok), by each ellipse method and accept rule, on
// the binary library and on its grey, blurred and noisy versions. Prints the Markdown
// tables of docs/ellipse-detection.md; with --plots, the thesis's per-image figures of
// the library (2.18, 2.20, 2.21, 2.23, 2.25 and B.1-B.6).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/plot_png.h"
#include "core/ellipse/bennett.h"
#include "core/ellipse/direct_fit.h"
#include "core/ellipse/synthetic_library.h"
#include "core/pipeline/stage_chain.h"
#include "studies/report.h"

namespace imagepro::studies {
namespace {

using cli::Args;
using cli::CommandRegistration;
using cli::InputError;
using cli::UsageError;

// What a detector made of one version of the library.
struct Tally {
  int ellipses = 0, rectangles = 0;      // in the library
  std::vector<int> missed, accepted;     // the images' numbers in their tables
  int found() const { return ellipses - static_cast<int>(missed.size()); }
};

// A rule of the tables: the settings files of docs/ellipse-detection.md over shapes.json.
enum class Rule { Default, Sampson, Bennett, BennettThesis };

// shapes.json: one global threshold, and no check that an ellipse views a circle tilted
// at most target_max_tilt_deg (the library's thinnest ellipses do not).
Settings settingsFor(const Settings& base, Rule rule, int manual_threshold) {
  Settings s = base;
  s.pipeline.level = ApplicationLevel::Ellipse;
  s.pipeline.binarization.mode = Binarization::Global;
  EllipseOptions& e = s.pipeline.ellipse;
  e.target_max_tilt_deg = 90.0;
  if (rule == Rule::Sampson) e.accept_rule = FitAcceptRule::SampsonDistance;
  if (rule == Rule::Bennett || rule == Rule::BennettThesis) e.method = EllipseMethod::Bennett;
  if (rule == Rule::BennettThesis) {  // bennett-thesis.json: thesis 2.6.1's windows
    e.bennett_min_score = 550.0;
    e.bennett_max_score = 840.0;
    e.bennett_min_quality = 255.0;
    e.bennett_max_quality = 375.0;
    e.bennett_min_peak_fraction = 0.0;
    e.bennett_max_relative_error = 1e9;  // the thesis's rules alone
  }
  if (manual_threshold >= 0) {  // t125.json
    s.pipeline.threshold.method = ThresholdMethod::Manual;
    s.pipeline.threshold.manual_value = manual_threshold;
  }
  return s;
}

// One version of the library: binary, or grey as `imagepro-cli library --grey|--blur|--noise`.
struct Version {
  const char* name;
  bool grey;
  double blur, noise;
  int manual_threshold;  // -1: the settings' (AT-Mod)
};

std::vector<cv::Mat> render(const Version& v) {
  LibraryGreyOptions grey;
  grey.blur_sigma_px = v.blur;
  grey.noise_sigma = v.noise;
  std::vector<cv::Mat> images;
  for (const LibraryEntry& e : syntheticLibrary()) {
    images.emplace_back();
    if (v.grey) renderLibraryImageGrey(e, grey, images.back());
    else renderLibraryImage(e, images.back());
  }
  return images;
}

Tally classify(const std::vector<cv::Mat>& images, const Settings& settings) {
  Tally t;
  StageChain chain;
  FrameResult result;
  const auto library = syntheticLibrary();
  for (std::size_t i = 0; i < library.size(); ++i) {
    const LibraryEntry& e = library[i];
    runStageChain(settings, images[i], {}, TargetsToReconstruct::Best, chain, result);
    const bool accepted = result.status == Status::Ok;
    if (e.shape == LibraryShape::Ellipse) {
      ++t.ellipses;
      if (!accepted) t.missed.push_back(e.number);
    } else {
      ++t.rectangles;
      if (accepted) t.accepted.push_back(e.number);
    }
  }
  return t;
}

std::string numbers(const std::vector<int>& v) {
  std::string s;
  for (const int n : v) s += (s.empty() ? "" : ", ") + std::to_string(n);
  return s;
}

// Image numbers are listed when there are few enough to read.
constexpr std::size_t kListedAtMost = 10;

std::string methodsTable(const Settings& base) {
  const std::vector<cv::Mat> images = render(Version{"binary", false, 0.0, 0.0, -1});
  struct Row {
    const char* name;
    Rule rule;
  };
  const Row rows[] = {
      {"direct fit, E_rel ≤ 0.02 + trace (default)", Rule::Default},
      {"direct fit, Sampson ≤ 0.5 px + trace", Rule::Sampson},
      {"Bennett", Rule::Bennett},
      {"Bennett at the thesis's thresholds (score 550-840, quality 255-375, no peak-share or fit rule)", Rule::BennettThesis},
  };
  std::string md =
      "| method | ellipses found | rectangles accepted | source |\n"
      "| --- | --- | --- | --- |\n"
      "| thesis, direct fit (E_rel ≤ 0.02) | all | none | thesis 2.6.2 |\n"
      "| thesis, Bennett | 63 of 72 (9 missed) | 7 of 66 | thesis 2.6.1 |\n";
  for (const Row& row : rows) {
    std::fprintf(stderr, "binary library, %s ...\n", row.name);
    const Tally t = classify(images, settingsFor(base, row.rule, -1));
    std::string found = format("%d of %d", t.found(), t.ellipses);
    if (!t.missed.empty() && t.missed.size() <= kListedAtMost)
      found += format(" (%zu missed: %s)", t.missed.size(), numbers(t.missed).c_str());
    std::string accepted = format("%zu of %d", t.accepted.size(), t.rectangles);
    if (!t.accepted.empty() && t.accepted.size() <= kListedAtMost) accepted += " (" + numbers(t.accepted) + ")";
    md += format("| %s | %s | %s | this implementation |\n", row.name, found.c_str(), accepted.c_str());
  }
  return md;
}

std::string versionsTable(const Settings& base) {
  const Version versions[] = {
      {"binary", false, 0.0, 0.0, -1},
      {"grey (anti-aliased)", true, 0.0, 0.0, -1},
      {"blur σ 1.5 px, threshold 125", true, 1.5, 0.0, 125},
      {"noise σ 10", true, 0.0, 10.0, -1},
      {"blur σ 1.5 + noise σ 5", true, 1.5, 5.0, -1},
  };
  std::string md =
      "| library | direct fit, E_rel (default): ellipses found, rectangles accepted | direct fit, Sampson | Bennett |\n"
      "| --- | --- | --- | --- |\n";
  for (const Version& v : versions) {
    std::fprintf(stderr, "%s ...\n", v.name);
    const std::vector<cv::Mat> images = render(v);
    md += format("| %s |", v.name);
    for (const Rule rule : {Rule::Default, Rule::Sampson, Rule::Bennett}) {
      const Tally t = classify(images, settingsFor(base, rule, v.manual_threshold));
      // The default's misses are named; every column names the rectangles it accepts.
      std::string cell = format("%d/%d", t.found(), t.ellipses);
      if (rule == Rule::Default && !t.missed.empty() && t.missed.size() <= kListedAtMost)
        cell += " (missed " + numbers(t.missed) + ")";
      cell += format(", %zu/%d", t.accepted.size(), t.rectangles);
      if (!t.accepted.empty() && t.accepted.size() <= kListedAtMost) cell += " (" + numbers(t.accepted) + ")";
      md += " " + cell + " |";
    }
    md += "\n";
  }
  return md;
}

// What the thesis plotted per library image, of the image's longest path (its outline).
struct ImageMeasures {
  const LibraryEntry* entry = nullptr;
  double edge_pixels = NAN, score = NAN, quality = NAN, symmetry = NAN, share = NAN, relative_error = NAN;
};

std::vector<ImageMeasures> measureLibrary(const Settings& base) {
  const Settings settings = settingsFor(base, Rule::Bennett, -1);
  const EllipseOptions& o = settings.pipeline.ellipse;
  const std::vector<cv::Mat> images = render(Version{"binary", false, 0.0, 0.0, -1});
  StageChain chain;
  FrameResult result;
  BennettWorkspace ws;
  std::vector<ImageMeasures> out;
  const auto library = syntheticLibrary();
  for (std::size_t i = 0; i < library.size(); ++i) {
    ImageMeasures m;
    m.entry = &library[i];
    runStageChain(settings, images[i], {}, TargetsToReconstruct::Best, chain, result);
    std::size_t longest = kNoPath;
    for (std::size_t p = 0; p < chain.paths.pathCount(); ++p)
      if (longest == kNoPath || chain.paths.path(p).size() > chain.paths.path(longest).size()) longest = p;
    if (longest != kNoPath) {
      const auto path = chain.paths.path(longest);
      m.edge_pixels = static_cast<double>(path.size());
      BennettResult r;  // the whole accumulation, as the rules read it
      if (ok(bennettAccumulate(path, o.bennett_max_points, ws, r))) {
        m.score = r.score;
        m.quality = r.quality;
        m.share = r.peak_fraction;
        m.symmetry = r.symmetry_px / (r.border_distance_px + 1.0);
      }
      EllipseFit fit;
      if (ok(fitEllipseDirect(path, fit))) m.relative_error = fit.relative_error;
    }
    out.push_back(m);
  }
  return out;
}

// One figure: a value per image, rectangles and ellipses each against their table's
// numbers, and the rule's limits as horizontal lines.
struct Figure {
  const char* file;
  const char* title;
  const char* y_label;
  double (*value)(const ImageMeasures&);
  std::vector<std::pair<std::string, double>> limits = {};         // the settings' (green)
  std::vector<std::pair<std::string, double>> thesis_limits = {};  // thesis 2.6.1's (grey)
};

void writeLibraryPlots(const std::vector<ImageMeasures>& measures, const std::vector<Figure>& figures,
                       const std::filesystem::path& dir) {
  const cv::Scalar rectangle_colour(0, 60, 220), ellipse_colour(200, 80, 0), limit_colour(0, 140, 0),
      thesis_colour(150, 150, 150);
  for (const Figure& f : figures) {
    cli::Plot plot{f.title, "image number (table B.1 for rectangles, B.2 for ellipses)", f.y_label, {}};
    cli::PlotSeries rectangles{"rectangles", rectangle_colour, {}, {}, true};
    cli::PlotSeries ellipses{"ellipses", ellipse_colour, {}, {}, true};
    double last = 0.0;
    for (const ImageMeasures& m : measures) {
      cli::PlotSeries& s = m.entry->shape == LibraryShape::Rectangle ? rectangles : ellipses;
      s.x.push_back(m.entry->number);
      s.y.push_back(f.value(m));
      last = std::max(last, static_cast<double>(m.entry->number));
    }
    plot.series = {rectangles, ellipses};
    for (const auto& [name, y] : f.limits) plot.series.push_back({name, limit_colour, {1.0, last}, {y, y}});
    for (const auto& [name, y] : f.thesis_limits) plot.series.push_back({name, thesis_colour, {1.0, last}, {y, y}});
    std::string error;
    if (!cli::writePlotPng((dir / f.file).string(), plot, error)) throw InputError(error);
    std::fprintf(stderr, "wrote %s\n", (dir / f.file).string().c_str());
  }
}

void libraryPlots(const Settings& base, const std::filesystem::path& dir) {
  const EllipseOptions& o = settingsFor(base, Rule::Bennett, -1).pipeline.ellipse;
  const std::vector<Figure> figures = {
      {"ellipse-library-edge-pixels.png", "Edge pixels of the outline (thesis fig. 2.18)", "edge pixels",
       [](const ImageMeasures& m) { return m.edge_pixels; }, {}},
      {"ellipse-library-symmetry.png", "Bennett: symmetry radius / distance to the accumulator's border (fig. 2.20)",
       "symmetry (1: to the border)", [](const ImageMeasures& m) { return m.symmetry; }, {}},
      {"ellipse-library-score.png", "Bennett: score of the absolute peak (fig. 2.21)", "score",
       [](const ImageMeasures& m) { return m.score; }, {{"min score", o.bennett_min_score}},
       {{"thesis: 550", 550.0}, {"thesis: 840", 840.0}}},
      {"ellipse-library-quality.png", "Bennett: quality factor (fig. 2.23)", "quality factor",
       [](const ImageMeasures& m) { return m.quality; }, {}, {{"thesis: 255", 255.0}, {"thesis: 375", 375.0}}},
      {"ellipse-library-peak-share.png", "Bennett: share of the path's pairs at the peak", "peak share",
       [](const ImageMeasures& m) { return m.share; }, {{"min share", o.bennett_min_peak_fraction}}},
      {"ellipse-library-relative-error.png", "Direct fit: relative error E_rel (fig. 2.25), log scale", "log10 E_rel",
       [](const ImageMeasures& m) { return std::log10(m.relative_error); },
       {{"max E_rel", std::log10(o.max_relative_error)}}},
      {"ellipse-library-length.png", "Rectangle width, ellipse major length (figs. B.1, B.2)", "length [px]",
       [](const ImageMeasures& m) { return m.entry->length_px; }, {}},
      {"ellipse-library-rotation.png", "Rotation (figs. B.3, B.4)", "rotation [deg]",
       [](const ImageMeasures& m) { return m.entry->rotation_deg; }, {}},
      {"ellipse-library-aspect.png", "Aspect ratio (figs. B.5, B.6)", "width / height, major / minor",
       [](const ImageMeasures& m) { return m.entry->aspect; }, {}},
  };
  writeLibraryPlots(measureLibrary(base), figures, dir);
}

int run(const Args& args) {
  args.rejectUnknown({"table", "plots"});
  if (const auto dir = args.value("plots")) {
    if (args.has("table")) throw UsageError("--plots and --table: one or the other");
    libraryPlots(cli::loadConfig(args), cli::outputFolder("plots", *dir));
    return 0;
  }
  const std::string table = args.valueOr("table", "methods");
  if (table != "methods" && table != "versions")
    throw UsageError("--table: \"" + table + "\" is not methods or versions");
  const Settings settings = cli::loadConfig(args);
  const std::string md = table == "methods" ? methodsTable(settings) : versionsTable(settings);
  std::printf("%s", md.c_str());
  return 0;
}

const CommandRegistration kRegistration{{
    "ellipse-library",
    "classify the synthetic library of appendix B by each ellipse rule (docs/ellipse-detection.md)",
    "usage: imagepro-studies ellipse-library [--table methods|versions | --plots DIR] [--config FILE]\n\n"
    "Renders the 67 rectangles and 70 ellipses of thesis tables B.1 and B.2 and runs the\n"
    "detector's chain up to the ellipse stage on each, as imagepro-cli library and detect\n"
    "do, with one global threshold and no tilt check (shapes.json of the doc); an image is\n"
    "an ellipse when the stage reports Ok. Prints a Markdown table:\n"
    "  --table methods    the binary library by the direct fit's two accept rules, Bennett\n"
    "                     and Bennett at the thesis's thresholds, beside the thesis (default)\n"
    "  --table versions   the binary, grey, blurred (threshold 125), noisy, and blurred and\n"
    "                     noisy libraries by the direct fit's two rules and Bennett\n"
    "  --plots DIR        instead of a table, the thesis's per-image figures of the binary\n"
    "                     library as PNG charts in DIR, of each image's outline (its\n"
    "                     longest path), rectangles and ellipses against their tables'\n"
    "                     numbers: ellipse-library-edge-pixels.png (fig. 2.18), -symmetry\n"
    "                     (2.20: Bennett's symmetry radius over the distance to the\n"
    "                     accumulator's farthest border, 1 when symmetric to it), -score\n"
    "                     (2.21), -quality (2.23), -peak-share, -relative-error (2.25,\n"
    "                     log10 of E_rel), -length, -rotation, -aspect (B.1-B.6); the\n"
    "                     settings' limits as lines. Bennett accumulates in full here.",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::studies
