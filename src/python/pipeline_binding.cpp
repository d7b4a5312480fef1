// imagepro's frame functions: detect and reconstruct on one image, the Engine over a
// stream, render for virtual frames. They run the core's own entry points (the stage
// chain, the engine, the renderer) with the interpreter's lock released.
//
// The rule for errors: a call that cannot run raises (an image that is not an 8-bit
// grey or BGR array, a file that cannot be read or written, a settings value the file
// would refuse); a frame that runs reports its outcome in Result.status, so a frame
// loop goes on past frames without a target. Result.raise_for_status() turns a failed
// frame into its exception where one is wanted.
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <optional>

#include "core/pipeline/engine.h"
#include "core/pipeline/frame_record.h"
#include "core/pipeline/stage_chain.h"
#include "core/settings/enum_names.h"
#include "core/source/virtual_renderer.h"
#include "python/bindings.h"
#include "python/errors.h"
#include "python/image_arg.h"

namespace py = pybind11;

namespace imagepro::python {

namespace {

using Point = std::array<double, 2>;

// What one frame gave, as the module reports it.
struct Result {
  FrameResult frame;
  // The centre spot's and the offset spot's centres in image pixels as seen, when found.
  std::optional<std::array<Point, 2>> spots;
};

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

std::string poseRepr(const Pose& p) {
  return "Pose(rx_deg=" + number(p.rx_deg) + ", ry_deg=" + number(p.ry_deg) + ", rz_deg=" + number(p.rz_deg) +
         ", tx_mm=" + number(p.tx_mm) + ", ty_mm=" + number(p.ty_mm) + ", tz_mm=" + number(p.tz_mm) + ")";
}

std::string ellipseRepr(const Ellipse& e) {
  return "Ellipse(cx=" + number(e.cx) + ", cy=" + number(e.cy) + ", a=" + number(e.a) + ", b=" + number(e.b) +
         ", angle_deg=" + number(e.angle_deg) + ")";
}

py::tuple rect(const cv::Rect& r) { return py::make_tuple(r.x, r.y, r.width, r.height); }

const Settings& settingsOr(const std::optional<Settings>& settings) {
  static const Settings defaults;
  return settings ? *settings : defaults;
}

Point centroid(std::span<const EdgePixel> path) {
  double u = 0.0, v = 0.0;
  for (const EdgePixel& p : path) {
    u += p.x;
    v += p.y;
  }
  const double n = path.empty() ? 1.0 : static_cast<double>(path.size());
  return {u / n, v / n};
}

// The reconstruction's spots, where it found them (a pose was computed from them).
void keepReconstructedSpots(Result& r) {
  if (!r.frame.pose && !r.frame.ambiguous_poses) return;
  const auto& s = r.frame.spots;
  r.spots = std::array<Point, 2>{Point{s[0].x, s[0].y}, Point{s[1].x, s[1].y}};
}

Result detect(const py::handle& image, const std::optional<Settings>& settings) {
  py::array holder;
  const cv::Mat grey = greyImageArg(image, holder);
  Settings s = settingsOr(settings);
  s.pipeline.level = ApplicationLevel::Ellipse;  // as imagepro-cli detect
  Result r;
  StageChain chain;
  {
    py::gil_scoped_release unlocked;
    runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, r.frame);
  }
  // The spots the ellipse stage found inside the target: the centres of their edge paths.
  if (!chain.detections.empty() && chain.detections.front().spots_found) {
    const auto& paths = chain.detections.front().spot_paths;
    if (paths[0] != kNoPath && paths[1] != kNoPath)
      r.spots = std::array<Point, 2>{centroid(chain.paths.path(paths[0])), centroid(chain.paths.path(paths[1]))};
  }
  return r;
}

Result reconstruct(const py::handle& image, const std::optional<Settings>& settings) {
  py::array holder;
  Frame frame;
  frame.image = greyImageArg(image, holder);
  frame.name = "image";  // a still: nothing tracked from or to another frame
  Result r;
  {
    py::gil_scoped_release unlocked;
    Engine engine(settingsOr(settings));
    engine.process(frame, r.frame);
  }
  keepReconstructedSpots(r);
  return r;
}

// The engine of a stream: frame after frame, with tracking. One call at a time (a lock,
// taken with the interpreter's lock released, so other Python threads run meanwhile).
class StreamEngine {
 public:
  explicit StreamEngine(const Settings& settings) : engine_(settings) {}

