// imagepro-cli two-targets: the distance and angle measurement of thesis 5.3.1. Both
// targets of every frame are reconstructed, with and without distortion correction;
// the distance between their centres and the angle between their normals are compared
// with the object's known values and summarised (mean, std, largest error) like thesis
// figs. 5.3-5.8. Input: images, a video, a camera, or the virtual object.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/frame_input.h"
#include "cli/plot_png.h"
#include "core/analysis/error_summary.h"
#include "core/analysis/two_targets.h"
#include "core/common/pose_csv.h"

namespace imagepro::cli {
namespace {

using json = nlohmann::ordered_json;

// The two ways every frame is processed.
constexpr bool kCorrections[2] = {true, false};

struct FrameMeasure {
  std::string frame;
  int position = 0;  // virtual object position, 0 for other input
  const char* lighting = "";
  Status status[2] = {Status::Stopped, Status::Stopped};  // [corrected, uncorrected]
  TwoTargetMeasurement m[2];
};

struct Group {
  int position = 0;
  std::vector<const FrameMeasure*> frames;
};

std::string fmt(double v, int decimals) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

// Errors of the frames measured with correction `c`.
void errors(const Group& g, int c, const TwoTargetObject& object, std::vector<double>& distance,
            std::vector<double>& angle) {
  distance.clear();
  angle.clear();
  for (const FrameMeasure* f : g.frames) {
    if (!ok(f->status[c])) continue;
    distance.push_back(f->m[c].distance_mm - object.spacing_mm);
    angle.push_back(f->m[c].angle_deg - object.angle_deg);
  }
}

json summaryJson(const ErrorSummary& s) {
  return json{{"mean", s.mean}, {"std", s.std}, {"max_abs", s.max_abs}};
}

void writePlots(const std::string& prefix, const Group& g, const TwoTargetObject& object) {
  const std::string tag = g.position > 0 ? "-position" + std::to_string(g.position) : "";
  const char* names[2] = {"distortion corrected", "not corrected"};
  const cv::Scalar colours[2] = {cv::Scalar(200, 80, 0), cv::Scalar(0, 100, 220)};
  for (int quantity = 0; quantity < 2; ++quantity) {
    Plot plot;
    const std::string where = g.position > 0 ? ", position " + std::to_string(g.position) : "";
    plot.title = (quantity == 0 ? "Distance between the target centres" : "Angle between the target normals") + where +
                 " (known " + fmt(quantity == 0 ? object.spacing_mm : object.angle_deg, 1) +
                 (quantity == 0 ? " mm)" : " deg)");
    plot.x_label = "frame";
    plot.y_label = quantity == 0 ? "distance [mm]" : "angle [deg]";
    for (int c = 0; c < 2; ++c) {
      PlotSeries s{names[c], colours[c], {}, {}};
      for (std::size_t i = 0; i < g.frames.size(); ++i) {
        const FrameMeasure& f = *g.frames[i];
        s.x.push_back(static_cast<double>(i));
        s.y.push_back(!ok(f.status[c]) ? NAN : quantity == 0 ? f.m[c].distance_mm : f.m[c].angle_deg);
      }
      plot.series.push_back(std::move(s));
    }
    const std::string path = prefix + tag + (quantity == 0 ? "-distance.png" : "-angle.png");
    std::string error;
    if (!writePlotPng(path, plot, error)) throw InputError(error);
    std::fprintf(stderr, "wrote %s\n", path.c_str());
  }
}

int run(const Args& args) {
  std::vector<std::string> known = kFrameInputOptions;
  known.insert(known.end(), {"format", "spacing", "angle", "position", "lens", "noise", "csv", "plot"});
  args.rejectUnknown(known);
  const std::string format = args.valueOr("format", "text");
  if (format != "text" && format != "json") throw UsageError("--format: \"" + format + "\" is not text or json");
  Settings settings = loadConfig(args);
  TwoTargetObject object;
  object.spacing_mm = args.number("spacing", object.spacing_mm);
  object.angle_deg = args.number("angle", object.angle_deg);
  if (!(object.spacing_mm > 0.0)) throw UsageError("--spacing must be above 0");
  if (!(object.angle_deg > 0.0 && object.angle_deg < 180.0)) throw UsageError("--angle must be between 0 and 180");
  const bool virtual_input = args.has("virtual");
  for (const char* option : {"position", "lens", "noise"})
    if (args.has(option) && !virtual_input) throw UsageError(std::string("--") + option + " goes with --virtual");

  std::vector<FrameMeasure> measures;
  MultiTargetWorkspace ws;
  MultiTargetResult result;
  Settings runs[2] = {settings, settings};
  auto measure = [&](const cv::Mat& image, FrameMeasure& f) {
    for (int c = 0; c < 2; ++c) {
      f.status[c] = reconstructAllTargets(runs[c], image, ws, result);
      if (ok(f.status[c])) f.status[c] = measureTwoTargets(result, f.m[c]);
    }
  };
  auto prepareRuns = [&] {
    for (int c = 0; c < 2; ++c) {
      runs[c] = settings;
      runs[c].pipeline.reconstruction.distortion_correction = kCorrections[c];
    }
  };

  if (virtual_input) {
    if (!args.positionals().empty()) throw UsageError("give either --virtual or image files, not both");
    for (const char* option : {"camera", "video", "size", "fps"})
      if (args.has(option)) throw UsageError(std::string("--") + option + " does not go with --virtual");
    const std::string lens = args.valueOr("lens", "thesis");
    if (lens == "thesis")
      settings.camera.distortion = kThesisCameraDistortion;
    else if (lens != "settings")
      throw UsageError("--lens: \"" + lens + "\" is not thesis or settings");
    settings.virtual_scene.noise_sigma = args.number("noise", 2.0);
    if (!(settings.virtual_scene.noise_sigma >= 0.0)) throw UsageError("--noise must be 0 or more");
    if (!twoTargetObjectFits(object, settings.virtual_scene.card_size_mm))
      throw UsageError("--spacing too small for the cards: each target centre must lie at least half a card (" +
                       fmt(0.5 * settings.virtual_scene.card_size_mm, 1) + " mm) from the edge between the faces");
    const int frames = args.integer("frames", 40);
    if (frames < 2) throw UsageError("--frames must be at least 2");
    std::vector<int> positions;
    const std::string which = args.valueOr("position", "all");
    if (which == "all")
      positions = {1, 2, 3};
    else if (which == "1" || which == "2" || which == "3")
      positions = {std::stoi(which)};
    else
      throw UsageError("--position: \"" + which + "\" is not 1, 2, 3 or all");
    prepareRuns();
    TwoTargetRenderWorkspace render_ws;
    cv::Mat image;
    measures.reserve(positions.size() * static_cast<std::size_t>(frames));
    for (const int position : positions) {
      const Pose object_pose = twoTargetStudyPosition(position);
      for (int i = 0; i < frames; ++i) {
        // The thesis's order: natural light for the first half, extra lights for the second.
        const StudyLighting lighting = i < frames / 2 ? StudyLighting::Natural : StudyLighting::Extra;
        VirtualSceneOptions scene = settings.virtual_scene;
        applyStudyLighting(lighting, scene);
        renderTwoTargets(settings.camera, settings.target, scene, object, object_pose, image,
                         static_cast<std::uint64_t>(measures.size()), render_ws);
        FrameMeasure f;
        f.frame = std::to_string(measures.size());
        f.position = position;
        f.lighting = lighting == StudyLighting::Natural ? "natural" : "extra";
        measure(image, f);
        measures.push_back(f);
      }
    }
  } else {
    prepareRuns();
    auto source = openFrameInput(args, settings);
    Frame frame;
    for (;;) {
      const Status s = source->next(frame);
      if (s == Status::EndOfStream) break;
      FrameMeasure f;
      f.frame = frame.name.empty() ? std::to_string(frame.index) : frame.name;
      if (ok(s)) {
        measure(frame.image, f);
      } else {
        f.status[0] = f.status[1] = s;
        if (!source->lastError().empty()) std::fprintf(stderr, "%s: %s\n", f.frame.c_str(), source->lastError().c_str());
      }
      measures.push_back(f);
    }
  }

  if (const auto path = args.value("csv")) {
    std::ofstream out(*path);
    if (!out) throw InputError(*path + ": cannot open for writing");
    out << "frame,position,lighting,correction,status,distance_mm,angle_deg,distance_error_mm,angle_error_deg\n";
    for (const FrameMeasure& f : measures)
      for (int c = 0; c < 2; ++c) {
        out << csvField(f.frame) << ',' << (f.position > 0 ? std::to_string(f.position) : "") << ',' << f.lighting
            << ',' << (kCorrections[c] ? "on" : "off") << ',' << statusName(f.status[c]);
        if (ok(f.status[c]))
          out << ',' << fmt(f.m[c].distance_mm, 4) << ',' << fmt(f.m[c].angle_deg, 4) << ','
              << fmt(f.m[c].distance_mm - object.spacing_mm, 4) << ',' << fmt(f.m[c].angle_deg - object.angle_deg, 4);
        else
          out << ",,,,";
        out << '\n';
      }
    if (!out.flush()) throw InputError(*path + ": cannot be written");
    std::fprintf(stderr, "wrote %s\n", path->c_str());
  }

  // One group per virtual position, or one for the whole input.
  std::vector<Group> groups;
  for (const FrameMeasure& f : measures) {
    if (groups.empty() || groups.back().position != f.position) groups.push_back(Group{f.position, {}});
    groups.back().frames.push_back(&f);
  }
  if (const auto prefix = args.value("plot"))
    for (const Group& g : groups) writePlots(*prefix, g, object);

  json summaries = json::array();
  std::vector<double> distance, angle;
  std::string text = "known: distance " + fmt(object.spacing_mm, 2) + " mm, angle " + fmt(object.angle_deg, 2) +
                     " deg\n\n"
                     "position  correction  measured       distance error [mm]         angle error [deg]\n"
                     "                                     mean     std     max       mean     std     max\n";
  for (const Group& g : groups)
    for (int c = 0; c < 2; ++c) {
      errors(g, c, object, distance, angle);
      const ErrorSummary d = summarizeErrors(distance), a = summarizeErrors(angle);
      json j;
      if (g.position > 0) j["position"] = g.position;
      j["distortion_correction"] = kCorrections[c];
      j["frames"] = g.frames.size();
      j["measured"] = d.samples;
      j["distance_error_mm"] = summaryJson(d);
      j["angle_error_deg"] = summaryJson(a);
      summaries.push_back(j);
      char line[200];
      std::snprintf(line, sizeof line, "%-9s %-11s %4d/%-4zu  %7.3f %7.3f %7.3f    %7.3f %7.3f %7.3f\n",
                    g.position > 0 ? std::to_string(g.position).c_str() : "-", kCorrections[c] ? "on" : "off",
                    d.samples, g.frames.size(), d.mean, d.std, d.max_abs, a.mean, a.std, a.max_abs);
      text += line;
    }
  if (format == "json") {
    json out;
    out["known"] = json{{"distance_mm", object.spacing_mm}, {"angle_deg", object.angle_deg}};
    out["summaries"] = summaries;
    std::printf("%s\n", out.dump(2).c_str());
  } else {
    std::printf("%s", text.c_str());
  }
  // Why frames were not measured, once per reason.
  std::vector<std::pair<Status, int>> reasons;
  for (const FrameMeasure& f : measures)
    for (const Status s : f.status) {
      if (ok(s)) continue;
      auto it = std::find_if(reasons.begin(), reasons.end(), [&](const auto& r) { return r.first == s; });
      if (it == reasons.end())
        reasons.emplace_back(s, 1);
      else
        ++it->second;
    }
  for (const auto& [s, count] : reasons)
    std::fprintf(stderr, "%d measurements: %s (%s)\n", count, std::string(statusName(s)).c_str(),
                 std::string(statusMessage(s)).c_str());
  return 0;
}

const CommandRegistration kRegistration{{
    "two-targets",
    "distance and angle between two targets against their known values (thesis 5.3.1)",
    std::string("usage: imagepro-cli two-targets [--config FILE] [--spacing MM] [--angle DEG]\n"
                "                                [--format text|json] [--csv FILE] [--plot PREFIX] INPUT\n\n") +
        kFrameInputHelp +
        "\n       --virtual renders the object of thesis fig. 5.2: two targets on two faces meeting in an\n"
        "          edge towards the camera, for --frames N (default 40) per position; the first half of\n"
        "          them in natural light, the second half with extra lights (thesis 5.3.1).\n\n"
        "Both targets of every frame are reconstructed, with and without distortion correction; the\n"
        "distance between their centres and the angle between their normals are compared with the\n"
        "known values, and the errors summarised (mean, std, largest |error|) per position.\n"
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
