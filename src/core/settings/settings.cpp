#include "core/settings/settings.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <limits>
#include <map>
#include <span>
#include <stdexcept>
#include <vector>

#include "core/common/atomic_file.h"
#include "core/common/image_limits.h"
#include "core/settings/enum_names.h"

namespace imagepro {

namespace {

using json = nlohmann::ordered_json;

constexpr double kInf = std::numeric_limits<double>::infinity();

// The methods that threshold a frame: every one of the enum's table but None, the
// re-threshold's by-pass only (a frame without a threshold has no binary image to search).
std::span<const ThresholdMethod> frameThresholds() {
  static const std::vector<ThresholdMethod> methods = [] {
    std::vector<ThresholdMethod> all;
    for (const EnumEntry<ThresholdMethod>& e : enumEntries(ThresholdMethod{}))
      if (e.value != ThresholdMethod::None) all.push_back(e.value);
    return all;
  }();
  return methods;
}

// A group of six per-parameter values in the pose's order (Rx, Ry, Rz, Tx, Ty, Tz), the
// rotations' and the translations' each in their own range.
template <class Visitor>
void poseGroup(Visitor& v, const char* key, Pose& p, const std::array<const char*, 6>& names, double angle_lo,
               double angle_hi, double mm_lo, double mm_hi) {
  v.object(key, [&] {
    v.field(names[0], p.rx_deg, angle_lo, angle_hi);
    v.field(names[1], p.ry_deg, angle_lo, angle_hi);
    v.field(names[2], p.rz_deg, angle_lo, angle_hi);
    v.field(names[3], p.tx_mm, mm_lo, mm_hi);
    v.field(names[4], p.ty_mm, mm_lo, mm_hi);
    v.field(names[5], p.tz_mm, mm_lo, mm_hi);
  });
}

// The keys of one camera model: a source's in "cameras", and an older file's one "camera".
template <class Visitor>
void visitCamera(Visitor& v, CameraModel& c) {
  v.field("width", c.width, 1, static_cast<int>(kMaxImageSide));
  v.field("height", c.height, 1, static_cast<int>(kMaxImageSide));
  v.field("pixel_size_mm", c.pixel_size_mm, 1e-9, kInf);
  v.field("image_plane_distance_mm", c.image_plane_distance_mm, 1e-9, kInf);
  v.field("principal_point_px", c.principal_point_px, -kInf, kInf);
  v.object("distortion", [&] {
    v.field("k1", c.distortion.k1, -kInf, kInf);
    v.field("k2", c.distortion.k2, -kInf, kInf);
    v.field("p1", c.distortion.p1, -kInf, kInf);
    v.field("p2", c.distortion.p2, -kInf, kInf);
  });
}

// Walks every key of the settings once. The same walk reads and writes, so a key,
// its place in the document and its valid range are written down exactly once.
template <class Visitor>
void visitSettings(Visitor& v, Settings& s) {
  v.object("cameras", [&] {
    for (const SourceKind k : kSourceKinds)
      v.object(std::string(enumName(k)).c_str(), [&] { visitCamera(v, s.camera(k)); });
  });
  v.object("target", [&] {
    v.field("radius_mm", s.target.radius_mm, 1e-9, kInf);
    v.field("spot_radius_mm", s.target.spot_radius_mm, 1e-9, kInf);
    v.field("spot_offset_mm", s.target.spot_offset_mm, 1e-9, kInf);
  });
  v.list("targets", s.targets, [&](TargetSpec& t) {
    v.field("id", t.id, 0, std::numeric_limits<int>::max());
    v.field("name", t.name);
    v.field("radius_mm", t.geometry.radius_mm, 1e-9, kInf);
    v.field("spot_radius_mm", t.geometry.spot_radius_mm, 1e-9, kInf);
    v.field("spot_offset_mm", t.geometry.spot_offset_mm, 1e-9, kInf);
  });
  v.object("frames", [&] {
    PoseFramesOptions& f = s.frames;
    v.field("reference_target", f.reference_target, -1, std::numeric_limits<int>::max());
    v.field("shown_target", f.shown_target, -1, std::numeric_limits<int>::max());
    v.field("measured_targets", f.measured_targets, -1, std::numeric_limits<int>::max());
    v.field("origin_set", f.origin_set);
    poseGroup(v, "origin", f.origin, {"rx_deg", "ry_deg", "rz_deg", "tx_mm", "ty_mm", "tz_mm"}, -360.0, 360.0, -kInf,
              kInf);
  });
  v.object("pattern", [&] {
    v.field("spot_spacing_mm", s.pattern.spot_spacing_mm, 1e-9, kInf);
    v.field("spot_radius_mm", s.pattern.spot_radius_mm, 1e-9, kInf);
    v.field("columns", s.pattern.columns, 1, 10000);
    v.field("rows", s.pattern.rows, 1, 10000);
    v.field("card_size_mm", s.pattern.card_size_mm, 1e-9, kInf);
  });
  v.object("virtual", [&] {
    VirtualSceneOptions& o = s.virtual_scene;
    v.field("mode", o.mode);
    v.field("backdrop", o.backdrop);
    v.field("supersampling", o.supersampling, 1, 16);
    v.field("blur_sigma_px", o.blur_sigma_px, 0.0, 50.0);
    v.field("noise_sigma", o.noise_sigma, 0.0, 255.0);
    v.field("illumination_gradient", o.illumination_gradient, -1.0, 1.0);
    v.field("clutter", o.clutter, 0, 1000);
    v.field("seed", o.seed, 0u, 0xffffffffu);
    v.field("white_level", o.white_level, 0, 255);
    v.field("black_level", o.black_level, 0, 255);
    v.field("background_level", o.background_level, 0, 255);
    v.field("card_size_mm", o.card_size_mm, 0.0, kInf);
    v.field("frame_rate_hz", o.frame_rate_hz, 1e-3, 1e6);
    v.object("pose", [&] {
      v.field("rx_deg", o.initial_pose.rx_deg, -360.0, 360.0);
      v.field("ry_deg", o.initial_pose.ry_deg, -360.0, 360.0);
      v.field("rz_deg", o.initial_pose.rz_deg, -360.0, 360.0);
      v.field("tx_mm", o.initial_pose.tx_mm, -kInf, kInf);
      v.field("ty_mm", o.initial_pose.ty_mm, -kInf, kInf);
      v.field("tz_mm", o.initial_pose.tz_mm, 1e-6, kInf);
    });
    v.object("motion", [&] {
      v.field("kind", o.motion.kind);
      v.field("axis", o.motion.axis);
      v.field("amplitude", o.motion.amplitude, -kInf, kInf);
      v.field("period_s", o.motion.period_s, 1e-6, kInf);
      poseGroup(v, "velocity", o.motion.velocity, {"rx_deg_s", "ry_deg_s", "rz_deg_s", "tx_mm_s", "ty_mm_s", "tz_mm_s"},
                -1e4, 1e4, -1e6, 1e6);
      poseGroup(v, "wrap_box", o.motion.wrap_box, {"rx_deg", "ry_deg", "rz_deg", "tx_mm", "ty_mm", "tz_mm"}, 0.0,
                360.0, 0.0, 1e6);
    });
    v.object("pendulum", [&] {
      v.field("length_mm", o.pendulum.length_mm, 1e-6, kInf);
      v.field("amplitude_deg", o.pendulum.amplitude_deg, 0.0, 89.0);
      v.field("gravity_m_s2", o.pendulum.gravity_m_s2, 1e-6, kInf);
      v.field("pivot_mm", o.pendulum.pivot_mm, -kInf, kInf);
      v.field("swing_axis_deg", o.pendulum.swing_axis_deg, -360.0, 360.0);
    });
    v.field("key_step_mm", o.key_step_mm, 0.0, kInf);
    v.field("key_step_deg", o.key_step_deg, 0.0, 180.0);
  });
  v.object("camera_source", [&] {
    CameraSourceOptions& o = s.camera_source;
    v.field("device", o.device);
    v.field("width", o.width, 0, static_cast<int>(kMaxImageSide));
    v.field("height", o.height, 0, static_cast<int>(kMaxImageSide));
    v.field("frame_rate_hz", o.frame_rate_hz, 0.0, 1e6);
    v.field("input", o.input, -1, 255);
    v.field("standard", o.standard);
    v.field("controls", o.controls);
  });
  v.object("stream", [&] {
    StreamOptions& o = s.stream;
    v.field("enabled", o.enabled);
    v.field("host", o.host);
    v.field("port", o.port, 1, 65535);
    v.field("format", o.format);
  });
  v.object("pipeline", [&] {
    PipelineOptions& p = s.pipeline;
    v.object("threshold", [&] {
      v.field("method", p.threshold.method, frameThresholds());
      v.field("value", p.threshold.manual_value, 0, 255);
    });
    v.object("binarization", [&] {
      v.field("mode", p.binarization.mode);
      v.field("window_px", p.binarization.window_px, 0, 2047);
      v.field("offset", p.binarization.offset, 0.0, 1.0);
      v.field("min_contrast", p.binarization.min_contrast, 0, 255);
      v.field("coarse_search", p.binarization.coarse_search);
    });
    v.field("edge_method", p.edge_method);
    v.field("connectivity", p.connectivity);
    v.object("ellipse", [&] {
      EllipseOptions& e = p.ellipse;
      v.field("method", e.method);
      v.field("accept_rule", e.accept_rule);
      v.field("max_relative_error", e.max_relative_error, 0.0, kInf);
      v.field("max_sampson_distance_px", e.max_sampson_distance_px, 0.0, kInf);
      v.field("min_path_pixels", e.min_path_pixels, 6, 1000000);
      v.field("trace_inlier_px", e.trace_inlier_px, 0.0, kInf);
      v.field("min_traced_fraction", e.min_traced_fraction, 0.0, 1.0);
      v.field("min_arc_fraction", e.min_arc_fraction, 0.0, 1.0);
      v.field("robust_fit", e.robust_fit);
      v.field("robust_iterations", e.robust_iterations, 1, 100000);
      v.field("robust_min_traced_fraction", e.robust_min_traced_fraction, 0.0, 1.0);
      v.field("bennett_min_score", e.bennett_min_score, 0.0, kInf);
      v.field("bennett_max_score", e.bennett_max_score, 0.0, kInf);
      v.field("bennett_min_quality", e.bennett_min_quality, 0.0, kInf);
      v.field("bennett_max_quality", e.bennett_max_quality, 0.0, kInf);
      v.field("bennett_min_peak_fraction", e.bennett_min_peak_fraction, 0.0, 1.0);
      v.field("bennett_max_relative_error", e.bennett_max_relative_error, 0.0, kInf);
      v.field("bennett_max_points", e.bennett_max_points, 0, 100000);
      v.field("target_spot_tolerance", e.target_spot_tolerance, 0.0, 1.0);
      v.field("target_max_tilt_deg", e.target_max_tilt_deg, 0.0, 90.0);
      v.field("require_target_spots", e.require_target_spots);
      v.field("report_all_targets", e.report_all_targets);
    });
    v.object("rethreshold", [&] {
      v.field("method", p.rethreshold.method);
      v.field("value", p.rethreshold.manual_value, 0, 255);
    });
    v.object("reconstruction", [&] {
      v.field("distortion_correction", p.reconstruction.distortion_correction);
      v.field("exact_undistortion", p.reconstruction.exact_undistortion);
      v.field("contour_mode", p.reconstruction.contour_mode);
      v.field("centre_spot_normal", p.reconstruction.centre_spot_normal);
      v.field("weighted_spot_centres", p.reconstruction.weighted_spot_centres);
      v.field("rim_edge_model", p.reconstruction.rim_edge_model);
      v.field("robust_rim_fit", p.reconstruction.robust_rim_fit);
      v.field("refine_pose", p.reconstruction.refine_pose);
      v.field("crop_margin_px", p.reconstruction.crop_margin_px, 0, 1000);
      v.field("max_spot_error_px", p.reconstruction.max_spot_error_px, 0.0, kInf);
      v.field("max_rim_error_px", p.reconstruction.max_rim_error_px, 0.0, kInf);
      v.field("ambiguity_ratio", p.reconstruction.ambiguity_ratio, 1.0, kInf);
      v.field("ambiguity_margin_px", p.reconstruction.ambiguity_margin_px, 0.0, kInf);
      v.field("ambiguity_tolerance_deg", p.reconstruction.ambiguity_tolerance_deg, 0.0, 180.0);
    });
    v.object("tracking", [&] {
      TrackingOptions& t = p.tracking;
      v.field("mode", t.mode);
      v.field("data_points", t.data_points, 1, 100);
      v.field("degree", t.degree, 0, 3);
      v.field("min_r", t.min_r, -1.0, 1.0);
      v.field("reduction_percent", t.reduction_percent, 0.0, 100.0);
      v.field("enlarge_px", t.enlarge_px, 0.0, kInf);
      v.field("enlarge_scale", t.enlarge_scale, 0.0, kInf);
      v.field("enlarge_speed_scale", t.enlarge_speed_scale, 0.0, kInf);
    });
    v.field("level", p.level);
    v.object("display", [&] {
      v.field("background", p.display.background);
      v.field("edges", p.display.edges);
      v.field("target", p.display.target);
      v.field("feature_edge", p.display.feature_edge);
      v.field("feature_spots", p.display.feature_spots);
      v.field("calibration_check", p.display.calibration_check);
    });
    v.object("calibration", [&] {
      v.field("relative_change", p.calibration.relative_change, 1e-12, 1.0);
      v.field("max_iterations", p.calibration.max_iterations, 1, 1000);
      v.field("min_matches", p.calibration.min_matches, 4, 1000000);
      v.field("max_ambiguous_fraction", p.calibration.max_ambiguous_fraction, 0.0, 1.0);
      v.field("refine_pose", p.calibration.refine_pose);
    });
  });
}

struct SettingsKeyError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

template <class E>
concept OptionEnum = std::is_enum_v<E> && requires(E e) { enumEntries(e); };

// A key that takes only some of its enum's values.
template <class E>
bool allows(std::span<const E> allowed, E value) {
  return std::find(allowed.begin(), allowed.end(), value) != allowed.end();
}

// "a, b, c": the keys of the values a key takes, for error messages.
template <class E>
std::string choicesOf(std::span<const E> allowed) {
  std::string out;
  for (const auto& e : enumEntries(E{}))
    if (allows(allowed, e.value)) out += (out.empty() ? "" : ", ") + std::string(e.key);
  return out;
}

class Reader {
 public:
  explicit Reader(const json& root) { stack_.push_back({&root, "", {}}); }

