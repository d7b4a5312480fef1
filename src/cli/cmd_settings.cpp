// imagepro-cli settings: prints the effective settings JSON (the defaults, or
// --config FILE checked and completed with defaults), or writes it with --out; with
// --methods-markdown, the user manual's tables of the methods and options instead. Takes
// the camera from OpenCV's camera file, or writes the camera as one
// (calibration/opencv_camera_file.h).
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/enum_options.h"
#include "core/calibration/opencv_camera_file.h"

namespace imagepro::cli {
namespace {

// A table cell: its first letter a capital (the descriptions continue a name in the
// GUI's tooltips), '|' escaped.
std::string cell(std::string_view text) {
  std::string out;
  for (const char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  if (!out.empty() && out[0] >= 'a' && out[0] <= 'z') out[0] = static_cast<char>(out[0] - 'a' + 'A');
  return out;
}

// One table per option enum, headed by the settings keys that take it (a key that takes
// only some of its values names those it does not take): a generated block of
// docs/user-manual.md (tools/regenerate-docs.sh).
std::string methodsMarkdown() {
  std::vector<std::vector<const SettingKey*>> groups;
  for (const SettingKey& k : settingKeys()) {
    if (k.type != SettingKey::Type::Choice) continue;
    bool placed = false;
    for (auto& g : groups)
      if (!placed && g.front()->choice == k.choice) {
        g.push_back(&k);
        placed = true;
      }
    if (!placed) groups.push_back({&k});
  }
  // The control panel's lists first, in its order, then the Settings dialog's.
  std::stable_partition(groups.begin(), groups.end(),
                        [](const auto& g) { return g.front()->path.rfind("pipeline.", 0) == 0; });
  std::string md;
  for (const auto& g : groups) {
    // The rows: the values of the key that takes the most of them, all of the enum's.
    const SettingKey* widest = *std::max_element(
        g.begin(), g.end(), [](const SettingKey* a, const SettingKey* b) { return a->choices.size() < b->choices.size(); });
    std::string keys;
    for (const SettingKey* k : g) {
      keys += (keys.empty() ? "`" : ", `") + k->path + "`";
      std::string left_out;
      for (const auto& c : widest->choices)
        if (std::none_of(k->choices.begin(), k->choices.end(), [&c](const auto& own) { return own.key == c.key; }))
          left_out += (left_out.empty() ? "`" : ", `") + std::string(c.key) + "`";
      if (!left_out.empty()) keys += " (not " + left_out + ")";
    }
    md += (md.empty() ? "" : "\n") + keys + "\n\n| name | key | what it is |\n| --- | --- | --- |\n";
    for (const auto& c : widest->choices)
      md += "| " + cell(c.label) + " | `" + std::string(c.key) + "` | " + cell(c.description) + " |\n";
  }
  return md;
}

int run(const Args& args) {
  args.rejectUnknown({"out", "methods-markdown", "import-opencv-camera", "export-opencv-camera", "source"});
  if (args.has("methods-markdown")) {
    if (args.has("out") || args.has("config")) throw UsageError("--methods-markdown takes no other option");
    std::fputs(methodsMarkdown().c_str(), stdout);
    return 0;
  }
  Settings settings = loadConfig(args);
  settings.source = enumOption(args, "source", SourceKind::File);
  std::string error;
  if (const auto in = args.value("import-opencv-camera")) {
    OpenCvCamera oc;
    if (!readOpenCvCamera(*in, oc, error)) throw InputError(error);
    // Into --source's camera, or every source's.
    for (const SourceKind k : kSourceKinds) {
      if (args.has("source") && k != settings.source) continue;
      double fit = 0.0;
      applyOpenCvCamera(oc, settings.camera(k), &fit);
      std::fprintf(stderr, "%s camera from %s: %dx%d, d0 %.4f mm for %g mm pixels; its distortion in this project's "
                   "model within %.4f px RMS\n",
                   std::string(enumName(k)).c_str(), in->c_str(), oc.width, oc.height,
                   settings.camera(k).image_plane_distance_mm, settings.camera(k).pixel_size_mm[0], fit);
    }
  }
  if (const auto exportPath = args.value("export-opencv-camera")) {
    if (!writeOpenCvCamera(*exportPath, openCvCameraOf(settings.camera()), error)) throw InputError(error);
    std::fprintf(stderr, "wrote %s\n", exportPath->c_str());
    if (!args.has("out")) return 0;
  }
  const std::string text = settingsToJson(settings);
  if (const auto out = args.value("out")) {
    if (!ok(saveSettings(*out, settings, error))) throw InputError(error);
    std::fprintf(stderr, "wrote %s\n", out->c_str());
  } else {
    std::fputs(text.c_str(), stdout);
  }
  return 0;
}

const CommandRegistration kRegistration{{
    "settings",
    "print or write the settings JSON (defaults, or --config checked and completed)",
    "usage: imagepro-cli settings [--config FILE] [--import-opencv-camera FILE] [--export-opencv-camera FILE]\n"
    "                             [--source S] [--out FILE]\n"
    "       imagepro-cli settings --methods-markdown\n\n"
    "Prints the effective settings: the defaults, or FILE with every missing key\n"
    "filled in. A malformed FILE is reported with the key at fault.\n"
    "  --import-opencv-camera FILE  take the camera from OpenCV's camera file (YAML/JSON:\n"
    "                      camera_matrix, distortion_coefficients, image_width, image_height):\n"
    "                      d0 for the settings' pixel size, the distortion fitted to this\n"
    "                      project's model; into every source's camera, or --source's\n"
    "  --export-opencv-camera FILE  write --source's camera as OpenCV's camera file (JSON for\n"
    "                      .json)\n"
    "  --source S          the camera of source S: file (default), camera or virtual\n"
    "  --out FILE          write to FILE (atomically) instead of printing\n"
    "  --methods-markdown  print instead the user manual's tables of every method and\n"
    "                      option list: for each value its name, its key in the settings\n"
    "                      file and what it is (docs/user-manual.md holds this output)",
    {"methods-markdown"},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
