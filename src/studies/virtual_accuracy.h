#pragma once
// The accuracy study's virtual part (docs/accuracy.md): virtual grey frames at random poses
// with noise, blur, an illumination gradient and clutter, with and without the thesis
// camera's lens distortion; the target detected once and reconstructed in every contour
// mode, beside an ArUco marker drawn at the same poses through the same effects.
#include <cstdint>
#include <string>

#include "core/settings/settings.h"

namespace imagepro::studies {

// `frames` frames per distortion case from `seed`: the report's sections from the frames'
// description to the lens distortion's; `seconds` the time it took.
std::string virtualAccuracyReport(const Settings& settings, int frames, std::uint64_t seed, double& seconds);

}  // namespace imagepro::studies