  template <class Fn>
  void object(const char* key, Fn&& body) {
    const json* child = enter(key);
    if (!child) return;
    if (!child->is_object()) fail(path(key), "expected an object");
    stack_.push_back({child, path(key), {}});
    body();
    finishObject();
    stack_.pop_back();
  }

  // A list of objects, each read over a default element; the list replaces the old one.
  template <class T, class Fn>
  void list(const char* key, std::vector<T>& items, Fn&& body) {
    const json* j = enter(key);
    if (!j) return;
    if (!j->is_array()) fail(path(key), "expected an array of objects");
    std::vector<T> parsed(j->size());
    for (std::size_t i = 0; i < j->size(); ++i) {
      const std::string where = path(key) + "[" + std::to_string(i) + "]";
      if (!(*j)[i].is_object()) fail(where, "expected an object");
      stack_.push_back({&(*j)[i], where, {}});
      body(parsed[i]);
      finishObject();
      stack_.pop_back();
    }
    items = std::move(parsed);
  }

  void field(const char* key, bool& value) {
    if (const json* j = enter(key)) {
      if (!j->is_boolean()) fail(path(key), "expected true or false");
      value = j->get<bool>();
    }
  }

  void field(const char* key, std::string& value) {
    if (const json* j = enter(key)) {
      if (!j->is_string() || j->get<std::string>().empty()) fail(path(key), "expected a non-empty string");
      value = j->get<std::string>();
    }
  }

