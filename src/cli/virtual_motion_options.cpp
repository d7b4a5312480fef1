#include "cli/virtual_motion_options.h"

#include <sstream>

#include "cli/enum_options.h"
#include "core/settings/enum_names.h"

namespace imagepro::cli {

const std::vector<OptionKey> kVirtualMotionOptionKeys = {
    {"virtual.motion.amplitude", "--amplitude"}, {"virtual.motion.period_s", "--period"},
    {"virtual.motion.velocity.", "--velocity"},  {"virtual.motion.wrap_box.", "--box"},
};

Pose sixNumbersOption(const Args& args, const std::string& key, const Pose& fallback) {
  const auto text = args.value(key);
  if (!text) return fallback;
  const std::string usage = "--" + key + " takes six numbers: RX,RY,RZ,TX,TY,TZ";
  double v[6];
  std::istringstream in(*text);
  std::string field;
  int n = 0;
  while (std::getline(in, field, ',')) {
    if (n == 6) throw UsageError(usage);
    try {
      size_t used = 0;
      v[n] = std::stod(field, &used);
      if (used != field.size()) throw std::invalid_argument(field);
    } catch (const std::exception&) {
      throw UsageError("--" + key + ": \"" + field + "\" is not a number");
    }
    ++n;
  }
  if (n != 6) throw UsageError(usage);
  return Pose{v[0], v[1], v[2], v[3], v[4], v[5]};
}

void applyVirtualMotionOptions(const Args& args, VirtualSceneOptions& scene) {
  MotionOptions& m = scene.motion;
  m.kind = enumOption(args, "motion", m.kind);
  m.axis = enumOption(args, "axis", m.axis);
  m.amplitude = args.number("amplitude", m.amplitude);
  m.period_s = args.number("period", m.period_s);
  if (!(m.period_s > 0.0)) throw UsageError("--period must be more than 0");
  m.velocity = sixNumbersOption(args, "velocity", m.velocity);
  m.wrap_box = sixNumbersOption(args, "box", m.wrap_box);
}

std::string virtualMotionHelp() {
  return "  --motion K        how the target moves:\n" + choicesHelp<MotionKind>() +
         "  --axis A          the parameter a sinusoid or saw-tooth moves: " + enumChoices<PoseAxis>() +
         "\n"
         "  --amplitude A     mm or degrees;  --period S  seconds\n"
         "  --velocity RX,RY,RZ,TX,TY,TZ   constant velocity: deg/s (" +
         rangeText("virtual.motion.velocity.rx_deg_s") + ") and mm/s (" +
         rangeText("virtual.motion.velocity.tx_mm_s") + ")\n"
         "  --box RX,RY,RZ,TX,TY,TZ        constant velocity: each parameter wraps around inside this\n"
         "                    full width (deg, mm) centred on its start value; 0 never wraps\n";
}

}  // namespace imagepro::cli
