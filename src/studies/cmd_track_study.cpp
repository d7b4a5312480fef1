// imagepro-studies track-study: reproduces thesis tables 3.1-3.3 — maximum, mean and
// standard deviation of the absolute estimation error of the target's corners for
// 2D-corner and 3D-parameter tracking, last 5 and 10 points, degree 0-3, over the
// sinusoid, saw-tooth and pendulum motions of the Virtual source — checks the default
// strategy (target inside the region in every frame, region size), and writes
// docs/tracking.md with the thesis's figures beside ours and the plots of figs. 3.2-3.3
// and 3.7-3.12. The prose is docs/tracking.md's own; the study fills in its measured places.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "cli/command.h"
#include "cli/plot_png.h"
#include "core/common/atomic_file.h"
#include "core/pipeline/engine.h"
#include "core/source/sources.h"
#include "core/tracking/tracker.h"
#include "studies/measured_doc.h"

namespace imagepro::studies {
namespace {

using namespace imagepro::cli;

struct Measurement {
  double t = 0.0;
  bool found = false;
  cv::Rect2d box;
  Pose pose;
  double true_x = NAN;  // the upper-left corner's u of the true pose's projected target
};

struct Stats {
  double max = 0.0, mean = 0.0, std = 0.0;
  int samples = 0;
};

struct Motion {
  const char* name;
  Settings settings;
};

// Thesis tables 3.1-3.3, [motion][2D 5, 2D 10, 3D 5, 3D 10][degree].
constexpr double kThesisMax[3][4][4] = {{{31, 3, 1, 11}, {54, 11, 2, 11}, {35, 2, 5, 3}, {55, 9, 3, 5}},
                                        {{20, 14, 8, 39}, {37, 23, 12, 14}, {22, 12, 10, 17}, {38, 21, 12, 20}},
                                        {{23, 11, 11, 8}, {31, 22, 11, 20}, {26, 11, 10, 9}, {33, 18, 11, 40}}};
constexpr double kThesisMean[3][4][4] = {
    {{15.8, 1.6, 0.4, 2.4}, {34.6, 4.6, 0.8, 0.8}, {21.8, 0.9, 1.5, 1.4}, {30.1, 4.2, 1.3, 1.6}},
    {{15.8, 0.8, 1.1, 4.4}, {30.0, 1.8, 1.6, 2.9}, {18.3, 1.7, 2.2, 2.0}, {30.7, 1.7, 3.7, 3.0}},
    {{12.3, 4.8, 2.6, 1.9}, {18.0, 7.4, 5.3, 5.3}, {11.5, 4.3, 3.2, 3.5}, {18.2, 5.5, 5.1, 4.8}}};
constexpr double kThesisStd[3][4][4] = {
    {{9.3, 1.0, 0.5, 2.3}, {16.0, 2.9, 0.6, 1.7}, {8.5, 0.6, 1.0, 0.9}, {16.4, 2.7, 0.9, 1.0}},
    {{4.0, 2.7, 1.8, 7.8}, {7.5, 5.2, 3.0, 4.3}, {3.4, 2.3, 2.4, 2.9}, {8.3, 3.5, 3.7, 3.8}},
    {{6.8, 3.0, 2.3, 1.8}, {8.6, 6.7, 2.9, 4.5}, {7.7, 2.8, 2.3, 2.3}, {9.2, 4.7, 3.0, 5.6}}};

std::vector<Motion> motions() {
  Settings base;
  base.virtual_scene.mode = RenderMode::Binary;
  base.virtual_scene.frame_rate_hz = 25.0;
  base.virtual_scene.initial_pose = Pose{0, 0, 0, 0, 0, 800};
  std::vector<Motion> out;
  for (const MotionKind kind : {MotionKind::Sinusoid, MotionKind::SawTooth}) {
    Motion m{kind == MotionKind::Sinusoid ? "sinusoid" : "saw-tooth", base};
    m.settings.virtual_scene.motion = {kind, PoseAxis::Tx, 150.0, 4.0};
    out.push_back(m);
  }
  Motion p{"pendulum", base};
  p.settings.virtual_scene.motion.kind = MotionKind::Pendulum;
  p.settings.virtual_scene.pendulum.pivot_mm = {0.0, -350.0, 900.0};
  p.settings.virtual_scene.pendulum.length_mm = 444.0;
  p.settings.virtual_scene.pendulum.amplitude_deg = 15.0;
  out.push_back(p);
  return out;
}

// The detections of every frame with tracking off: what the tracker is fed with.
std::vector<Measurement> measure(const Settings& settings, int frames) {
  Settings s = settings;
  s.pipeline.tracking.mode = TrackingMode::Off;
  VirtualSource source(s);
  Engine engine(s);
  FrameResult r;
  std::vector<Measurement> out;
  for (int i = 0; i < frames; ++i) {
    engine.step(source, r);
    Measurement m;
    m.t = r.timestamp_s;
    m.found = ok(r.status) && r.pose.has_value();
    m.box = cv::Rect2d(r.detected_region);
    if (r.pose) m.pose = *r.pose;
    if (r.truth) m.true_x = projectedTargetBox(s.camera(), s.target, *r.truth).x;
    out.push_back(m);
  }
  return out;
}

// Replays the detections through the tracker; the error is |measured - estimated| of
// each corner coordinate (thesis eq. 3.8), pooled over the four.
Stats replay(const std::vector<Measurement>& ms, const Settings& settings, const TrackingOptions& options,
             std::vector<double>* estimated_x0 = nullptr) {
  RegionTracker tracker;
  std::vector<double> errors;
  const cv::Size image(settings.camera().width, settings.camera().height);
  for (const Measurement& m : ms) {
    // The region about a single detection is a guess that the target stands still, not an
    // extrapolation (thesis 3.3 estimates from two points on): it is not counted.
    const bool guess = tracker.fromOneDetection();
    const auto region = tracker.estimate(options, settings.camera(), settings.target, m.t, image);
    const bool predicted = !guess && region.has_value() && tracker.lastPredictedBox().has_value();
    if (predicted && m.found) {
      const cv::Rect2d& p = *tracker.lastPredictedBox();
      errors.push_back(std::abs(p.x - m.box.x));
      errors.push_back(std::abs(p.y - m.box.y));
      errors.push_back(std::abs(p.br().x - m.box.br().x));
      errors.push_back(std::abs(p.br().y - m.box.br().y));
    }
    if (estimated_x0) estimated_x0->push_back(predicted ? tracker.lastPredictedBox()->x : NAN);
    if (m.found)
      tracker.observe(m.t, m.box, m.pose);
    else
      tracker.observeMiss();
  }
  Stats st;
  st.samples = static_cast<int>(errors.size());
  if (errors.empty()) return st;
  for (double e : errors) {
    st.max = std::max(st.max, e);
    st.mean += e;
  }
  st.mean /= errors.size();
  for (double e : errors) st.std += (e - st.mean) * (e - st.mean);
  st.std = std::sqrt(st.std / errors.size());
  return st;
}

// The thesis's figures 3.7-3.12: one motion tracked by one strategy (last 5 points),
// the upper-left corner's u estimated, measured and true over the frames.
struct TrackingFigure {
  std::size_t motion;
  TrackingMode mode;
  int degree;
  const char* thesis_figure;
  const char* file;  // beside the --plot file; empty: the --plot file itself
};

constexpr TrackingFigure kTrackingFigures[] = {
    {0, TrackingMode::Corners2D, 2, "3.7", ""},
    {0, TrackingMode::Parameters3D, 1, "3.8", "tracking-sinusoid-3d.png"},
    {1, TrackingMode::Corners2D, 2, "3.9", "tracking-saw-tooth-2d.png"},
    {1, TrackingMode::Parameters3D, 2, "3.10", "tracking-saw-tooth-3d.png"},
    {2, TrackingMode::Corners2D, 3, "3.11", "tracking-pendulum-2d.png"},
    {2, TrackingMode::Parameters3D, 3, "3.12", "tracking-pendulum-3d.png"},
};

std::string strategyName(TrackingMode mode) { return mode == TrackingMode::Corners2D ? "2D corners" : "3D parameters"; }

// Writes one figure; returns the largest |estimated - measured| of the plotted corner.
double plotTracking(const Motion& motion, const std::vector<Measurement>& measured, const TrackingFigure& f,
                    const std::string& path) {
  TrackingOptions o = motion.settings.pipeline.tracking;
  o.mode = f.mode;
  o.data_points = 5;
  o.degree = f.degree;
  std::vector<double> estimated;
  replay(measured, motion.settings, o, &estimated);
  std::string title = motion.name;
  title[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(title[0])));
  title += " motion, tracking " + strategyName(f.mode) + " (degree " + std::to_string(f.degree) +
           ", last 5 points): thesis fig. " + f.thesis_figure;
  Plot plot{title, "frame", "upper-left corner u [px]", {}};
  PlotSeries truth{"true", cv::Scalar(160, 160, 160), {}, {}}, meas{"measured", cv::Scalar(200, 80, 0), {}, {}},
      est{"estimated", cv::Scalar(0, 140, 0), {}, {}};
  double largest = 0.0;
  for (std::size_t i = 0; i < measured.size(); ++i) {
    const double x = static_cast<double>(i);
    truth.x.push_back(x);
    truth.y.push_back(measured[i].true_x);
    meas.x.push_back(x);
    meas.y.push_back(measured[i].found ? measured[i].box.x : NAN);
    est.x.push_back(x);
    est.y.push_back(estimated[i]);
    if (measured[i].found && std::isfinite(estimated[i]))
      largest = std::max(largest, std::abs(estimated[i] - measured[i].box.x));
  }
  plot.series = {truth, meas, est};
  std::string error;
  if (!writePlotPng(path, plot, error)) throw InputError(error);
  return largest;
}

struct DefaultCheck {
  int frames = 0, tracked = 0, inside = 0, found = 0;
  double mean_area = 0.0;
};

// The default strategy, live: is the whole target inside the searched region?
DefaultCheck checkDefault(const Settings& settings, int frames) {
  VirtualSource source(settings);
  Engine engine(settings);
  FrameResult r;
  DefaultCheck c;
  for (int i = 0; i < frames; ++i) {
    engine.step(source, r);
    ++c.frames;
    if (ok(r.status)) ++c.found;
    if (r.search_region.area() >= r.image_size.area()) continue;
    ++c.tracked;
    const cv::Rect2d box = projectedTargetBox(settings.camera(), settings.target, *r.truth);
    if ((box & cv::Rect2d(r.search_region)).area() >= box.area() - 1e-6) ++c.inside;
    c.mean_area += static_cast<double>(r.search_region.area()) / r.image_size.area();
  }
  if (c.tracked) c.mean_area /= c.tracked;
  return c;
}

std::string fmt(double v, int decimals) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

int run(const Args& args) {
  args.rejectUnknown({"frames", "out", "template", "plot"});
  const int frames = args.integer("frames", 250);
  if (frames < 20) throw UsageError("--frames must be at least 20");
  const std::string out_path = args.valueOr("out", "docs/tracking.md");
  const std::string template_path = args.valueOr("template", out_path);
  if (std::string error; !checkMeasuredDoc(template_path, error)) throw InputError(error);
  const std::string plot_path =
      args.valueOr("plot", (std::filesystem::path(out_path).parent_path() / "tracking-sinusoid.png").string());

  const auto ms = motions();
  // stats[motion][strategy][degree], strategy: 2D 5, 2D 10, 3D 5, 3D 10
  Stats stats[3][4][4];
  DefaultCheck defaults[3];
  std::vector<std::vector<Measurement>> measured;
  for (std::size_t k = 0; k < ms.size(); ++k) {
    std::fprintf(stderr, "%s: measuring %d frames ...\n", ms[k].name, frames);
    measured.push_back(measure(ms[k].settings, frames));
    for (int strategy = 0; strategy < 4; ++strategy)
      for (int degree = 0; degree <= 3; ++degree) {
        TrackingOptions o = ms[k].settings.pipeline.tracking;
        o.mode = strategy < 2 ? TrackingMode::Corners2D : TrackingMode::Parameters3D;
        o.data_points = strategy % 2 == 0 ? 5 : 10;
        o.degree = degree;
        stats[k][strategy][degree] = replay(measured.back(), ms[k].settings, o);
      }
    defaults[k] = checkDefault(ms[k].settings, frames);
  }

  // The plots of figs. 3.7-3.12.
  const std::filesystem::path plot_dir = std::filesystem::path(plot_path).parent_path();
  std::vector<std::string> figure_paths;
  std::vector<double> figure_largest;
  for (const TrackingFigure& f : kTrackingFigures) {
    figure_paths.push_back(*f.file ? (plot_dir / f.file).string() : plot_path);
    figure_largest.push_back(plotTracking(ms[f.motion], measured[f.motion], f, figure_paths.back()));
  }
  std::string error;

  // How the critical r was chosen (thesis figs. 3.2-3.3): the default strategy replayed
  // with each critical correlation coefficient, the estimation error over each motion.
  const std::vector<double> critical_r = {0.0, 0.5, 0.8, 0.9, 0.95, 0.98, 0.99, 0.995, 0.999};
  std::vector<std::vector<Stats>> sweep(ms.size());
  for (std::size_t k = 0; k < ms.size(); ++k)
    for (double r : critical_r) {
      TrackingOptions options = Settings{}.pipeline.tracking;
      options.min_r = r;
      sweep[k].push_back(replay(measured[k], ms[k].settings, options));
    }
  Plot r_plot{"Estimation error against the critical r (default strategy)", "-log10(1 - r): 1 is r = 0.9, 2 is 0.99",
              "max |error| [px]", {}};
  const cv::Scalar colours[3] = {cv::Scalar(200, 80, 0), cv::Scalar(0, 140, 0), cv::Scalar(0, 60, 220)};
  for (std::size_t k = 0; k < ms.size(); ++k) {
    PlotSeries series{ms[k].name, colours[k % 3], {}, {}};
    for (std::size_t i = 0; i < critical_r.size(); ++i) {
      series.x.push_back(-std::log10(1.0 - critical_r[i]));
      series.y.push_back(sweep[k][i].max);
    }
    r_plot.series.push_back(std::move(series));
  }
  const std::string r_plot_path = (plot_dir / "tracking-critical-r.png").string();
  if (!writePlotPng(r_plot_path, r_plot, error)) throw InputError(error);

  MeasuredValues v;
  v["command"] = "`imagepro-studies track-study --frames " + std::to_string(frames) + " --out " + out_path + "`";
  const char* keys[3] = {"table.max", "table.mean", "table.std"};
  for (int table = 0; table < 3; ++table) {
    std::ostringstream md;
    md << "| motion |";
    for (const char* strat : {"2D, 5", "2D, 10", "3D, 5", "3D, 10"})
      for (int d = 0; d <= 3; ++d) md << ' ' << strat << ", deg " << d << " |";
    md << "\n|---|";
    for (int i = 0; i < 16; ++i) md << "---|";
    md << "\n";
    for (std::size_t k = 0; k < ms.size(); ++k) {
      md << "| " << ms[k].name << " |";
      for (int s = 0; s < 4; ++s)
        for (int d = 0; d <= 3; ++d) {
          const Stats& st = stats[k][s][d];
          const double ours = table == 0 ? st.max : table == 1 ? st.mean : st.std;
          const double thesis = table == 0 ? kThesisMax[k][s][d] : table == 1 ? kThesisMean[k][s][d] : kThesisStd[k][s][d];
          md << ' ' << fmt(ours, 1) << " (" << fmt(thesis, table == 0 ? 0 : 1) << ") |";
        }
      md << "\n";
    }
    v[keys[table]] = md.str();
  }
  const TrackingOptions& d = Settings{}.pipeline.tracking;
  auto text = [](const auto& x) {
    std::ostringstream o;
    o << x;
    return o.str();
  };
  v["default.degree"] = text(d.degree);
  v["default.points"] = text(d.data_points);
  v["default.min_r"] = text(d.min_r);
  v["default.reduction"] = text(d.reduction_percent);
  v["default.enlarge_px"] = text(d.enlarge_px);
  v["default.enlarge_scale"] = text(d.enlarge_scale);
  v["default.enlarge_speed"] = text(d.enlarge_speed_scale);
  {
    std::ostringstream md;
    md << "| motion | frames | target found | tracked frames | target wholly inside | mean region / frame |\n"
          "|---|---|---|---|---|---|\n";
    for (std::size_t k = 0; k < ms.size(); ++k) {
      const DefaultCheck& c = defaults[k];
      md << "| " << ms[k].name << " | " << c.frames << " | " << c.found << " | " << c.tracked << " | " << c.inside
         << " (" << fmt(c.tracked ? 100.0 * c.inside / c.tracked : 0.0, 1) << " %) | " << fmt(100.0 * c.mean_area, 1)
         << " % |\n";
    }
    v["default.table"] = md.str();
  }
  {
    std::ostringstream md;
    md << "| critical r |";
    for (const Motion& m : ms) md << ' ' << m.name << " |";
    md << "\n|---|";
    for (std::size_t k = 0; k < ms.size(); ++k) md << "---|";
    md << "\n";
    for (std::size_t i = 0; i < critical_r.size(); ++i) {
      md << "| " << critical_r[i] << (critical_r[i] == d.min_r ? " (default)" : "") << " |";
      for (std::size_t k = 0; k < ms.size(); ++k)
        md << ' ' << fmt(sweep[k][i].max, 1) << " (" << fmt(sweep[k][i].mean, 2) << ") |";
      md << "\n";
    }
    v["critical.table"] = md.str();
  }
  v["critical.plot"] = "`" + r_plot_path + "`";
  {
    std::ostringstream table, images;
    table << "| thesis figure | motion | strategy | degree, points | largest error [px] | plot |\n"
             "|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < std::size(kTrackingFigures); ++i) {
      const TrackingFigure& f = kTrackingFigures[i];
      const std::string file = std::filesystem::path(figure_paths[i]).filename().string();
      table << "| " << f.thesis_figure << " | " << ms[f.motion].name << " | " << strategyName(f.mode) << " | "
            << f.degree << ", 5 | " << fmt(figure_largest[i], 1) << " | `" << file << "` |\n";
      images << (i ? "\n" : "") << "![" << ms[f.motion].name << ", " << strategyName(f.mode) << "](" << file
             << ")\n\n*Thesis fig. " << f.thesis_figure << ": " << ms[f.motion].name << ", " << strategyName(f.mode)
             << ", degree " << f.degree << ", last 5 points.*\n";
    }
    v["figures.table"] = table.str();
    v["figures.images"] = images.str();
  }