  // Names of the caller's choosing (camera control keys) with whole numbers.
  void field(const char* key, std::map<std::string, std::int64_t>& value) {
    const json* j = enter(key);
    if (!j) return;
    if (!j->is_object()) fail(path(key), "expected an object of names and whole numbers");
    std::map<std::string, std::int64_t> parsed;
    for (const auto& [name, item] : j->items()) {
      const std::string where = path(key) + "." + name;
      const bool well_formed = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
      });
      if (!well_formed) fail(where, "a name of lower-case letters, digits and '_' expected");
      parsed[name] = number<std::int64_t>(item, where, std::numeric_limits<std::int64_t>::min(),
                                          std::numeric_limits<std::int64_t>::max());
    }
    value = std::move(parsed);
  }

  template <class E>
    requires OptionEnum<E>
  void field(const char* key, E& value) {
    if (const json* j = enter(key)) value = choice<E>(*j, path(key), enumChoices<E>(), {});
  }

  template <class E>
    requires OptionEnum<E>
  void field(const char* key, E& value, std::span<const E> allowed) {
    if (const json* j = enter(key)) value = choice<E>(*j, path(key), choicesOf(allowed), allowed);
  }

  template <class T>
    requires std::is_arithmetic_v<T>
  void field(const char* key, T& value, T lo, T hi) {
    if (const json* j = enter(key)) value = number<T>(*j, path(key), lo, hi);
  }