  Result process(const py::handle& image, std::optional<double> timestamp_s) {
    py::array holder;
    Frame frame;
    // The engine keeps the last frame until the next one: its own copy, not the caller's array.
    frame.image = greyImageArg(image, holder).clone();
    Result r;
    {
      py::gil_scoped_release unlocked;
      const std::lock_guard lock(mutex_);
      frame.index = next_index_++;
      // Without a timestamp the tracker's clock is the frame's index.
      frame.timestamp_s = timestamp_s.value_or(0.0);
      engine_.process(frame, r.frame);
    }
    keepReconstructedSpots(r);
    return r;
  }

  Settings settings() {
    py::gil_scoped_release unlocked;
    const std::lock_guard lock(mutex_);
    return engine_.settings();
  }
  void setSettings(const Settings& s) {
    py::gil_scoped_release unlocked;
    const std::lock_guard lock(mutex_);
    engine_.setSettings(s);
  }
  void resetTracking() {
    py::gil_scoped_release unlocked;
    const std::lock_guard lock(mutex_);
    engine_.resetTracking();
  }
  std::int64_t frames() {
    py::gil_scoped_release unlocked;
    const std::lock_guard lock(mutex_);
    return next_index_;
  }

 private:
  std::mutex mutex_;
  Engine engine_;
  std::int64_t next_index_ = 0;
};

py::array_t<std::uint8_t> render(const Pose& pose, const std::optional<Settings>& settings, bool pattern,
                                 std::uint64_t frame_seed) {
  const Settings& s = settingsOr(settings);
  const CameraModel& camera = s.camera(SourceKind::Virtual);
  py::array_t<std::uint8_t> out({camera.height, camera.width});
  // Drawn straight into the array: the renderer keeps an output of the camera's size and type.
  cv::Mat image(camera.height, camera.width, CV_8UC1, out.mutable_data());
  const void* pixels = image.data;
  {
    py::gil_scoped_release unlocked;
    if (pattern) renderPattern(camera, s.target, s.pattern, s.virtual_scene, pose, image, frame_seed);
    else renderTarget(camera, s.target, s.virtual_scene, pose, image, frame_seed);
  }
  return image.data == pixels ? out : numpyImage(image);
}

void bindGeometry(py::module_& m) {
  py::class_<Pose>(m, "Pose", R"(The target's pose in the camera frame (docs/conventions.md):
P_camera = Rz(rz) Ry(ry) Rx(rx) P_target + (tx, ty, tz); angles in degrees, lengths in mm.)")
      .def(py::init([](double rx, double ry, double rz, double tx, double ty, double tz) {
             return Pose{rx, ry, rz, tx, ty, tz};
           }),
           py::arg("rx_deg") = 0.0, py::arg("ry_deg") = 0.0, py::arg("rz_deg") = 0.0, py::arg("tx_mm") = 0.0,
           py::arg("ty_mm") = 0.0, py::arg("tz_mm") = 1000.0)
      .def_readwrite("rx_deg", &Pose::rx_deg)
      .def_readwrite("ry_deg", &Pose::ry_deg)
      .def_readwrite("rz_deg", &Pose::rz_deg)
      .def_readwrite("tx_mm", &Pose::tx_mm)
      .def_readwrite("ty_mm", &Pose::ty_mm)
      .def_readwrite("tz_mm", &Pose::tz_mm)
      .def("as_tuple", [](const Pose& p) { return py::make_tuple(p.rx_deg, p.ry_deg, p.rz_deg, p.tx_mm, p.ty_mm, p.tz_mm); },
           "(rx_deg, ry_deg, rz_deg, tx_mm, ty_mm, tz_mm)")
      .def("rotation_error_deg",
           [](const Pose& a, const Pose& b) { return rotationAngleBetweenDeg(rotationMatrix(a), rotationMatrix(b)); },
           py::arg("other"), "The angle of the rotation between this pose's orientation and the other's, degrees.")
      .def("__eq__", [](const Pose& a, const Pose& b) {
        return a.rx_deg == b.rx_deg && a.ry_deg == b.ry_deg && a.rz_deg == b.rz_deg && a.tx_mm == b.tx_mm &&
               a.ty_mm == b.ty_mm && a.tz_mm == b.tz_mm;
      })
      .def("__repr__", &poseRepr);

  py::class_<Ellipse>(m, "Ellipse", "An ellipse in image pixels: centre, semi-axes a >= b, major axis from +u towards +v.")
      .def_readonly("cx", &Ellipse::cx)
      .def_readonly("cy", &Ellipse::cy)
      .def_readonly("a", &Ellipse::a)
      .def_readonly("b", &Ellipse::b)
      .def_readonly("angle_deg", &Ellipse::angle_deg)
      .def("__repr__", &ellipseRepr);

  py::class_<TargetSummary>(m, "Target", "One target the ellipse stage found.")
      .def_readonly("ellipse", &TargetSummary::ellipse)
      .def_readonly("fit_error", &TargetSummary::fit_error, "E_rel of the direct fit (eq. 2.42), else 0")
      .def_readonly("sampson_px", &TargetSummary::sampson_px, "mean Sampson distance of its path, pixels")
      .def_readonly("bennett_score", &TargetSummary::bennett_score)
      .def_property_readonly("bbox", [](const TargetSummary& t) { return rect(t.bbox); }, "(x, y, width, height)")
      .def_property_readonly("status", [](const TargetSummary& t) { return std::string(statusName(t.status)); },
                             "its own reconstruction's status (a set of targets; \"Stopped\" when not reconstructed)")
      .def_property_readonly("target", [](const TargetSummary& t) -> std::optional<int> {
            if (t.target_id < 0) return std::nullopt;
            return t.target_id;
          }, "the id of the settings' target it is, or None")
      .def_property_readonly("pose", [](const TargetSummary& t) -> std::optional<Pose> {
            if (!ok(t.status)) return std::nullopt;
            return t.pose;
          }, "its pose when its status is ok, else None")
      .def_property_readonly("pose_in_reference", [](const TargetSummary& t) { return t.pose_in_reference; },
                             "its pose in the reference target's frame (settings frames.reference_target), or None")
      .def_property_readonly("pose_in_world", [](const TargetSummary& t) { return t.pose_in_world; },
                             "its pose in the world frame of settings frames.origin, or None")
      .def("__repr__", [](const TargetSummary& t) {
        std::string text = "Target(" + ellipseRepr(t.ellipse);
        if (t.target_id >= 0) text += ", id " + std::to_string(t.target_id);
        return text + ")";
      });
}

void bindResult(py::module_& m) {
  py::class_<Result> result(m, "Result", R"(What one frame gave. status is "ok" or the name of the first stage's
failure (NoTarget, SpotsNotFound, AmbiguousPose, ...); a failure is reported here, not raised:
raise_for_status() raises it as its imagepro exception.)");
  result.def_property_readonly("status", [](const Result& r) { return std::string(statusName(r.frame.status)); })
      .def_property_readonly("message", [](const Result& r) { return std::string(statusMessage(r.frame.status)); })
      .def_property_readonly("ok", [](const Result& r) { return ok(r.frame.status); })
      .def_property_readonly(
          "ellipse",
          [](const Result& r) -> std::optional<Ellipse> {
            if (r.frame.targets.empty()) return std::nullopt;
            return r.frame.targets.front().ellipse;
          },
          "The target's ellipse (the first target's), or None.")
      .def_readonly("spots", &Result::spots,
                    "((u, v) of the centre spot, (u, v) of the offset spot) in image pixels as seen, or None")
      .def_property_readonly("pose", [](const Result& r) { return r.frame.pose; }, "The pose, or None.")
      .def_property_readonly(
          "candidates",
          [](const Result& r) {
            std::vector<Pose> poses;
            if (r.frame.ambiguous_poses) poses.assign(r.frame.ambiguous_poses->begin(), r.frame.ambiguous_poses->end());
            return poses;
          },
          "The two poses the rim allows when the spots could not tell them apart (AmbiguousPose, or ok "
          "with the pose halfway between them), the one fitting the spots better first.")
      .def_property_readonly("targets", [](const Result& r) { return r.frame.targets; })
      .def_property_readonly("index", [](const Result& r) { return r.frame.index; })
      .def_property_readonly("reached", [](const Result& r) { return std::string(enumName(r.frame.reached)); },
                             "The last stage that ran.")
      .def_property_readonly("threshold", [](const Result& r) { return r.frame.threshold; })
      .def_property_readonly("search_region", [](const Result& r) { return rect(r.frame.search_region); },
                             "(x, y, width, height) searched: the tracked region, or the whole image")
      .def_property_readonly("detected_region", [](const Result& r) { return rect(r.frame.detected_region); })
      .def_property_readonly(
          "times_us",
          [](const Result& r) {
            py::dict times;
            for (std::size_t i = 0; i < kStageCount; ++i)
              times[stageName(static_cast<Stage>(i))] = r.frame.times.us[i];
            return times;
          },
          "Each stage's wall time, microseconds.")
      .def("raise_for_status",
           [](const Result& r) {
             if (!ok(r.frame.status)) throw StatusError(r.frame.status, {});
           })
      .def("__repr__", [](const Result& r) {
        std::string text = "<imagepro.Result " + std::string(statusName(r.frame.status));
        if (r.frame.pose) text += " " + poseRepr(*r.frame.pose);
        else if (!r.frame.targets.empty()) text += " " + ellipseRepr(r.frame.targets.front().ellipse);
        return text + ">";
      });
  // The frame record's scalar fields (core/pipeline/frame_record.h): a number, a text, or None.
  for (const FrameField& field : frameFields()) {
    if (!(field.outputs & kPython)) continue;
    result.def_property_readonly(
        std::string(field.name).c_str(),
        [&field](const Result& r) -> py::object {
          const FieldValue v = field.value(r.frame, field.arg);
          if (v.kind == FieldValue::Kind::Number) return py::float_(v.number);
          if (v.kind == FieldValue::Kind::Text) return py::str(v.text);
          return py::none();
        },
        std::string(field.description).c_str());
  }
}

}  // namespace

