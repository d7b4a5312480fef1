// imagepro-studies pendulum-study: the virtual pendulum of thesis 5.3.2 over the five data
// sets of thesis table 5.3 (the camera in five places) and over swing amplitudes, each a
// run of core/analysis/pendulum_study.h as `imagepro-cli pendulum --virtual` makes it.
// Prints the Markdown tables of docs/case-studies.md.
#include <array>
#include <cstdio>
#include <string>

#include "cli/command.h"
#include "core/analysis/pendulum_study.h"
#include "studies/report.h"

namespace imagepro::studies {
namespace {

using cli::Args;
using cli::CommandRegistration;
using cli::InputError;
using cli::UsageError;

// Thesis table 5.3's five placements of the camera, as pivots in the camera frame; the
// noise seed is the set's number.
struct DataSet {
  std::array<double, 3> pivot_mm;
  double swing_axis_deg;
};
constexpr DataSet kDataSets[] = {
    {{0.0, -300.0, 1200.0}, 0.0},  {{-100.0, -300.0, 1100.0}, 0.0}, {{80.0, -280.0, 1300.0}, 0.0},
    {{0.0, -320.0, 1000.0}, 0.0},  {{40.0, -300.0, 1200.0}, 25.0},
};
constexpr double kAmplitudesDeg[] = {5.0, 10.0, 15.0, 25.0};

PendulumStudyResult runOne(const Settings& settings) {
  PendulumStudyResult r = runVirtualPendulum(settings, VirtualPendulumParams{}, {});
  if (!ok(r.status)) throw InputError(r.error);
  return r;
}

std::string dataSetsTable(const Settings& base) {
  std::string md =
      "| data set | pivot [mm] / swing heading | length [mm] | period [s] | g [m/s^2] | g by eq. 5.1 alone |\n"
      "|---|---|---|---|---|---|\n";
  double sum_length = 0.0, sum_period = 0.0, sum_g = 0.0, sum_g_plain = 0.0;
  PendulumTruth truth;
  int n = 0;
  for (const DataSet& set : kDataSets) {
    ++n;
    std::fprintf(stderr, "data set %d ...\n", n);
    Settings s = base;
    s.virtual_scene.seed = static_cast<unsigned>(n);
    s.virtual_scene.pendulum.pivot_mm = set.pivot_mm;
    s.virtual_scene.pendulum.swing_axis_deg = set.swing_axis_deg;
    const PendulumStudyResult r = runOne(s);
    const PendulumAnalysis& a = r.analysis;
    md += format("| %d | (%g, %g, %g) / %g | %.2f ± %.2f | %.5f | %.4f ± %.4f | %.4f |\n", n, set.pivot_mm[0],
                 set.pivot_mm[1], set.pivot_mm[2], set.swing_axis_deg, a.length_mm, a.length_sigma_mm, a.period_s,
                 a.g_m_s2, a.g_sigma_m_s2, a.g_uncorrected_m_s2);
    sum_length += a.length_mm;
    sum_period += a.period_s;
    sum_g += a.g_m_s2;
    sum_g_plain += a.g_uncorrected_m_s2;
    truth = r.truth;  // the same length and g for every set
  }
  md += format("| average | | %.2f | %.5f | %.4f | %.4f |\n", sum_length / n, sum_period / n, sum_g / n,
               sum_g_plain / n);
  md += format("| truth | | %.1f | %.5f | %.5f | |\n", truth.length_mm, truth.period_s, truth.g_m_s2);
  md += "| thesis, table 5.3 (real pendulum) | | 443.23 (true 444 ± 0.5) | 1.338 | 9.761 (Ankara: 9.806) | |\n";
  return md;
}

std::string amplitudesTable(const Settings& base) {
  std::string md =
      "| amplitude | length [mm] | period [s] (truth) | g [m/s^2] |\n"
      "|---|---|---|---|\n";
  for (const double amplitude : kAmplitudesDeg) {
    std::fprintf(stderr, "amplitude %g deg ...\n", amplitude);
    Settings s = base;
    s.virtual_scene.pendulum.amplitude_deg = amplitude;
    const PendulumStudyResult r = runOne(s);
    const PendulumAnalysis& a = r.analysis;
    md += format("| %g deg | %.2f ± %.2f | %.5f (%.5f) | %.3f ± %.3f |\n", amplitude, a.length_mm, a.length_sigma_mm,
                 a.period_s, r.truth.period_s, a.g_m_s2, a.g_sigma_m_s2);
  }
  return md;
}

int run(const Args& args) {
  args.rejectUnknown({"table"});
  const std::string table = args.valueOr("table", "data-sets");
  if (table != "data-sets" && table != "amplitudes")
    throw UsageError("--table: \"" + table + "\" is not data-sets or amplitudes");
  const Settings settings = cli::loadConfig(args);
  const std::string md = table == "data-sets" ? dataSetsTable(settings) : amplitudesTable(settings);
  std::printf("%s", md.c_str());
  return 0;
}

const CommandRegistration kRegistration{{
    "pendulum-study",
    "the virtual pendulum over thesis table 5.3's data sets or over amplitudes (docs/case-studies.md)",
    "usage: imagepro-studies pendulum-study [--table data-sets|amplitudes] [--config FILE]\n\n"
    "Runs `imagepro-cli pendulum --virtual` (250 frames, noise 3) on the settings' pendulum and\n"
    "prints a Markdown table:\n"
    "  --table data-sets    the five data sets of thesis table 5.3 (the pivot moved, in set 5 the\n"
    "                       swing plane turned 25 deg; noise seed = set number), their average,\n"
    "                       the truth and the thesis's row (the default)\n"
    "  --table amplitudes   swings of 5, 10, 15 and 25 deg, the period's truth beside each",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::studies