  template <class T, std::size_t N>
  void field(const char* key, std::array<T, N>& value, T lo, T hi) {
    const json* j = enter(key);
    if (!j) return;
    if (!j->is_array() || j->size() != N)
      fail(path(key), "expected an array of " + std::to_string(N) + " numbers");
    for (std::size_t i = 0; i < N; ++i)
      value[i] = number<T>((*j)[i], path(key) + "[" + std::to_string(i) + "]", lo, hi);
  }

  void finishObject() {
    const Level& level = stack_.back();
    for (const auto& [k, unused] : level.node->items()) {
      bool known = false;
      for (const auto& seen : level.seen) known = known || seen == k;
      if (!known) fail(level.path.empty() ? k : level.path + "." + k, "unknown key");
    }
  }

 private:
  struct Level {
    const json* node;
    std::string path;
    std::vector<std::string> seen;
  };

  const json* enter(const char* key) {
    Level& level = stack_.back();
    level.seen.emplace_back(key);
    const auto it = level.node->find(key);
    return it == level.node->end() ? nullptr : &*it;
  }

  std::string path(const char* key) const {
    return stack_.back().path.empty() ? std::string(key) : stack_.back().path + "." + key;
  }

  // An enum's key; with `allowed` given, one of those values only.
  template <class E>
  static E choice(const json& j, const std::string& where, const std::string& choices, std::span<const E> allowed) {
    if (!j.is_string()) fail(where, "expected a string, one of: " + choices);
    const std::string text = j.get<std::string>();
    const auto parsed = parseEnum<E>(text);
    if (!parsed) fail(where, "unknown value \"" + text + "\" (expected one of: " + choices + ")");
    if (!allowed.empty() && !allows(allowed, *parsed))
      fail(where, "\"" + text + "\" is not allowed here (expected one of: " + choices + ")");
    return *parsed;
  }

