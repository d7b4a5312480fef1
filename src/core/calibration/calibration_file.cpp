#include "core/calibration/calibration_file.h"

#include <nlohmann/json.hpp>

#include "core/common/atomic_file.h"
#include "core/settings/enum_names.h"

namespace imagepro {

std::string calibrationFileJson(const Settings& settings) {
  // Taken from the settings writer, so the section has exactly its keys and formats.
  const nlohmann::ordered_json all = nlohmann::ordered_json::parse(settingsToJson(settings));
  const std::string source(enumName(settings.source));
  nlohmann::ordered_json out;
  out["cameras"][source] = all.at("cameras").at(source);
  return out.dump(2) + "\n";
}

bool writeCalibrationFile(const std::string& path, const Settings& settings, std::string& error) {
  return writeFileAtomically(path, calibrationFileJson(settings), error, true);
}

}  // namespace imagepro
