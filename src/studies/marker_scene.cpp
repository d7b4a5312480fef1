#include "studies/marker_scene.h"

namespace imagepro::studies {

MarkerGeometry markerLikeTarget(const TargetGeometry& target, double card_size_mm) {
  return MarkerGeometry{2.0 * target.radius_mm, card_size_mm, 0};
}

ScenePainter markerPainter(const CameraModel& camera, const MarkerGeometry& marker) {
  return [camera, marker](const cv::Mat& background, const Pose& pose, const TargetLook& look, cv::Mat& scene) {
    MarkerGeometry card = marker;
    card.card_mm = look.card_size_mm;
    VirtualSceneOptions ink;
    ink.white_level = look.white;
    ink.black_level = look.black;
    composeOver(
        background,
        [&](int level, cv::Mat& out) {
          // Over a flat frame of `level`, which the marker's anti-aliased edge blends with.
          out.create(background.size(), CV_8UC1);
          out.setTo(level);
          ink.background_level = level;
          paintMarkerCard(camera, card, ink, pose, out);
        },
        scene);
  };
}

}  // namespace imagepro::studies
