#include "core/pipeline/frame_result.h"

#include <cstdio>

namespace imagepro {

const char* stageName(Stage s) {
  switch (s) {
    case Stage::Grab: return "grab";
    case Stage::Crop: return "crop";
    case Stage::Threshold: return "threshold";
    case Stage::Edges: return "edges";
    case Stage::Connectivity: return "connectivity";
    case Stage::Ellipse: return "ellipse";
    case Stage::Reconstruction: return "reconstruction";
    case Stage::Tracking: return "tracking";
    case Stage::kCount: break;
  }
  return "?";
}

double StageTimes::total() const {
  double sum = 0;
  for (double v : us) sum += v;
  return sum;
}

std::string frameLabel(const FrameResult& r) { return r.name.empty() ? std::to_string(r.index) : r.name; }

}  // namespace imagepro
