#pragma once
// The settings file (docs/conventions.md): one JSON document with the camera, the
// target, the calibration pattern, the virtual scene and every pipeline option.
// Unknown keys and wrong types are errors naming the key; a missing key keeps its
// default; saving is atomic, so a failed save never damages the old file.
#include <string>
#include <string_view>

#include "core/common/geometry.h"
#include "core/common/status.h"
#include "core/settings/options.h"

namespace imagepro {

struct Settings {
  CameraModel camera;
  TargetGeometry target;
  PatternGeometry pattern;
  VirtualSceneOptions virtual_scene;
  CameraSourceOptions camera_source;
  PipelineOptions pipeline;
};

// Parses JSON text over the defaults. On failure returns InvalidSettings, leaves
// `out` unchanged and sets `error` to "<key.path>: <problem>".
Status settingsFromJson(std::string_view json_text, Settings& out, std::string& error);
std::string settingsToJson(const Settings& settings);

Status loadSettings(const std::string& path, Settings& out, std::string& error);
Status saveSettings(const std::string& path, const Settings& settings, std::string& error);


}  // namespace imagepro
