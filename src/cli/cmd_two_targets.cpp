// imagepro-cli two-targets: the distance and angle measurement of thesis 5.3.1. Both
// targets of every frame are reconstructed, with and without distortion correction;
// the distance between their centres and the angle between their normals are compared
// with the object's known values and summarised (mean, std, largest error) like thesis
// figs. 5.3-5.8 (core/analysis/two_target_study.h). Input: images, a video, a camera,
// or the virtual object.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/frame_input.h"
#include "cli/plot_png.h"
#include "core/analysis/two_target_study.h"
#include "core/common/atomic_file.h"
#include "core/common/pose_csv.h"

namespace imagepro::cli {
namespace {

using json = nlohmann::ordered_json;

// The frames of one virtual position, or all frames of other input.
struct Group {
  int position = 0;
  std::vector<const TwoTargetFrame*> frames;
};

std::string fmt(double v, int decimals) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string frameLabel(const TwoTargetFrame& f) { return f.name.empty() ? std::to_string(f.index) : f.name; }

const char* lightingName(const TwoTargetFrame& f) {
  if (!f.lighting) return "";
  return *f.lighting == StudyLighting::Natural ? "natural" : "extra";
}

json summaryJson(const ErrorSummary& s) {
  return json{{"mean", s.mean}, {"std", s.std}, {"max_abs", s.max_abs}};
}

void writePlots(const std::string& prefix, const Group& g, const TwoTargetObject& object) {
  const std::string tag = g.position > 0 ? "-position" + std::to_string(g.position) : "";
  const char* names[kCorrections] = {"distortion corrected", "not corrected"};
  const cv::Scalar colours[kCorrections] = {cv::Scalar(200, 80, 0), cv::Scalar(0, 100, 220)};
  for (int quantity = 0; quantity < 2; ++quantity) {
    Plot plot;
    const std::string where = g.position > 0 ? ", position " + std::to_string(g.position) : "";
    plot.title = (quantity == 0 ? "Distance between the target centres" : "Angle between the target normals") + where +
                 " (known " + fmt(quantity == 0 ? object.spacing_mm : object.angle_deg, 1) +
                 (quantity == 0 ? " mm)" : " deg)");
    plot.x_label = "frame";
    plot.y_label = quantity == 0 ? "distance [mm]" : "angle [deg]";
    for (int c = 0; c < kCorrections; ++c) {
      PlotSeries s{names[c], colours[c], {}, {}};
      for (std::size_t i = 0; i < g.frames.size(); ++i) {
        const TwoTargetFrame& f = *g.frames[i];
        s.x.push_back(static_cast<double>(i));
        s.y.push_back(!ok(f.status[c])           ? NAN
                      : quantity == 0 ? f.measurement[c].distance_mm
                                      : f.measurement[c].angle_deg);
      }
      plot.series.push_back(std::move(s));
    }
    const std::string path = prefix + tag + (quantity == 0 ? "-distance.png" : "-angle.png");
    std::string error;
    if (!writePlotPng(path, plot, error)) throw InputError(error);
    std::fprintf(stderr, "wrote %s\n", path.c_str());
  }
}

// One row per frame and correction, written whole or not at all.
void writeCsv(const std::string& path, const TwoTargetStudyResult& result) {
  const TwoTargetObject& object = result.object;
  std::string csv = "frame,position,lighting,correction,status,distance_mm,angle_deg,distance_error_mm,angle_error_deg\n";
  for (const TwoTargetFrame& f : result.frames)
    for (int c = 0; c < kCorrections; ++c) {
      csv += csvField(frameLabel(f)) + ',' + (f.position > 0 ? std::to_string(f.position) : "") + ',' +
             lightingName(f) + ',' + (kCorrectionOn[c] ? "on" : "off") + ',' + std::string(statusName(f.status[c]));
      const TwoTargetMeasurement& m = f.measurement[c];
      if (ok(f.status[c]))
        csv += ',' + fmt(m.distance_mm, 4) + ',' + fmt(m.angle_deg, 4) + ',' + fmt(m.distance_mm - object.spacing_mm, 4) +
               ',' + fmt(m.angle_deg - object.angle_deg, 4);
      else
        csv += ",,,,";
      csv += '\n';
    }
  std::string error;
  if (!writeFileAtomically(path, csv, error)) throw InputError(error);
  std::fprintf(stderr, "wrote %s\n", path.c_str());
}

TwoTargetStudyResult measureVirtual(const Args& args, const Settings& settings, const TwoTargetObject& object) {
  if (!args.positionals().empty()) throw UsageError("give either --virtual or image files, not both");
  for (const char* option : {"camera", "video", "size", "fps"})
    if (args.has(option)) throw UsageError(std::string("--") + option + " does not go with --virtual");
  VirtualTwoTargetParams params;
  params.object = object;
  const std::string lens = args.valueOr("lens", "thesis");
  if (lens != "thesis" && lens != "settings") throw UsageError("--lens: \"" + lens + "\" is not thesis or settings");
  params.thesis_lens = lens == "thesis";
  params.noise_sigma = args.number("noise", params.noise_sigma);
  if (!(params.noise_sigma >= 0.0)) throw UsageError("--noise must be 0 or more");
  if (!twoTargetObjectFits(object, settings.virtual_scene.card_size_mm))
    throw UsageError("--spacing too small for the cards: each target centre must lie at least half a card (" +
                     fmt(0.5 * settings.virtual_scene.card_size_mm, 1) + " mm) from the edge between the faces");
  params.frames_per_position = args.integer("frames", params.frames_per_position);
  if (params.frames_per_position < 2) throw UsageError("--frames must be at least 2");
  const std::string which = args.valueOr("position", "all");
  if (which == "1" || which == "2" || which == "3")
    params.position = std::stoi(which);
  else if (which != "all")
    throw UsageError("--position: \"" + which + "\" is not 1, 2, 3 or all");
  TwoTargetStudyResult result = runVirtualTwoTargets(settings, params, {});
  if (result.status == Status::InvalidSettings) throw UsageError(result.error);
  return result;
}

int run(const Args& args) {
  std::vector<std::string> known = kFrameInputOptions;
  known.insert(known.end(), {"format", "spacing", "angle", "position", "lens", "noise", "csv", "plot"});
  args.rejectUnknown(known);
  const std::string format = args.valueOr("format", "text");
  if (format != "text" && format != "json" && format != "markdown")
    throw UsageError("--format: \"" + format + "\" is not text, json or markdown");
  const Settings settings = loadConfigForInput(args);
  TwoTargetObject object;
  object.spacing_mm = args.number("spacing", object.spacing_mm);
  object.angle_deg = args.number("angle", object.angle_deg);
  if (!(object.spacing_mm > 0.0)) throw UsageError("--spacing must be above 0");
  if (!(object.angle_deg > 0.0 && object.angle_deg < 180.0)) throw UsageError("--angle must be between 0 and 180");
  const bool virtual_input = args.has("virtual");
  for (const char* option : {"position", "lens", "noise"})
    if (args.has(option) && !virtual_input) throw UsageError(std::string("--") + option + " goes with --virtual");

  TwoTargetStudyResult result;
  if (virtual_input) {
    result = measureVirtual(args, settings, object);
  } else {
    auto source = openFrameInput(args, settings);
    result = runTwoTargetSource(*source, settings, object, {});
    for (const TwoTargetFrame& f : result.frames)
      if (!f.error.empty()) std::fprintf(stderr, "%s: %s\n", frameLabel(f).c_str(), f.error.c_str());
  }

  if (const auto path = args.value("csv")) writeCsv(*path, result);

  if (const auto prefix = args.value("plot")) {
    std::vector<Group> groups;
    for (const TwoTargetFrame& f : result.frames) {
      if (groups.empty() || groups.back().position != f.position) groups.push_back(Group{f.position, {}});
      groups.back().frames.push_back(&f);
    }
    for (const Group& g : groups) writePlots(*prefix, g, object);
  }

  json summaries = json::array();
  std::string text = "known: distance " + fmt(object.spacing_mm, 2) + " mm, angle " + fmt(object.angle_deg, 2) +
                     " deg\n\n"
                     "position  correction  measured       distance error [mm]         angle error [deg]\n"
                     "                                     mean     std     max       mean     std     max\n";
  // The table of docs/case-studies.md, which tools/regenerate-docs.sh fills in from this.
  std::string markdown =
      "| position | correction | distance error mean / std / max [mm] | angle error mean / std / max [deg] |\n"
      "|---|---|---|---|\n";
  for (const TwoTargetSummary& s : result.summaries) {
    const ErrorSummary& d = s.distance_mm;
    const ErrorSummary& a = s.angle_deg;
    json j;
    if (s.position > 0) j["position"] = s.position;
    j["distortion_correction"] = s.correction;
    j["frames"] = s.frames;
    j["measured"] = d.samples;
    j["distance_error_mm"] = summaryJson(d);
    j["angle_error_deg"] = summaryJson(a);
    summaries.push_back(j);
    char line[200];
    std::snprintf(line, sizeof line, "%-9s %-11s %4d/%-4d  %7.3f %7.3f %7.3f    %7.3f %7.3f %7.3f\n",
                  s.position > 0 ? std::to_string(s.position).c_str() : "-", s.correction ? "on" : "off", d.samples,
                  s.frames, d.mean, d.std, d.max_abs, a.mean, a.std, a.max_abs);
    text += line;
    std::snprintf(line, sizeof line, "| %s | %s | %.3f / %.3f / %.3f | %.3f / %.3f / %.3f |\n",
                  s.position > 0 ? std::to_string(s.position).c_str() : "-", s.correction ? "on" : "off", d.mean,
                  d.std, d.max_abs, a.mean, a.std, a.max_abs);
    markdown += line;
  }
  if (format == "json") {
    json out;
    out["known"] = json{{"distance_mm", object.spacing_mm}, {"angle_deg", object.angle_deg}};
    out["summaries"] = summaries;
    std::printf("%s\n", out.dump(2).c_str());
  } else if (format == "markdown") {
    std::printf("%s", markdown.c_str());
  } else {
    std::printf("%s", text.c_str());
  }
  // Why frames were not measured, once per reason.
  for (const auto& [s, count] : result.failures)
    std::fprintf(stderr, "%d measurements: %s (%s)\n", count, std::string(statusName(s)).c_str(),
                 std::string(statusMessage(s)).c_str());
  return 0;
}

const CommandRegistration kRegistration{{
    "two-targets",
    "distance and angle between two targets against their known values (thesis 5.3.1)",
    std::string("usage: imagepro-cli two-targets [--config FILE] [--spacing MM] [--angle DEG]\n"
                "                                [--format text|json|markdown] [--csv FILE] [--plot PREFIX]\n"
                "                                INPUT\n\n") +
        kFrameInputHelp +
        "\n       --virtual renders the object of thesis fig. 5.2: two targets on two faces meeting in an\n"
        "          edge towards the camera, for --frames N (default 40) per position; the first half of\n"
        "          them in natural light, the second half with extra lights (thesis 5.3.1).\n\n"
        "Both targets of every frame are reconstructed, with and without distortion correction; the\n"
        "distance between their centres and the angle between their normals are compared with the\n"
        "known values, and the errors summarised (mean, std, largest |error|) per position.\n"
        "  --format F        text (default), json, or markdown: the summary as a Markdown table\n"
        "  --spacing MM      known distance between the target centres (default 200)\n"
        "  --angle DEG       known angle between the target normals (default 90: perpendicular faces)\n"
        "  --position P      virtual: object position 1, 2, 3 or all (default all)\n"
        "  --lens L          virtual: thesis (render and correct with the thesis camera's distortion,\n"
        "                    the default) or settings (the settings' camera)\n"
        "  --noise SIGMA     virtual: image noise in grey levels (default 2)\n"
        "  --csv FILE        one row per frame and correction: status, distance, angle, their errors\n"
        "  --plot PREFIX     PNG charts of distance and angle per frame (PREFIX[-positionP]-distance.png,\n"
        "                    -angle.png), like thesis figs. 5.3-5.8",
    {"virtual"},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