  template <class T>
  static T number(const json& j, const std::string& where, T lo, T hi) {
    if constexpr (std::is_integral_v<T>) {
      if (!j.is_number_integer()) fail(where, "expected a whole number");
      // Above 2^63-1 JSON's unsigned numbers do not fit a long long: out of range as they stand.
      const bool huge = j.is_number_unsigned() &&
                        j.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<long long>::max());
      const long long v = huge ? 0 : j.get<long long>();
      if (huge || v < static_cast<long long>(lo) || v > static_cast<long long>(hi))
        fail(where, "value " + j.dump() + " out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
      return static_cast<T>(v);
    } else {
      if (!j.is_number()) fail(where, "expected a number");
      const double v = j.get<double>();
      if (!(v >= lo && v <= hi)) fail(where, "value " + j.dump() + " out of range");
      return static_cast<T>(v);
    }
  }

  [[noreturn]] static void fail(const std::string& where, const std::string& what) {
    throw SettingsKeyError(where + ": " + what);
  }

  std::vector<Level> stack_;
};

class Writer {
 public:
  Writer() { stack_.push_back(&root_); }

  template <class Fn>
  void object(const char* key, Fn&& body) {
    json& child = (*stack_.back())[key] = json::object();
    stack_.push_back(&child);
    body();
    stack_.pop_back();
  }

  // An empty list is left out: a file without it reads the same.
  template <class T, class Fn>
  void list(const char* key, std::vector<T>& items, Fn&& body) {
    if (items.empty()) return;
    json& array = (*stack_.back())[key] = json::array();
    for (T& item : items) {
      array.push_back(json::object());
      stack_.push_back(&array.back());
      body(item);
      stack_.pop_back();
    }
  }

