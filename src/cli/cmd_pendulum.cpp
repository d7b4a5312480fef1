// imagepro-cli pendulum: the g measurement of thesis 5.3.2. From a reconstructed
// sequence of a target on a swinging pendulum (a data-out or reconstruct CSV, or frames
// reconstructed here from a video, images, a camera or the virtual pendulum): the
// period, the pivot and length by the constrained sphere fit of eqs. 5.2-5.6, and g by
// eq. 5.1, with their uncertainties (core/analysis/pendulum_study.h); plots of the
// translations (fig. 5.10) and the rotations (fig. 5.13) over time, where asked.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/frame_input.h"
#include "cli/plot_png.h"
#include "core/analysis/pendulum_study.h"
#include "core/pipeline/data_out.h"

namespace imagepro::cli {
namespace {

using json = nlohmann::ordered_json;

// DIR/pendulum-translations.png and DIR/pendulum-rotations.png (the folder made if need be).
void writePlots(const std::string& dir, const std::vector<PoseSample>& samples) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(dir + ": cannot make the folder (" + ec.message() + ")");
  const char* names[2][3] = {{"Tx", "Ty", "Tz"}, {"Rx", "Ry", "Rz"}};
  const cv::Scalar colours[3] = {cv::Scalar(200, 80, 0), cv::Scalar(0, 140, 0), cv::Scalar(0, 60, 220)};
  for (int kind = 0; kind < 2; ++kind) {
    // Each parameter about its mean, so the three share one scale.
    Plot plot;
    plot.title = kind == 0 ? "Reconstructed translations, swinging pendulum (about their means)"
                           : "Reconstructed rotations, swinging pendulum (about their means)";
    plot.x_label = "time [s]";
    plot.y_label = kind == 0 ? "T - mean [mm]" : "R - mean [deg]";
    for (int k = 0; k < 3; ++k) {
      auto value = [&](const Pose& p) {
        const double v[2][3] = {{p.tx_mm, p.ty_mm, p.tz_mm}, {p.rx_deg, p.ry_deg, p.rz_deg}};
        return v[kind][k];
      };
      double mean = 0.0;
      int count = 0;
      for (const PoseSample& s : samples)
        if (s.valid) {
          mean += value(s.pose);
          ++count;
        }
      if (count > 0) mean /= count;
      char name[64];
      std::snprintf(name, sizeof name, "%s (mean %.1f)", names[kind][k], mean);
      PlotSeries series{name, colours[k], {}, {}};
      for (const PoseSample& s : samples) {
        series.x.push_back(s.t_s);
        series.y.push_back(s.valid ? value(s.pose) - mean : NAN);
      }
      plot.series.push_back(std::move(series));
    }
    const std::string path =
        (std::filesystem::path(dir) / (kind == 0 ? "pendulum-translations.png" : "pendulum-rotations.png")).string();
    std::string error;
    if (!writePlotPng(path, plot, error)) throw InputError(error);
    std::fprintf(stderr, "wrote %s\n", path.c_str());
  }
}

// Each frame that could not be read, then the analysis's failure: one line each.
const PendulumStudyResult& checked(const PendulumStudyResult& result) {
  if (!ok(result.status)) throw InputError(result.error);
  for (const std::string& frame : result.unreadable) std::fprintf(stderr, "%s\n", frame.c_str());
  return result;
}

// "a.csv,b.csv" -> {"a.csv", "b.csv"}.
std::vector<std::string> commaList(const std::string& text) {
  std::vector<std::string> out;
  std::size_t from = 0;
  for (;;) {
    const std::size_t comma = text.find(',', from);
    out.push_back(text.substr(from, comma == std::string::npos ? std::string::npos : comma - from));
    if (comma == std::string::npos) return out;
    from = comma + 1;
  }
}

PeriodMethod periodMethod(const Args& args) {
  const std::string method = args.valueOr("period-method", "crossings");
  if (method == "crossings") return PeriodMethod::Crossings;
  if (method == "maxima") return PeriodMethod::Maxima;
  throw UsageError("--period-method: \"" + method + "\" is not crossings or maxima");
}

// The thesis's period in words: the mean and each axis's period and cycles.
std::string maximaText(const PendulumAnalysis& a) {
  if (!ok(a.maxima_status)) return std::string("none (") + std::string(statusName(a.maxima_status)) + ")";
  char buf[256];
  std::snprintf(buf, sizeof buf, "%.6f +- %.6f s  (first to last maximum:", a.maxima.period_s, a.maxima.period_sigma_s);
  std::string text = buf;
  const char* names[3] = {"Tx", "Ty", "Tz"};
  for (int k = 0; k < 3; ++k) {
    if (a.maxima.axis_cycles[k] > 0)
      std::snprintf(buf, sizeof buf, " %s %.5f s over %d cycles", names[k], a.maxima.axis_period_s[k],
                    a.maxima.axis_cycles[k]);
    else
      std::snprintf(buf, sizeof buf, " %s not at the swing's period", names[k]);
    text += buf;
    text += k < 2 ? ";" : ")";
  }
  return text;
}

json analysisJson(const PendulumAnalysis& a, const PendulumAnalysisOptions& options) {
  json j;
  j["frames"] = a.frames;
  j["valid_frames"] = a.valid_frames;
  j["length_mm"] = a.length_mm;
  j["length_sigma_mm"] = a.length_sigma_mm;
  j["length_from_still"] = a.length_from_still;
  if (a.length_from_still) {
    j["still_frames"] = a.still_frames;
    j["still_valid_frames"] = a.still_valid_frames;
  }
  j["period_method"] = options.period_method == PeriodMethod::Maxima ? "maxima" : "crossings";
  j["period_s"] = a.period_s;
  j["period_sigma_s"] = a.period_sigma_s;
  j["crossings_period_s"] = a.period.period_s;
  j["crossings_period_sigma_s"] = a.period.period_sigma_s;
  if (ok(a.maxima_status)) {
    j["maxima_period_s"] = a.maxima.period_s;
    j["maxima_period_sigma_s"] = a.maxima.period_sigma_s;
    j["maxima_axis_period_s"] = a.maxima.axis_period_s;
    j["maxima_axis_cycles"] = a.maxima.axis_cycles;
  } else {
    j["maxima_status"] = statusName(a.maxima_status);
  }
  j["g_m_s2"] = a.g_m_s2;
  j["g_sigma_m_s2"] = a.g_sigma_m_s2;
  j["amplitude_deg"] = a.amplitude_deg;
  j["small_amplitude_period_s"] = a.small_amplitude_period_s;
  j["g_uncorrected_m_s2"] = a.g_uncorrected_m_s2;
  j["amplitude_correction"] = options.amplitude_correction;
  j["pivot_mm"] = {a.sphere.centre_mm.x(), a.sphere.centre_mm.y(), a.sphere.centre_mm.z()};
  j["crossings"] = a.period.crossings;
  return j;
}

void printAnalysis(const PendulumAnalysis& a, const PendulumAnalysisOptions& options) {
  const bool maxima = options.period_method == PeriodMethod::Maxima;
  std::printf("frames        %d, %d with a pose\n", a.frames, a.valid_frames);
  if (a.length_from_still) std::printf("still frames  %d, %d with a pose\n", a.still_frames, a.still_valid_frames);
  std::printf("period        %.6f +- %.6f s  (%d mid-swing crossings; amplitude %.2f deg)%s\n", a.period.period_s,
              a.period.period_sigma_s, a.period.crossings, a.amplitude_deg, maxima ? "" : "  <- g");
  std::printf("thesis period %s%s\n", maximaText(a).c_str(), maxima ? "  <- g" : "");
  std::printf("length        %.2f +- %.2f mm  (%s; pivot %.1f, %.1f, %.1f mm; RMS off the sphere %.3f mm)\n",
              a.length_mm, a.length_sigma_mm, a.length_from_still ? "from the still recording" : "from the swing",
              a.sphere.centre_mm.x(), a.sphere.centre_mm.y(), a.sphere.centre_mm.z(), a.sphere.radial_rms_mm);
  if (options.amplitude_correction)
    std::printf("g             %.4f +- %.4f m/s^2  (small-amplitude period %.5f s; eq. 5.1 with the measured "
                "period: %.4f)\n",
                a.g_m_s2, a.g_sigma_m_s2, a.small_amplitude_period_s, a.g_uncorrected_m_s2);
  else
    std::printf("g             %.4f +- %.4f m/s^2  (eq. 5.1 with the measured period)\n", a.g_m_s2, a.g_sigma_m_s2);
}

// Several runs as thesis table 5.3: one row each (a failed run names its error and is
// left out of the mean), then the mean and the standard deviation.
int printRuns(const std::vector<std::string>& names, const std::vector<PendulumStudyResult>& results,
              const std::string& format) {
  std::vector<PendulumAnalysis> good;
  for (const PendulumStudyResult& r : results)
    if (ok(r.status)) good.push_back(r.analysis);
  const PendulumRunsSummary sum = summarizePendulumRuns(good);
  if (format == "json") {
    json j;
    j["runs"] = json::array();
    for (std::size_t i = 0; i < results.size(); ++i) {
      json run = ok(results[i].status) ? analysisJson(results[i].analysis, results[i].options) : json::object();
      run["run"] = names[i];
      if (!ok(results[i].status)) run["error"] = results[i].error;
      j["runs"].push_back(run);
    }
    j["mean"] = {{"length_mm", sum.length_mm}, {"period_s", sum.period_s}, {"g_m_s2", sum.g_m_s2},
                 {"g_uncorrected_m_s2", sum.g_uncorrected_m_s2}};
    j["sd"] = {{"length_mm", sum.length_sd_mm}, {"period_s", sum.period_sd_s}, {"g_m_s2", sum.g_sd_m_s2},
               {"g_uncorrected_m_s2", sum.g_uncorrected_sd_m_s2}};
    std::printf("%s\n", j.dump(2).c_str());
    return good.empty() ? 1 : 0;
  }
  std::printf("| run | length [mm] | period [s], crossings | period [s], thesis | g [m/s^2] | g by eq. 5.1 alone |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (std::size_t i = 0; i < results.size(); ++i) {
    const PendulumAnalysis& a = results[i].analysis;
    if (!ok(results[i].status)) {
      std::printf("| %s | %s | | | | |\n", names[i].c_str(), results[i].error.c_str());
      continue;
    }
    char maxima[32] = "-";
    if (ok(a.maxima_status)) std::snprintf(maxima, sizeof maxima, "%.5f", a.maxima.period_s);
    std::printf("| %s | %.2f ± %.2f | %.5f | %s | %.4f ± %.4f | %.4f |\n", names[i].c_str(), a.length_mm,
                a.length_sigma_mm, a.period.period_s, maxima, a.g_m_s2, a.g_sigma_m_s2, a.g_uncorrected_m_s2);
  }
  std::printf("| mean of %d | %.2f | %.5f (g's period) | | %.4f | %.4f |\n", sum.runs, sum.length_mm, sum.period_s,
              sum.g_m_s2, sum.g_uncorrected_m_s2);
  std::printf("| standard deviation | %.2f | %.5f | | %.4f | %.4f |\n", sum.length_sd_mm, sum.period_sd_s, sum.g_sd_m_s2,
              sum.g_uncorrected_sd_m_s2);
  return good.empty() ? 1 : 0;
}

int run(const Args& args) {
  std::vector<std::string> known = kFrameInputOptions;
  known.insert(known.end(), {"format", "plots", "rate", "no-amplitude-correction", "noise", "blur-exposure",
                             "subframes", "data-out", "still", "swing", "period-method", "interlaced",
                             "still-positions", "still-span", "still-frames", "runs"});
  args.rejectUnknown(known);
  const std::string format = args.valueOr("format", "text");
  if (format != "text" && format != "json") throw UsageError("--format: \"" + format + "\" is not text or json");
  const Settings settings = loadConfigForInput(args);
  const bool virtual_input = args.has("virtual");
  for (const char* option : {"noise", "blur-exposure", "subframes", "interlaced", "still-positions", "still-span",
                             "still-frames", "runs"})
    if (args.has(option) && !virtual_input) throw UsageError(std::string("--") + option + " goes with --virtual");
  const double rate_hz = args.number("rate", settings.virtual_scene.frame_rate_hz);
  if (!(rate_hz > 0.0)) throw UsageError("--rate must be above 0");
  PendulumAnalysisOptions options;
  options.amplitude_correction = !args.has("no-amplitude-correction");
  options.period_method = periodMethod(args);

  // The thesis's two recordings: --still and --swing, each one path or a comma list paired in order.
  if (args.has("still") || args.has("swing")) {
    if (!args.has("still") || !args.has("swing")) throw UsageError("--still and --swing go together");
    if (virtual_input || !args.positionals().empty() || args.has("camera") || args.has("video"))
      throw UsageError("--still and --swing are the input: give no other");
    for (const char* option : {"data-out", "frames", "size", "fps"})
      if (args.has(option)) throw UsageError(std::string("--") + option + " does not go with --still and --swing");
    const std::vector<std::string> still = commaList(*args.value("still")), swing = commaList(*args.value("swing"));
    if (still.size() != swing.size()) throw UsageError("--still and --swing need as many recordings each");
    std::vector<PendulumStudyResult> results;
    for (std::size_t i = 0; i < still.size(); ++i)
      results.push_back(runPendulumStillSwing(still[i], swing[i], settings, rate_hz, options, {}));
    if (results.size() > 1) {
      if (args.has("plots")) throw UsageError("--plots goes with one run");
      std::vector<std::string> names;
      for (std::size_t i = 0; i < still.size(); ++i) names.push_back(std::to_string(i + 1));
      return printRuns(names, results, format);
    }
    const PendulumStudyResult& result = results.front();
    if (const auto dir = args.value("plots"); dir && !result.samples.empty()) writePlots(*dir, result.samples);
    const PendulumAnalysis& a = checked(result).analysis;
    if (format == "json")
      std::printf("%s\n", analysisJson(a, options).dump(2).c_str());
    else
      printAnalysis(a, options);
    return 0;
  }

  const bool csv_input = args.positionals().size() == 1 &&
                         std::filesystem::path(args.positionals()[0]).extension() == ".csv";
  if (csv_input && args.has("data-out")) throw UsageError("--data-out goes with frames to reconstruct, not a CSV");
  if (csv_input || virtual_input)
    for (const char* option : {"camera", "video", "size", "fps"})
      if (args.has(option))
        throw UsageError(std::string("--") + option + (csv_input ? " does not go with a CSV" : " does not go with --virtual"));
  if (csv_input && args.has("frames")) throw UsageError("--frames does not go with a CSV");
  DataOut data_out;
  if (const auto path = args.value("data-out")) {
    std::string error;
    if (!ok(data_out.open(*path, ExistingFile::Fail, error))) throw InputError(error);
  }
  const FrameResultSink write_data_out = [&data_out](const FrameResult& r) {
    if (!data_out.isOpen()) return;
    std::string error;
    if (!data_out.write(r, error)) std::fprintf(stderr, "data out stopped: %s\n", error.c_str());
  };

  PendulumStudyResult result;
  if (csv_input) {
    result = runPendulumFile(args.positionals()[0], rate_hz, options);
  } else if (virtual_input) {
    if (!args.positionals().empty()) throw UsageError("give either --virtual or input files, not both");
    VirtualPendulumParams params;
    params.rate_hz = rate_hz;
    params.options = options;
    params.noise_sigma = args.number("noise", params.noise_sigma);
    if (!(params.noise_sigma >= 0.0)) throw UsageError("--noise must be 0 or more");
    params.blur.exposure_s = args.number("blur-exposure", 0.0);
    params.blur.subframes = args.integer("subframes", params.blur.subframes);
    if (!(params.blur.exposure_s >= 0.0)) throw UsageError("--blur-exposure must be 0 or more");
    if (params.blur.subframes < 2) throw UsageError("--subframes must be at least 2");
    params.interlaced = args.has("interlaced");
    params.frames = args.integer("frames", params.frames);
    if (params.frames < 1) throw UsageError("--frames must be at least 1");
    params.still_recording = args.has("still-positions");
    params.still.positions = args.integer("still-positions", params.still.positions);
    params.still.span_deg = args.number("still-span", params.still.span_deg);
    params.still.frames_per_position = args.integer("still-frames", params.still.frames_per_position);
    if ((args.has("still-span") || args.has("still-frames")) && !params.still_recording)
      throw UsageError("--still-span and --still-frames go with --still-positions");
    if (params.still.positions < 1) throw UsageError("--still-positions must be at least 1");
    if (params.still.frames_per_position < 1) throw UsageError("--still-frames must be at least 1");
    if (!(params.still.span_deg >= 0.0 && params.still.span_deg < 90.0))
      throw UsageError("--still-span must be from 0 to below 90 degrees");
    const int runs = args.integer("runs", 1);
    if (runs < 1) throw UsageError("--runs must be at least 1");
    std::fprintf(stderr, "reconstructing %d frames of the virtual pendulum %.0f Hz%s%s%s ...\n", params.frames,
                 rate_hz, params.blur.exposure_s > 0.0 ? ", motion blur" : "", params.interlaced ? ", interlaced" : "",
                 params.still_recording ? ", after its still recording" : "");
    if (runs > 1) {
      if (args.has("plots") || args.has("data-out")) throw UsageError("--plots and --data-out go with one run");
      // Run i: the noise seeded i, as the pendulum study's data sets.
      std::vector<PendulumStudyResult> results;
      std::vector<std::string> names;
      for (int i = 1; i <= runs; ++i) {
        Settings s = settings;
        s.virtual_scene.seed = static_cast<unsigned>(i);
        results.push_back(runVirtualPendulum(s, params, {}));
        names.push_back("seed " + std::to_string(i));
      }
      return printRuns(names, results, format);
    }
    result = runVirtualPendulum(settings, params, {}, write_data_out);
  } else {
    auto source = openFrameInput(args, settings);
    result = runPendulumSource(*source, settings, rate_hz, options, {}, write_data_out);
  }
  data_out.close();
  if (const auto dir = args.value("plots"); dir && !result.samples.empty()) writePlots(*dir, result.samples);
  const PendulumAnalysis& a = checked(result).analysis;

  const PendulumOptions& truth = settings.virtual_scene.pendulum;
  const double true_period = result.truth.period_s;  // 0 but for the virtual pendulum
  if (format == "json") {
    json j = analysisJson(a, options);
    if (virtual_input) {
      j["true_length_mm"] = truth.length_mm;
      j["true_period_s"] = true_period;
      j["true_g_m_s2"] = truth.gravity_m_s2;
      j["true_pivot_mm"] = truth.pivot_mm;
    }
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
  }
  printAnalysis(a, options);
  if (virtual_input) {
    std::printf("truth         length %.2f mm, period %.5f s, g %.5f m/s^2\n", truth.length_mm, true_period,
                truth.gravity_m_s2);
    std::printf("errors        length %+.3f %%, period %+.4f %%, g %+.3f %%\n",
                100.0 * (a.length_mm / truth.length_mm - 1.0), 100.0 * (a.period_s / true_period - 1.0),
                100.0 * (a.g_m_s2 / truth.gravity_m_s2 - 1.0));
  }
  return 0;
}

const CommandRegistration kRegistration{{
    "pendulum",
    "period, length and g from a target on a swinging pendulum (thesis 5.3.2)",
    std::string("usage: imagepro-cli pendulum [--config FILE] [--format text|json] [--plots DIR]\n"
                "                             [--rate HZ] [--no-amplitude-correction] [--period-method M]\n"
                "                             [--data-out FILE] INPUT\n\n"
                "input: --still STILL --swing SWING (as the thesis ran it: the length from STILL, frames of the\n"
                "          target held still at a few places on its arc; the period from SWING; each a pose CSV,\n"
                "          a video or images; comma lists pair several runs into one table like thesis table 5.3)\n"
                "       or FILE.csv (data out, or the output of imagepro-cli reconstruct)\n"
                "       or --virtual [--frames N] [--noise SIGMA] [--blur-exposure S [--subframes N]] [--interlaced]\n"
                "          [--still-positions N [--still-span DEG] [--still-frames N]] [--runs N]\n"
                "          (the Virtual source's pendulum of the settings, grey, default 250 frames, noise 3)\n"
                "       or --video FILE, --camera /dev/videoN [--size WxH] [--fps N] [--frames N],\n"
                "          or IMAGES... (files, folders, text files listing paths), reconstructed frame by frame") +
        "\n\nThe period comes from the translations over time, the pivot and the length from the\n"
        "constrained sphere fit of thesis eqs. 5.2-5.6, g from eq. 5.1 with the period reduced to\n"
        "a small swing's (the exact pendulum's amplitude correction), each with its uncertainty.\n"
        "  --rate HZ                   frame rate giving the times of frames without timestamps (image\n"
        "                              files, CSV without timestamp_s; default: the settings' virtual\n"
        "                              frame rate, 25); --virtual renders at this rate\n"
        "  --no-amplitude-correction   g by eq. 5.1 with the measured period, as in the thesis\n"
        "  --period-method M           the period g uses: crossings (mid-swing crossings, the default) or\n"
        "                              maxima (the thesis's: first to last maximum averaged over Tx, Ty,\n"
        "                              Tz); both are printed\n"
        "  --interlaced                virtual: two fields a frame, the even rows a field time (half the\n"
        "                              frame time) before the odd ones (thesis fig. 5.11)\n"
        "  --still-positions N         virtual: the length from a still recording first, the pendulum\n"
        "                              held at N angles over +-DEG (--still-span, default 20), N frames\n"
        "                              at each (--still-frames, default 5)\n"
        "  --runs N                    virtual: N runs, the noise seeded 1..N, in one table\n"
        "  --blur-exposure S           virtual: motion blur, exposure S seconds centred on each frame,\n"
        "                              averaged over --subframes renders (default 8)\n"
        "  --plots DIR                 DIR/pendulum-translations.png (thesis fig. 5.10) and\n"
        "                              DIR/pendulum-rotations.png (fig. 5.13); none without it\n"
        "  --data-out FILE             also write the reconstructed frames as data out\n"
        "  --format json               length_mm, period_s, g_m_s2 and their sigmas (and the true values\n"
        "                              for --virtual)",
    {"virtual", "no-amplitude-correction", "interlaced"},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
