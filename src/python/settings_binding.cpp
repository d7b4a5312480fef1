// imagepro.Settings: the settings file's document (core/settings/settings.h), read and
// edited by the keys of its settings table. A value is set by writing it into the JSON
// document and reading that back, so the loader's checks (type, range, choices) are the
// ones that apply, and its message names the key.
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include <string>

#include "core/settings/enum_names.h"
#include "core/settings/settings.h"
#include "python/bindings.h"
#include "python/errors.h"

namespace py = pybind11;
using json = nlohmann::ordered_json;

namespace imagepro::python {

namespace {

const SettingKey& settingKey(const std::string& key) {
  const SettingKey* k = findSettingKey(key);
  if (!k) throw StatusError(Status::InvalidSettings, key + ": unknown key (Settings.keys() lists them)");
  return *k;
}

// A key whose value is a whole list: the set of targets ("targets", a list of objects,
// docs/conventions.md) or an array whose elements are keys of their own
// ("frames.measured_targets", whose "frames.measured_targets[0]" is a key).
bool isListKey(const std::string& key) { return key == "targets" || findSettingKey(key + "[0]") != nullptr; }

// Where `key` ("cameras.file.principal_point_px[1]") lies in the settings document.
json::json_pointer pointerTo(const std::string& key) {
  std::string pointer = "/";
  for (const char c : key) {
    if (c == '.' || c == '[') pointer += '/';
    else if (c != ']') pointer += c;
  }
  return json::json_pointer(pointer);
}

py::object toPython(const json& j) {
  switch (j.type()) {
    case json::value_t::boolean: return py::bool_(j.get<bool>());
    case json::value_t::number_integer: return py::int_(j.get<std::int64_t>());
    case json::value_t::number_unsigned: return py::int_(j.get<std::uint64_t>());
    case json::value_t::number_float: return py::float_(j.get<double>());
    case json::value_t::string: return py::str(j.get<std::string>());
    case json::value_t::object: {
      py::dict d;
      for (const auto& [name, item] : j.items()) d[py::str(name)] = toPython(item);
      return d;
    }
    case json::value_t::array: {
      py::list l;
      for (const auto& item : j) l.append(toPython(item));
      return l;
    }
    default: return py::none();
  }
}

json fromPython(const std::string& key, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();  // before int: bool is an int in Python
  if (py::isinstance<py::int_>(value)) {
    try {
      return value.cast<std::int64_t>();
    } catch (const py::cast_error&) {
      throw StatusError(Status::InvalidSettings, key + ": " + py::repr(value).cast<std::string>() + " is out of range");
    }
  }
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    json array = json::array();
    std::size_t i = 0;
    for (const py::handle item : value) array.push_back(fromPython(key + "[" + std::to_string(i++) + "]", item));
    return array;
  }
  if (py::isinstance<py::dict>(value)) {
    json object = json::object();
    for (const auto& [name, item] : value.cast<py::dict>())
      object[py::str(name).cast<std::string>()] = fromPython(key + "." + py::str(name).cast<std::string>(), item);
    return object;
  }
  throw StatusError(Status::InvalidSettings, key + ": a " + py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>() +
                                                 " is no settings value (bool, int, float, str, list or dict)");
}

py::object getValue(const Settings& s, const std::string& key) {
  const json document = json::parse(settingsToJson(s));
  if (isListKey(key)) {
    // The file leaves out an empty set of targets.
    const json::json_pointer at = pointerTo(key);
    return document.contains(at) ? toPython(document.at(at)) : py::list();
  }
  settingKey(key);
  return toPython(document.at(pointerTo(key)));
}

void setValue(Settings& s, const std::string& key, const py::handle& value) {
  json document = json::parse(settingsToJson(s));
  if (isListKey(key)) {
    if (!py::isinstance<py::list>(value) && !py::isinstance<py::tuple>(value))
      throw StatusError(Status::InvalidSettings, key + ": a list is wanted, not a " +
                                                     py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
    document[pointerTo(key)] = fromPython(key, value);
  } else {
    settingKey(key);
    document.at(pointerTo(key)) = fromPython(key, value);
  }
  std::string error;
  if (!ok(settingsFromJson(document.dump(), s, error))) throw StatusError(Status::InvalidSettings, error);
}

const char* typeName(SettingKey::Type t) {
  switch (t) {
    case SettingKey::Type::Number: return "number";
    case SettingKey::Type::WholeNumber: return "whole number";
    case SettingKey::Type::Flag: return "flag";
    case SettingKey::Type::Choice: return "choice";
    case SettingKey::Type::Text: return "text";
    case SettingKey::Type::Names: return "names";
  }
  return "unknown";
}

py::dict keyInfo(const std::string& key) {
  const SettingKey& k = settingKey(key);
  py::dict d;
  d["key"] = k.path;
  d["type"] = typeName(k.type);
  if (k.type == SettingKey::Type::Number || k.type == SettingKey::Type::WholeNumber) {
    d["min"] = k.lo;
    d["max"] = k.hi;
  }
  if (k.type == SettingKey::Type::Choice) {
    py::list choices;
    for (const auto& c : k.choices) choices.append(py::str(std::string(c.key)));
    d["choices"] = choices;
  }
  return d;
}

Settings fromJsonText(const std::string& text) {
  Settings s;
  std::string error;
  if (!ok(settingsFromJson(text, s, error))) throw StatusError(Status::InvalidSettings, error);
  return s;
}

}  // namespace

void bindSettings(py::module_& m) {
  py::class_<Settings>(m, "Settings", R"(The settings of the pipeline: each source's camera, target, virtual scene, every option.

Values are read and written by the keys of the settings file (docs/conventions.md),
e.g. s["pipeline.tracking.mode"] = "off" or s.get("cameras.file.principal_point_px[0]").
A list is read and written whole under its own key: s["targets"] = [{"id": 1, "radius_mm":
50, "spot_radius_mm": 6, "spot_offset_mm": 20}, ...] (the set of targets, [] for none) or
s["frames.measured_targets"] = [1, 2].
A value the settings file would refuse raises imagepro.InvalidSettings naming the key.)")
      .def(py::init<>(), "The defaults.")
      .def_static("defaults", [] { return Settings{}; }, "The defaults (the same as Settings()).")
      .def_static(
          "load",
          [](const std::string& path) {
            Settings s;
            std::string error;
            std::vector<std::string> warnings;
            const Status status = loadSettings(path, s, error, &warnings);
            if (!ok(status)) throw StatusError(status, error);
            for (const std::string& w : warnings)
              if (PyErr_WarnEx(PyExc_DeprecationWarning, w.c_str(), 1) != 0) throw py::error_already_set();
            return s;
          },
          py::arg("path"),
          "Reads a settings file; missing keys keep their defaults. Raises imagepro.FileNotFound "
          "or imagepro.InvalidSettings; a key under its old name warns (DeprecationWarning).")
      .def(
          "save",
          [](const Settings& s, const std::string& path) {
            std::string error;
            const Status status = saveSettings(path, s, error);
            if (!ok(status)) throw StatusError(status, error);
          },
          py::arg("path"), "Writes the settings file atomically. Raises imagepro.FileNotWritable.")
      .def_static("from_json", &fromJsonText, py::arg("text"), "Settings from the settings file's JSON text.")
      .def("to_json", &settingsToJson, "The settings file's JSON text.")
      .def("get", &getValue, py::arg("key"), "The value at a key of the settings file.")
      .def("set", &setValue, py::arg("key"), py::arg("value"), "Sets the value at a key, checked as the settings file is.")
      .def("__getitem__", &getValue)
      .def("__setitem__", &setValue)
      .def("__contains__", [](const Settings&, const std::string& key) { return findSettingKey(key) != nullptr || isListKey(key); })
      .def_static(
          "keys",
          [] {
            py::list keys;
            for (const SettingKey& k : settingKeys()) keys.append(k.path);
            return keys;
          },
          "Every key, in the order of the file.")
      .def_static("key_info", &keyInfo, py::arg("key"), "A key's type, its range (numbers) or its choices.")
      .def_property(
          "source", [](const Settings& s) { return std::string(enumName(s.source)); },
          [](Settings& s, const std::string& name) {
            const auto kind = parseEnum<SourceKind>(name);
            if (!kind) throw StatusError(Status::InvalidSettings, "source: \"" + name + "\" is not one of " + enumChoices<SourceKind>());
            s.source = *kind;
          },
          R"(The source in use, "file", "camera" or "virtual" (default): its camera model, cameras.<source>,
is the one reconstruct() and Engine use. Not saved in the file.)")
      .def("copy", [](const Settings& s) { return s; })
      .def("__copy__", [](const Settings& s) { return s; })
      .def("__deepcopy__", [](const Settings& s, const py::dict&) { return s; })
      .def("__eq__", [](const Settings& a, const Settings& b) { return settingsToJson(a) == settingsToJson(b); })
      .def("__repr__", [](const Settings& s) {
        const Settings defaults;
        int changed = 0;
        const json mine = json::parse(settingsToJson(s)), theirs = json::parse(settingsToJson(defaults));
        for (const SettingKey& k : settingKeys()) changed += mine.at(pointerTo(k.path)) != theirs.at(pointerTo(k.path));
        return "<imagepro.Settings: " + (changed == 0 ? std::string("the defaults") : std::to_string(changed) + " keys changed from the defaults") + ">";
      });
}

}  // namespace imagepro::python
