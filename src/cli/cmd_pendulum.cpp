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

int run(const Args& args) {
  std::vector<std::string> known = kFrameInputOptions;
  known.insert(known.end(), {"format", "plots", "rate", "no-amplitude-correction", "noise", "blur-exposure",
                             "subframes", "data-out"});
  args.rejectUnknown(known);
  const std::string format = args.valueOr("format", "text");
  if (format != "text" && format != "json") throw UsageError("--format: \"" + format + "\" is not text or json");
  const Settings settings = loadConfig(args);
  const bool virtual_input = args.has("virtual");
  for (const char* option : {"noise", "blur-exposure", "subframes"})
    if (args.has(option) && !virtual_input) throw UsageError(std::string("--") + option + " goes with --virtual");
  const double rate_hz = args.number("rate", settings.virtual_scene.frame_rate_hz);
  if (!(rate_hz > 0.0)) throw UsageError("--rate must be above 0");
  const bool amplitude_correction = !args.has("no-amplitude-correction");

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
    result = runPendulumFile(args.positionals()[0], rate_hz, amplitude_correction);
  } else if (virtual_input) {
    if (!args.positionals().empty()) throw UsageError("give either --virtual or input files, not both");
    VirtualPendulumParams params;
    params.rate_hz = rate_hz;
    params.amplitude_correction = amplitude_correction;
    params.noise_sigma = args.number("noise", params.noise_sigma);
    if (!(params.noise_sigma >= 0.0)) throw UsageError("--noise must be 0 or more");
    params.blur.exposure_s = args.number("blur-exposure", 0.0);
    params.blur.subframes = args.integer("subframes", params.blur.subframes);
    if (!(params.blur.exposure_s >= 0.0)) throw UsageError("--blur-exposure must be 0 or more");
    if (params.blur.subframes < 2) throw UsageError("--subframes must be at least 2");
    params.frames = args.integer("frames", params.frames);
    if (params.frames < 1) throw UsageError("--frames must be at least 1");
    std::fprintf(stderr, "reconstructing %d frames of the virtual pendulum %.0f Hz%s ...\n", params.frames, rate_hz,
                 params.blur.exposure_s > 0.0 ? ", motion blur" : "");
    result = runVirtualPendulum(settings, params, {}, write_data_out);
  } else {
    auto source = openFrameInput(args, settings);
    result = runPendulumSource(*source, settings, rate_hz, amplitude_correction, {}, write_data_out);
  }
  data_out.close();
  if (const auto dir = args.value("plots"); dir && !result.samples.empty()) writePlots(*dir, result.samples);
  const PendulumAnalysis& a = checked(result).analysis;

  const PendulumOptions& truth = settings.virtual_scene.pendulum;
  const double true_period = result.truth.period_s;  // 0 but for the virtual pendulum
  if (format == "json") {
    json j;
    j["frames"] = a.frames;
    j["valid_frames"] = a.valid_frames;
    j["length_mm"] = a.length_mm;
    j["length_sigma_mm"] = a.length_sigma_mm;
    j["period_s"] = a.period_s;
    j["period_sigma_s"] = a.period_sigma_s;
    j["g_m_s2"] = a.g_m_s2;
    j["g_sigma_m_s2"] = a.g_sigma_m_s2;
    j["amplitude_deg"] = a.amplitude_deg;
    j["small_amplitude_period_s"] = a.small_amplitude_period_s;
    j["g_uncorrected_m_s2"] = a.g_uncorrected_m_s2;
    j["amplitude_correction"] = amplitude_correction;
    j["pivot_mm"] = {a.sphere.centre_mm.x(), a.sphere.centre_mm.y(), a.sphere.centre_mm.z()};
    j["crossings"] = a.period.crossings;
    if (virtual_input) {
      j["true_length_mm"] = truth.length_mm;
      j["true_period_s"] = true_period;
      j["true_g_m_s2"] = truth.gravity_m_s2;
      j["true_pivot_mm"] = truth.pivot_mm;
    }
    std::printf("%s\n", j.dump(2).c_str());
    return 0;
  }
  std::printf("frames        %d, %d with a pose\n", a.frames, a.valid_frames);
  std::printf("period        %.6f +- %.6f s  (%d mid-swing crossings; amplitude %.2f deg)\n", a.period_s,
              a.period_sigma_s, a.period.crossings, a.amplitude_deg);
  std::printf("length        %.2f +- %.2f mm  (pivot %.1f, %.1f, %.1f mm; RMS off the sphere %.3f mm)\n", a.length_mm,
              a.length_sigma_mm, a.sphere.centre_mm.x(), a.sphere.centre_mm.y(), a.sphere.centre_mm.z(),
              a.sphere.radial_rms_mm);
  if (amplitude_correction)
    std::printf("g             %.4f +- %.4f m/s^2  (small-amplitude period %.5f s; eq. 5.1 with the measured "
                "period: %.4f)\n",
                a.g_m_s2, a.g_sigma_m_s2, a.small_amplitude_period_s, a.g_uncorrected_m_s2);
  else
    std::printf("g             %.4f +- %.4f m/s^2  (eq. 5.1 with the measured period)\n", a.g_m_s2, a.g_sigma_m_s2);
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
                "                             [--rate HZ] [--no-amplitude-correction] [--data-out FILE] INPUT\n\n"
                "input: FILE.csv (data out, or the output of imagepro-cli reconstruct)\n"
                "       or --virtual [--frames N] [--noise SIGMA] [--blur-exposure S [--subframes N]]\n"
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
        "  --blur-exposure S           virtual: motion blur, exposure S seconds centred on each frame,\n"
        "                              averaged over --subframes renders (default 8)\n"
        "  --plots DIR                 DIR/pendulum-translations.png (thesis fig. 5.10) and\n"
        "                              DIR/pendulum-rotations.png (fig. 5.13); none without it\n"
        "  --data-out FILE             also write the reconstructed frames as data out\n"
        "  --format json               length_mm, period_s, g_m_s2 and their sigmas (and the true values\n"
        "                              for --virtual)",
    {"virtual", "no-amplitude-correction"},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