  void field(const char* key, bool& value) { (*stack_.back())[key] = value; }
  // An empty text (a target's name left out) is not written: the reader takes none as empty.
  void field(const char* key, std::string& value) {
    if (!value.empty()) (*stack_.back())[key] = value;
  }
  void field(const char* key, std::map<std::string, std::int64_t>& value) {
    json& object = (*stack_.back())[key] = json::object();
    for (const auto& [name, v] : value) object[name] = v;
  }

  template <class E>
    requires OptionEnum<E>
  void field(const char* key, E& value) {
    (*stack_.back())[key] = std::string(enumName(value));
  }

  template <class E>
    requires OptionEnum<E>
  void field(const char* key, E& value, std::span<const E>) {
    field(key, value);
  }

  template <class T>
  void field(const char* key, T& value, T, T) {
    (*stack_.back())[key] = value;
  }

  template <class T, std::size_t N>
  void field(const char* key, std::array<T, N>& value, T, T) {
    (*stack_.back())[key] = value;
  }

  const json& root() const { return root_; }

 private:
  json root_ = json::object();
  std::vector<json*> stack_;
};

// Finds where in the document parsing stopped: a second, SAX pass that keeps the key
// path ("cameras.file.principal_point_px[1]") of the value being read when the error comes.
class ErrorLocator {
 public:
  using string_t = json::string_t;
  std::string where;
  int id = 0;  // the nlohmann exception's id (406: a number too large for a double)
  std::string what;

  bool null() { return value(); }
  bool boolean(bool) { return value(); }
  bool number_integer(json::number_integer_t) { return value(); }
  bool number_unsigned(json::number_unsigned_t) { return value(); }
  bool number_float(json::number_float_t, const string_t&) { return value(); }
  bool string(string_t&) { return value(); }
  bool binary(json::binary_t&) { return value(); }
  bool start_object(std::size_t) {
    levels_.push_back({false, {}, 0});
    return true;
  }
  bool key(string_t& k) {
    levels_.back().key = k;
    return true;
  }
  bool end_object() { return endLevel(); }
  bool start_array(std::size_t) {
    levels_.push_back({true, {}, 0});
    return true;
  }
  bool end_array() { return endLevel(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) {
    for (const Level& l : levels_) {
      if (l.array) where += "[" + std::to_string(l.index) + "]";
      else if (!l.key.empty()) where += (where.empty() ? "" : ".") + l.key;
    }
    id = e.id;
    what = e.what();
    return false;
  }

 private:
  struct Level {
    bool array;
    std::string key;
    std::size_t index;
  };
  bool value() {
    if (!levels_.empty() && levels_.back().array) ++levels_.back().index;
    return true;
  }
  bool endLevel() {
    levels_.pop_back();
    return value();
  }
  std::vector<Level> levels_;
};

// "[json.exception.parse_error.101] parse error at line 1 ..." -> "parse error at line 1 ...".
std::string withoutExceptionTag(const std::string& what) {
  const auto end = what.rfind("] ", what.find(' '));
  return what.rfind("[json.exception.", 0) == 0 && end != std::string::npos ? what.substr(end + 2) : what;
}

// The problem that stopped parsing, named by the key it was reading.
std::string parseProblem(std::string_view json_text, const std::string& what) {
  ErrorLocator locator;
  json::sax_parse(json_text, &locator);
  const std::string message = locator.what.empty() ? what : locator.what;
  if (locator.id == 406 && !locator.where.empty())
    return locator.where + ": " + withoutExceptionTag(message) + " (larger than any number a double holds)";
  return std::string("not valid JSON") + (locator.where.empty() ? "" : " at " + locator.where) + ": " +
         withoutExceptionTag(message);
}

// The path of the key being visited ("pipeline.ellipse.method"), for the visitors
// that name keys without reading or writing a document.
class KeyPath {
 public:
  template <class Fn>
  void object(const char* key, Fn&& body) {
    prefix_.push_back(path(key) + ".");
    body();
    prefix_.pop_back();
  }

  // The elements there are: none in the defaults, so settingKeys() lists no element's key.
  template <class T, class Fn>
  void list(const char* key, std::vector<T>& items, Fn&& body) {
    for (std::size_t i = 0; i < items.size(); ++i) {
      prefix_.push_back(path(key) + "[" + std::to_string(i) + "].");
      body(items[i]);
      prefix_.pop_back();
    }
  }

 protected:
  std::string path(const char* key) const { return (prefix_.empty() ? std::string() : prefix_.back()) + key; }

