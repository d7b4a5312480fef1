#pragma once
// The virtual motion on the command line, shared by `render` and `reconstruct --virtual`:
// --motion, --axis, --amplitude, --period, and the constant-velocity motion's --velocity
// and --box (thesis A.2), each overriding the settings' "virtual.motion" within the
// ranges the settings file allows.
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/option_ranges.h"
#include "core/settings/settings.h"

namespace imagepro::cli {

inline const std::vector<std::string> kVirtualMotionOptions{"motion", "axis", "amplitude", "period", "velocity", "box"};
// The settings keys they set, for checkOptionRanges.
extern const std::vector<OptionKey> kVirtualMotionOptionKeys;

// Six comma-separated numbers in the pose's order (RX,RY,RZ,TX,TY,TZ), or `fallback` when
// --key is not given; UsageError naming --key otherwise.
Pose sixNumbersOption(const Args& args, const std::string& key, const Pose& fallback);

// Applies the options above to `scene` (the ranges are checked by the caller, with
// kVirtualMotionOptionKeys, once every option is in).
void applyVirtualMotionOptions(const Args& args, VirtualSceneOptions& scene);

// --help's lines for the options.
std::string virtualMotionHelp();

}  // namespace imagepro::cli
