#pragma once
// The settings file (docs/conventions.md): one JSON document with the camera, the
// target, the calibration pattern, the virtual scene, the live pose stream and every
// pipeline option.
// Unknown keys and wrong types are errors naming the key; a missing key keeps its
// default; saving is atomic, so a failed save never damages the old file.
#include <string>
#include <string_view>
#include <typeindex>
#include <vector>

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
  StreamOptions stream;
  PipelineOptions pipeline;
};

// Parses JSON text over the defaults. On failure returns InvalidSettings, leaves
// `out` unchanged and sets `error` to "<key.path>: <problem>".
Status settingsFromJson(std::string_view json_text, Settings& out, std::string& error);
std::string settingsToJson(const Settings& settings);

Status loadSettings(const std::string& path, Settings& out, std::string& error);
Status saveSettings(const std::string& path, const Settings& settings, std::string& error);

// One key of the settings file as the settings table (settings.cpp) has it: the one
// home of its valid range, which the loader, the CLI's options and the GUI's widgets
// all apply.
struct SettingKey {
  enum class Type { Number, WholeNumber, Flag, Choice, Text, Names };
  struct Choice {
    std::string_view key, label, description;  // the enum table's row (enum_names.h)
  };
  std::string path;  // "pipeline.ellipse.trace_inlier_px", "camera.principal_point_px[1]"
  Type type = Type::Number;
  double lo = 0.0, hi = 0.0;              // Number, WholeNumber: valid from lo to hi, both included
  std::type_index choice = typeid(void);  // Choice: the option enum
  std::vector<Choice> choices;            // Choice: its table, in order
};

// Every key, in the order of the file.
const std::vector<SettingKey>& settingKeys();
// The key at `path`, or nullptr.
const SettingKey* findSettingKey(std::string_view path);
// The key of the value at `field`, which lies inside `settings`; nullptr when no key
// holds it.
const SettingKey* settingKeyOf(const Settings& settings, const void* field);


}  // namespace imagepro