 private:
  std::vector<std::string> prefix_;
};

// Lists the keys: their paths, types and ranges.
class KeyLister : public KeyPath {
 public:
  void field(const char* key, bool&) { add(key, SettingKey::Type::Flag); }
  void field(const char* key, std::string&) { add(key, SettingKey::Type::Text); }
  void field(const char* key, std::map<std::string, std::int64_t>&) { add(key, SettingKey::Type::Names); }

  template <class E>
    requires OptionEnum<E>
  void field(const char* key, E& value) {
    field(key, value, std::span<const E>());
  }

  // Empty `allowed`: every value of the enum.
  template <class E>
    requires OptionEnum<E>
  void field(const char* key, E&, std::span<const E> allowed) {
    SettingKey& k = add(key, SettingKey::Type::Choice);
    k.choice = typeid(E);
    for (const auto& e : enumEntries(E{}))
      if (allowed.empty() || allows(allowed, e.value)) k.choices.push_back({e.key, e.label, e.description});
  }

  template <class T>
    requires std::is_arithmetic_v<T>
  void field(const char* key, T&, T lo, T hi) {
    number<T>(path(key), lo, hi);
  }

  template <class T, std::size_t N>
  void field(const char* key, std::array<T, N>&, T lo, T hi) {
    for (std::size_t i = 0; i < N; ++i) number<T>(path(key) + "[" + std::to_string(i) + "]", lo, hi);
  }

  std::vector<SettingKey> keys;

 private:
  SettingKey& add(const char* key, SettingKey::Type type) { return add(path(key), type); }
  SettingKey& add(std::string path, SettingKey::Type type) {
    keys.push_back({});
    keys.back().path = std::move(path);
    keys.back().type = type;
    return keys.back();
  }

  template <class T>
  void number(std::string path, T lo, T hi) {
    SettingKey& k = add(std::move(path), std::is_integral_v<T> ? SettingKey::Type::WholeNumber : SettingKey::Type::Number);
    k.lo = static_cast<double>(lo);
    k.hi = static_cast<double>(hi);
  }
};

// The path of the value at one address: the key a widget bound to that value edits.
class AddressFinder : public KeyPath {
 public:
  explicit AddressFinder(const void* target) : target_(target) {}

  template <class T>
  void field(const char* key, T& value) {
    check(key, &value);
  }

  template <class T>
  void field(const char* key, T& value, T, T) {
    check(key, &value);
  }

  template <class E>
  void field(const char* key, E& value, std::span<const E>) {
    check(key, &value);
  }

  template <class T, std::size_t N>
  void field(const char* key, std::array<T, N>& value, T, T) {
    for (std::size_t i = 0; i < N; ++i)
      if (&value[i] == target_) found = path(key) + "[" + std::to_string(i) + "]";
  }

  std::string found;

 private:
  void check(const char* key, const void* address) {
    if (address == target_) found = path(key);
  }

  const void* target_;
};

}  // namespace

namespace {

// Keys renamed since files were written with them: read under the old name too, with a
// warning; written under the new one.
struct RenamedKey {
  std::string_view parent;  // the object holding it, "pipeline.reconstruction"
  std::string_view old_name, new_name;
};
constexpr std::array kRenamedKeys{
    // A tolerance (the halfway pose lies within it of both circles), not a minimum.
    RenamedKey{"pipeline.reconstruction", "ambiguity_min_deg", "ambiguity_tolerance_deg"},
};

// Moves each renamed key of `root` to its new name; both names at once is an error.
void readRenamedKeys(json& root, std::vector<std::string>& warnings) {
  for (const RenamedKey& r : kRenamedKeys) {
    json* parent = &root;
    std::string_view rest = r.parent;
    while (parent && !rest.empty()) {
      const std::size_t dot = rest.find('.');
      const std::string name(rest.substr(0, dot));
      rest = dot == std::string_view::npos ? std::string_view{} : rest.substr(dot + 1);
      const auto it = parent->is_object() ? parent->find(name) : parent->end();
      parent = it == parent->end() ? nullptr : &*it;
    }
    if (!parent || !parent->is_object() || !parent->contains(r.old_name)) continue;
    const std::string old_path = std::string(r.parent) + "." + std::string(r.old_name);
    const std::string new_path = std::string(r.parent) + "." + std::string(r.new_name);
    if (parent->contains(r.new_name))
      throw SettingsKeyError(old_path + ": the old name of " + new_path + ", which is given too; keep one");
    (*parent)[std::string(r.new_name)] = std::move((*parent)[std::string(r.old_name)]);
    parent->erase(std::string(r.old_name));
    warnings.push_back(old_path + " is now " + new_path + ": read as such (saving writes the new name)");
  }
}

}  // namespace

