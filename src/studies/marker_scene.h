#pragma once
// The reference marker in real scenes: the accuracy study's ArUco marker (reference_marker.h)
// drawn by the real-scene generator (core/source/real_scene.h) in the target's place, so
// that it shares the target's pose, photograph, paper and ink, light, blur, motion blur,
// noise and JPEG frame by frame.
#include "core/source/real_scene.h"
#include "studies/reference_marker.h"

namespace imagepro::studies {

// The marker of the target's size: its black square as wide as the disk, on a white card
// as large as the target's card.
MarkerGeometry markerLikeTarget(const TargetGeometry& target, double card_size_mm);

// Paints `marker` (its card in the look's paper white, its cells in the look's black) at the
// frame's pose over the frame's photograph; pass it to RealScenes::still or RealSceneVideo::frame.
// The marker's card size is the look's.
ScenePainter markerPainter(const CameraModel& camera, const MarkerGeometry& marker);

}  // namespace imagepro::studies
