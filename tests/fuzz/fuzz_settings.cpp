// The settings JSON: any text through the settings file's reader. What it accepts must
// save and load back to the same settings, and the engine must run with it (on the
// default camera's frame size, where a frame of the virtual scene is at hand).
#include <cstddef>
#include <cstdint>

#include "core/common/geometry.h"
#include "core/pipeline/engine.h"
#include "core/settings/settings.h"
#include "core/source/virtual_renderer.h"
#include "fuzz_support.h"

using namespace imagepro;

namespace {

const cv::Mat& defaultSceneFrame() {
  static const cv::Mat frame = [] {
    const Settings d;
    cv::Mat out;
    renderTarget(d.camera(), d.target, d.virtual_scene, Pose{10.0, -5.0, 0.0, 5.0, 0.0, 700.0}, out);
    return out;
  }();
  return frame;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::scratchFile("settings.json", data, size);
  Settings settings;
  std::string error;
  if (loadSettings(path, settings, error) != Status::Ok) {
    if (error.empty()) fuzz::fail("a refused settings file names no reason", "");
    return 0;
  }
  const std::string saved = settingsToJson(settings);
  Settings again;
  if (settingsFromJson(saved, again, error) != Status::Ok) fuzz::fail("saved settings do not load", error + "\n" + saved);
  if (settingsToJson(again) != saved) fuzz::fail("saved settings load as other settings", saved);

  const cv::Mat& image = defaultSceneFrame();
  if (settings.camera().width != image.cols || settings.camera().height != image.rows) return 0;
  Engine engine(settings);
  Frame frame;
  frame.image = image;
  FrameResult result;
  for (int i = 0; i < 2; ++i) {
    frame.index = i;
    engine.process(frame, result);
  }
  return 0;
}