Status settingsFromJson(std::string_view json_text, Settings& out, std::string& error,
                        std::vector<std::string>* warnings) {
  json root;
  try {
    root = json::parse(json_text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number beyond a double
    error = parseProblem(json_text, e.what());
    return Status::InvalidSettings;
  }
  if (!root.is_object()) {
    error = "the settings must be a JSON object";
    return Status::InvalidSettings;
  }
  Settings parsed = out;
  std::vector<std::string> renamed;
  try {
    readRenamedKeys(root, renamed);
    Reader reader(root);
    // An older file's one camera is every source's; "cameras", read next, may still give
    // a source its own.
    const bool one_camera = root.contains("camera");
    if (one_camera)
      for (const SourceKind k : kSourceKinds) reader.object("camera", [&] { visitCamera(reader, parsed.camera(k)); });
    visitSettings(reader, parsed);
    reader.finishObject();
    // Each side is bounded by its key; together they may still be more than a frame can hold.
    for (const SourceKind k : kSourceKinds) {
      const CameraModel& c = parsed.camera(k);
      const std::string name(enumName(k));
      const auto own = root.find("cameras");
      const bool own_entry = own != root.end() && own->contains(name);
      const std::string at = one_camera && !own_entry ? std::string("camera") : "cameras." + name;
      if (const std::string problem = imageSizeProblem(c.width, c.height); !problem.empty())
        throw SettingsKeyError(at + ".width, " + at + ".height: " + problem);
    }
    if (const std::string problem = targetSetProblem(parsed.targets); !problem.empty())
      throw SettingsKeyError("targets: " + problem);
    if (const std::string problem = framesProblem(parsed.frames, parsed.targets); !problem.empty())
      throw SettingsKeyError(problem);
  } catch (const SettingsKeyError& e) {
    error = e.what();
    return Status::InvalidSettings;
  } catch (const json::exception& e) {  // a value nlohmann cannot convert: no key to blame, but no abort
    error = std::string("cannot read the settings: ") + withoutExceptionTag(e.what());
    return Status::InvalidSettings;
  }
  out = parsed;
  if (warnings) warnings->insert(warnings->end(), renamed.begin(), renamed.end());
  return Status::Ok;
}

std::string settingsToJson(const Settings& settings) {
  Settings copy = settings;  // the visitor takes non-const references
  Writer writer;
  visitSettings(writer, copy);
  return writer.root().dump(2) + "\n";
}

Status loadSettings(const std::string& path, Settings& out, std::string& error,
                    std::vector<std::string>* warnings) {
  std::string text;
  if (!readWholeFile(path, text, error)) return Status::FileNotFound;
  std::string detail;
  std::vector<std::string> read_warnings;
  const Status s = settingsFromJson(text, out, detail, &read_warnings);
  if (!ok(s)) error = path + ": " + detail;
  if (warnings)
    for (const std::string& w : read_warnings) warnings->push_back(path + ": " + w);
  return s;
}

Status saveSettings(const std::string& path, const Settings& settings, std::string& error) {
  return writeFileAtomically(path, settingsToJson(settings), error) ? Status::Ok : Status::FileNotWritable;
}

const std::vector<SettingKey>& settingKeys() {
  static const std::vector<SettingKey> keys = [] {
    Settings defaults;
    KeyLister lister;
    visitSettings(lister, defaults);
    return std::move(lister.keys);
  }();
  return keys;
}

const SettingKey* findSettingKey(std::string_view path) {
  for (const SettingKey& k : settingKeys())
    if (k.path == path) return &k;
  return nullptr;
}

const SettingKey* settingKeyOf(const Settings& settings, const void* field) {
  AddressFinder finder(field);
  // The walk only compares addresses; nothing is written through it.
  visitSettings(finder, const_cast<Settings&>(settings));
  return finder.found.empty() ? nullptr : findSettingKey(finder.found);
}

}  // namespace imagepro