void bindPipeline(py::module_& m) {
  bindGeometry(m);
  bindResult(m);

  m.def("detect", &detect, py::arg("image"), py::arg("settings") = py::none(),
        R"(Finds the target's ellipse and spots in one image (imagepro-cli detect): threshold,
edges, paths, ellipse stage. image: uint8 numpy array, HxW grey or HxWx3 BGR. The pose is None.)");
  m.def("reconstruct", &reconstruct, py::arg("image"), py::arg("settings") = py::none(),
        R"(The whole pipeline on one image (imagepro-cli reconstruct on a still): the ellipse,
the spots and the pose. The image's size must be the settings' camera's, else FrameSizeMismatch.)");

  py::class_<StreamEngine>(m, "Engine", R"(The frame loop's engine: frames of one stream in order, with
tracking (the searched region follows the target; pipeline.tracking). process(image) gives a Result.)")
      .def(py::init([](const std::optional<Settings>& s) { return new StreamEngine(settingsOr(s)); }),
           py::arg("settings") = py::none())
      .def("process", &StreamEngine::process, py::arg("image"), py::arg("timestamp_s") = py::none(),
           "The next frame of the stream. Without timestamp_s the tracker counts in frames.")
      .def_property("settings", &StreamEngine::settings, &StreamEngine::setSettings,
                    "A copy of the settings; set them to change them from the next frame on.")
      .def("reset_tracking", &StreamEngine::resetTracking, "Forgets the history: the next frame searches the whole image.")
      .def_property_readonly("frames", &StreamEngine::frames, "Frames processed so far.");

  m.def("render", &render, py::arg("pose"), py::arg("settings") = py::none(), py::arg("pattern") = false,
        py::arg("frame_seed") = 0,
        R"(The Virtual source's frame of the target at `pose` through the settings' virtual camera (lens
distortion included), as an HxW uint8 array; pattern=True draws the calibration pattern around it.
The settings' "virtual" section sets the look (grey or binary, blur, noise, clutter); frame_seed varies the noise.)");
  m.def(
      "target_in_view",
      [](const Pose& pose, const std::optional<Settings>& s) {
        const Settings& settings = settingsOr(s);
        return targetInView(settings.camera(SourceKind::Virtual), settings.target, pose);
      },
      py::arg("pose"), py::arg("settings") = py::none(),
      "Whether the whole target faces the virtual camera inside the image at `pose`.");
}

}  // namespace imagepro::python
