#include "core/calibration/calibration_file.h"

#include <nlohmann/json.hpp>

#include "core/common/atomic_file.h"

namespace imagepro {

std::string calibrationFileJson(const Settings& settings) {
  // Taken from the settings writer, so the section has exactly its keys and formats.
  const nlohmann::ordered_json all = nlohmann::ordered_json::parse(settingsToJson(settings));
  nlohmann::ordered_json out;
  out["camera"] = all.at("camera");
  return out.dump(2) + "\n";
}

bool writeCalibrationFile(const std::string& path, const Settings& settings, std::string& error) {
  return writeFileAtomically(path, calibrationFileJson(settings), error, true);
}

}  // namespace imagepro