  // Every place of the doc is this study's: all are filled.
  if (!fillMeasuredDoc(template_path, out_path, v, {""}, error)) throw InputError(error);
  std::fprintf(stderr, "wrote %s, %s, the other figures beside it and %s\n", out_path.c_str(), plot_path.c_str(),
               r_plot_path.c_str());
  return 0;
}

const CommandRegistration kRegistration{{
    "track-study",
    "reproduce thesis tables 3.1-3.3 (tracking errors) and write docs/tracking.md with a plot",
    "usage: imagepro-studies track-study [--frames N] [--out FILE.md] [--template DOC] [--plot FILE.png]\n\n"
    "Runs the sinusoid, saw-tooth and pendulum motions of the Virtual source, replays\n"
    "the detections through every tracking strategy (2D/3D, last 5/10 points, degree\n"
    "0-3), and writes the maximum, mean and standard deviation of the corner estimation\n"
    "error beside the thesis's tables, the default strategy's live check, the default\n"
    "strategy's error against the critical correlation coefficient (figs. 3.2-3.3,\n"
    "plotted in tracking-critical-r.png) and the tracking runs of figs. 3.7-3.12: the\n"
    "upper-left corner's u estimated, measured and true over the frames, fig. 3.7 in\n"
    "the --plot file and the others beside it (tracking-sinusoid-3d.png,\n"
    "tracking-saw-tooth-2d.png, -3d, tracking-pendulum-2d.png, -3d). Defaults: 250\n"
    "frames, docs/tracking.md, docs/tracking-sinusoid.png. The figures fill the measured\n"
    "places (<!--m:NAME-->...<!--/m-->) of the hand-written doc given with --template\n"
    "(default: the --out file itself); its prose stays as written.",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::studies
