#pragma once
// The accuracy study's virtual part (docs/accuracy.md): virtual grey frames at random poses
// with noise, blur, an illumination gradient and clutter, with and without the thesis
// camera's lens distortion; the target detected once and reconstructed in every contour
// mode, beside an ArUco marker drawn at the same poses through the same effects. It measures
// the values of the doc's places named virtual.*; the prose around them lives in the doc.
#include <cstdint>

#include "core/settings/settings.h"
#include "studies/measured_doc.h"

namespace imagepro::studies {

// `frames` frames per distortion case from `seed`: every virtual.* value of docs/accuracy.md,
// from the frames' description to the lens distortion's table, into `values`; `seconds` the
// time it took.
void measureVirtualAccuracy(const Settings& settings, int frames, std::uint64_t seed, MeasuredValues& values,
                            double& seconds);

}  // namespace imagepro::studies
