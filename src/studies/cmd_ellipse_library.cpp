// imagepro-studies ellipse-library: the synthetic library of thesis appendix B classified
// as `imagepro-cli library DIR` then `imagepro-cli detect DIR` classify it (an image is an
// ellipse when the ellipse stage reports Ok), by each ellipse method and accept rule, on
// the binary library and on its grey, blurred and noisy versions. Prints the Markdown
// tables of docs/ellipse-detection.md.
#include <cstdio>
#include <string>
#include <vector>

#include "cli/command.h"
#include "core/ellipse/synthetic_library.h"
#include "core/pipeline/stage_chain.h"
#include "studies/report.h"

namespace imagepro::studies {
namespace {

using cli::Args;
using cli::CommandRegistration;
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

int run(const Args& args) {
  args.rejectUnknown({"table"});
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
    "usage: imagepro-studies ellipse-library [--table methods|versions] [--config FILE]\n\n"
    "Renders the 67 rectangles and 70 ellipses of thesis tables B.1 and B.2 and runs the\n"
    "detector's chain up to the ellipse stage on each, as imagepro-cli library and detect\n"
    "do, with one global threshold and no tilt check (shapes.json of the doc); an image is\n"
    "an ellipse when the stage reports Ok. Prints a Markdown table:\n"
    "  --table methods    the binary library by the direct fit's two accept rules, Bennett\n"
    "                     and Bennett at the thesis's thresholds, beside the thesis (default)\n"
    "  --table versions   the binary, grey, blurred (threshold 125), noisy, and blurred and\n"
    "                     noisy libraries by the direct fit's two rules and Bennett",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::studies
