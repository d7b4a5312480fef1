#pragma once
// The settings file (docs/conventions.md): one JSON document with each source's camera
// model, the target, the calibration pattern, the virtual scene, the live pose stream
// and every pipeline option.
// Unknown keys and wrong types are errors naming the key; a missing key keeps its
// default; saving is atomic, so a failed save never damages the old file. An older
// file's one "camera" is read as the camera of every source.
#include <array>
#include <string>
#include <string_view>
#include <typeindex>
#include <vector>

#include "core/common/geometry.h"
#include "core/common/status.h"
#include "core/settings/options.h"
#include "core/settings/target_set.h"

namespace imagepro {

struct Settings {
  // Each source's camera model, in kSourceKinds' order ("cameras" in the file).
  std::array<CameraModel, kSourceKinds.size()> cameras;
  // The source whose frames are processed, which picks camera(). Not in the file: whoever
  // runs a source sets it (the application's Input Source panel, the command line's input).
  SourceKind source = SourceKind::Virtual;
  TargetGeometry target;
  // Several targets told apart by their offset spots (target_set.h); empty: `target` alone.
  // Not written when empty, so a file of one target reads as before.
  std::vector<TargetSpec> targets;
  PoseFramesOptions frames;
  PatternGeometry pattern;
  // The Virtual source: by default the card in a lit room (docs/user-manual.md 3.3), so
  // the first frames look like a camera's.
  VirtualSceneOptions virtual_scene = [] {
    VirtualSceneOptions scene;
    scene.backdrop = Backdrop::Room;
    return scene;
  }();
  CameraSourceOptions camera_source;
  StreamOptions stream;
  PipelineOptions pipeline;

  CameraModel& camera(SourceKind kind) { return cameras[static_cast<std::size_t>(kind)]; }
  const CameraModel& camera(SourceKind kind) const { return cameras[static_cast<std::size_t>(kind)]; }
  // The camera of the source in use: the one the pipeline reconstructs with.
  CameraModel& camera() { return camera(source); }
  const CameraModel& camera() const { return camera(source); }
};

// Parses JSON text over the defaults. On failure returns InvalidSettings, leaves
// `out` unchanged and sets `error` to "<key.path>: <problem>". A key read under the old
// name of a renamed key (settings.cpp, kRenamedKeys) adds a line to `warnings`.
Status settingsFromJson(std::string_view json_text, Settings& out, std::string& error,
                        std::vector<std::string>* warnings = nullptr);
std::string settingsToJson(const Settings& settings);

Status loadSettings(const std::string& path, Settings& out, std::string& error,
                    std::vector<std::string>* warnings = nullptr);
Status saveSettings(const std::string& path, const Settings& settings, std::string& error);

// One key of the settings file as the settings table (settings.cpp) has it: the one
// home of its valid range, which the loader, the CLI's options and the GUI's widgets
// all apply.
struct SettingKey {
  enum class Type { Number, WholeNumber, Flag, Choice, Text, Names };
  struct Choice {
    std::string_view key, label, description;  // the enum table's row (enum_names.h)
  };
  std::string path;  // "pipeline.ellipse.trace_inlier_px", "cameras.file.principal_point_px[1]"
  Type type = Type::Number;
  double lo = 0.0, hi = 0.0;              // Number, WholeNumber: valid from lo to hi, both included
  std::type_index choice = typeid(void);  // Choice: the option enum
  std::vector<Choice> choices;            // Choice: the values it takes, in its table's order
};

// Every key, in the order of the file.
const std::vector<SettingKey>& settingKeys();
// The key at `path`, or nullptr.
const SettingKey* findSettingKey(std::string_view path);
// The key of the value at `field`, which lies inside `settings`; nullptr when no key
// holds it.
const SettingKey* settingKeyOf(const Settings& settings, const void* field);


}  // namespace imagepro
