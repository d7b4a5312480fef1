#include "core/camera/camera_settings.h"

#include <algorithm>

namespace imagepro {

CameraRequest cameraRequest(const Settings& settings) {
  const CameraSourceOptions& o = settings.camera_source;
  CameraRequest request;
  request.device = o.device;
  const bool own_size = o.width > 0 && o.height > 0;
  const CameraModel& model = settings.camera(SourceKind::Camera);
  request.width = own_size ? o.width : model.width;
  request.height = own_size ? o.height : model.height;
  request.frame_rate_hz = o.frame_rate_hz;
  request.input = o.input;
  request.standard = o.standard;
  return request;
}

namespace {

Status setKnownControl(CameraSource& camera, const std::vector<CameraControl>& all, const std::string& key,
                       std::int64_t value, std::string& error) {
  const std::string wanted = controlKey(key);
  const auto it = std::find_if(all.begin(), all.end(), [&](const CameraControl& c) { return c.key == wanted; });
  if (it == all.end()) {
    error = camera.request().device + ": no control \"" + key + "\"";
    return Status::InvalidSettings;
  }
  const Status s = camera.setControl(it->id, value);
  if (!ok(s)) error = camera.lastError();
  return s;
}

}  // namespace

Status setControlByKey(CameraSource& camera, const std::string& key, std::int64_t value, std::string& error) {
  std::vector<CameraControl> all;
  if (const Status s = camera.controls(all); !ok(s)) {
    error = camera.lastError();
    return s;
  }
  return setKnownControl(camera, all, key, value, error);
}

void applyStoredControls(CameraSource& camera, const std::map<std::string, std::int64_t>& controls,
                         std::vector<std::string>& problems) {
  if (controls.empty()) return;
  std::vector<CameraControl> all;
  if (!ok(camera.controls(all))) {
    problems.push_back(camera.lastError());
    return;
  }
  // The stored keys in the device's order; keys it does not have at the end.
  std::vector<std::pair<std::string, std::int64_t>> pending;
  for (const CameraControl& c : all)
    if (const auto it = controls.find(c.key); it != controls.end()) pending.emplace_back(it->first, it->second);
  for (const auto& stored : controls)  // not a structured binding: clang 14 cannot capture one
    if (std::none_of(all.begin(), all.end(), [&](const CameraControl& c) { return c.key == stored.first; }))
      pending.emplace_back(stored.first, stored.second);

  struct Refused {
    std::string key;
    std::int64_t value;
    std::string error;
  };
  std::vector<Refused> refused;
  for (const auto& [key, value] : pending) {
    std::string error;
    if (!ok(setKnownControl(camera, all, key, value, error))) refused.push_back({key, value, error});
  }
  // Something was set that a refused control may depend on: each is tried once more,
  // against the device's controls as they are now.
  if (!refused.empty() && refused.size() < pending.size() && ok(camera.controls(all)))
    for (Refused& r : refused) {
      r.error.clear();
      setKnownControl(camera, all, r.key, r.value, r.error);
    }
  for (const Refused& r : refused)
    if (!r.error.empty()) problems.push_back(r.error);
}

}  // namespace imagepro
