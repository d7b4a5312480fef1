#include "core/settings/settings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <typeindex>
#include <vector>

#include "core/common/atomic_file.h"
#include "core/settings/enum_names.h"
#include "support/file_size_limit.h"

namespace imagepro {
namespace {

std::string loadError(const std::string& json) {
  Settings s;
  std::string err;
  EXPECT_EQ(settingsFromJson(json, s, err), Status::InvalidSettings) << json;
  return err;
}

TEST(Settings, DefaultsRoundTrip) {
  Settings a;
  a.pipeline.threshold.method = ThresholdMethod::Manual;
  a.pipeline.threshold.manual_value = 77;
  a.camera().distortion = kThesisCameraDistortion;
  a.virtual_scene.initial_pose.rz_deg = 33;
  a.pipeline.tracking.mode = TrackingMode::Parameters3D;
  const std::string text = settingsToJson(a);
  Settings b;
  std::string err;
  ASSERT_EQ(settingsFromJson(text, b, err), Status::Ok) << err;
  EXPECT_EQ(settingsToJson(b), text);
  EXPECT_EQ(b.pipeline.threshold.manual_value, 77);
  EXPECT_DOUBLE_EQ(b.camera().distortion.k2, kThesisCameraDistortion.k2);
}

// Each source keeps its own camera model through a save and a load (thesis A.3).
TEST(Settings, ACameraPerSourceSurvivesSaveAndLoad) {
  Settings a;
  a.camera(SourceKind::File).distortion = kThesisCameraDistortion;
  a.camera(SourceKind::File).image_plane_distance_mm = 8.5;
  CameraModel& card = a.camera(SourceKind::Camera);
  card.width = 768;
  card.height = 576;
  card.principal_point_px = {383.5, 287.5};
  card.pixel_size_mm = {0.0086, 0.0083};
  card.image_plane_distance_mm = 12.0;
  card.distortion = {-1e-7, 0.0, 2e-6, -1e-6};
  a.source = SourceKind::Camera;
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(IMAGEPRO_TEST_TMP) / "settings_cameras";
  fs::create_directories(dir);
  const std::string path = (dir / "cameras.json").string();
  std::string err;
  ASSERT_EQ(saveSettings(path, a, err), Status::Ok) << err;
  Settings b;
  ASSERT_EQ(loadSettings(path, b, err), Status::Ok) << err;
  EXPECT_EQ(settingsToJson(b), settingsToJson(a));  // every key of every source's camera
  EXPECT_EQ(b.camera(SourceKind::File).distortion.k2, kThesisCameraDistortion.k2);
  EXPECT_EQ(b.camera(SourceKind::Camera).pixel_size_mm, card.pixel_size_mm);
  EXPECT_EQ(b.camera(SourceKind::Camera).distortion.p2, -1e-6);
  EXPECT_EQ(b.camera(SourceKind::Camera).width, 768);
  EXPECT_EQ(b.camera(SourceKind::Virtual).width, CameraModel{}.width);
  // The source in use is the running program's, not the file's.
  EXPECT_EQ(b.source, SourceKind::Virtual);
  EXPECT_EQ(settingsToJson(a).find("\n  \"source\":"), std::string::npos);  // no top-level key
  EXPECT_NE(findSettingKey("cameras.camera.distortion.p1"), nullptr);
  EXPECT_EQ(settingKeyOf(a, &a.camera(SourceKind::Camera).principal_point_px[1])->path,
            "cameras.camera.principal_point_px[1]");
}

// An older file has one "camera": every source takes it, and "cameras" beside it still
// gives a source its own.
TEST(Settings, AnOldFilesOneCameraServesEverySource) {
  Settings s;
  std::string err;
  ASSERT_EQ(settingsFromJson(R"({"camera": {"width": 768, "height": 576, "image_plane_distance_mm": 9.5,
                                            "distortion": {"k1": -2e-7}}})",
                             s, err),
            Status::Ok)
      << err;
  for (const SourceKind k : kSourceKinds) {
    EXPECT_EQ(s.camera(k).width, 768);
    EXPECT_EQ(s.camera(k).image_plane_distance_mm, 9.5);
    EXPECT_EQ(s.camera(k).distortion.k1, -2e-7);
    EXPECT_EQ(s.camera(k).principal_point_px, CameraModel{}.principal_point_px);  // not given: kept
  }
  // Written back the new way.
  const std::string text = settingsToJson(s);
  EXPECT_EQ(text.find("\n  \"camera\":"), std::string::npos);  // top level: "cameras" only
  EXPECT_NE(text.find("\n  \"cameras\":"), std::string::npos);
  Settings again;
  ASSERT_EQ(settingsFromJson(text, again, err), Status::Ok) << err;
  EXPECT_EQ(again.camera(SourceKind::File).width, 768);

  ASSERT_EQ(settingsFromJson(R"({"camera": {"image_plane_distance_mm": 9.5},
                                 "cameras": {"file": {"image_plane_distance_mm": 16.0}}})",
                             s, err),
            Status::Ok)
      << err;
  EXPECT_EQ(s.camera(SourceKind::File).image_plane_distance_mm, 16.0);
  EXPECT_EQ(s.camera(SourceKind::Camera).image_plane_distance_mm, 9.5);
  EXPECT_EQ(s.camera(SourceKind::Virtual).image_plane_distance_mm, 9.5);
  // Errors name the key as the file has it.
  EXPECT_NE(loadError(R"({"cameras": {"camera": {"width": 0}}})").find("cameras.camera.width: value 0 out of range"),
            std::string::npos);
  EXPECT_NE(loadError(R"({"cameras": {"tv": {}}})").find("cameras.tv: unknown key"), std::string::npos);
  EXPECT_NE(loadError(R"({"cameras": {"file": {"width": 16384, "height": 16384}}})")
                .find("cameras.file.width, cameras.file.height: "),
            std::string::npos);
}

TEST(Settings, ACaptureCardsInputAndStandard) {
  Settings a;
  a.camera_source.input = 2;
  a.camera_source.standard = TvStandard::Ntsc;
  Settings b;
  std::string err;
  ASSERT_EQ(settingsFromJson(settingsToJson(a), b, err), Status::Ok) << err;
  EXPECT_EQ(b.camera_source.input, 2);
  EXPECT_EQ(b.camera_source.standard, TvStandard::Ntsc);
  EXPECT_EQ(Settings{}.camera_source.input, -1);  // the device's own, untouched
  EXPECT_EQ(Settings{}.camera_source.standard, TvStandard::Keep);
  EXPECT_NE(loadError(R"({"camera_source": {"standard": "PAL-M"}})")
                .find("camera_source.standard: unknown value \"PAL-M\" (expected one of: keep, pal, ntsc, secam)"),
            std::string::npos);
  EXPECT_NE(loadError(R"({"camera_source": {"input": -2}})").find("camera_source.input: value -2 out of range"),
            std::string::npos);
}

// The constant-velocity motion's velocities and wrap-around box (thesis A.2) under virtual.motion.
TEST(Settings, ConstantVelocityMotionRoundTrip) {
  Settings a;
  a.virtual_scene.motion.kind = MotionKind::ConstantVelocity;
  a.virtual_scene.motion.velocity = Pose{1, -2, 3, 40, -50, 60};
  a.virtual_scene.motion.wrap_box = Pose{10, 20, 30, 400, 500, 0};
  const std::string text = settingsToJson(a);
  EXPECT_NE(text.find("\"constant-velocity\""), std::string::npos);
  EXPECT_NE(text.find("\"tx_mm_s\""), std::string::npos);
  Settings b;
  std::string err;
  ASSERT_EQ(settingsFromJson(text, b, err), Status::Ok) << err;
  EXPECT_EQ(settingsToJson(b), text);
  EXPECT_EQ(b.virtual_scene.motion.velocity.ty_mm, -50);
  EXPECT_EQ(b.virtual_scene.motion.wrap_box.rz_deg, 30);
  err = loadError(R"({"virtual": {"motion": {"wrap_box": {"tx_mm": -1}}}})");
  EXPECT_NE(err.find("virtual.motion.wrap_box.tx_mm: value -1 out of range"), std::string::npos) << err;
  err = loadError(R"({"virtual": {"motion": {"velocity": {"speed": 1}}}})");
  EXPECT_NE(err.find("virtual.motion.velocity.speed"), std::string::npos) << err;
}

TEST(Settings, CameraSourceRoundTrip) {
  Settings a;
  a.camera_source.device = "/dev/video2";
  a.camera_source.width = 1280;
  a.camera_source.height = 720;
  a.camera_source.frame_rate_hz = 30.0;
  a.camera_source.controls = {{"brightness", -12}, {"exposure_time_absolute", 250}, {"white_balance_automatic", 0}};
  const std::string text = settingsToJson(a);
  Settings b;
  std::string err;
  ASSERT_EQ(settingsFromJson(text, b, err), Status::Ok) << err;
  EXPECT_EQ(b.camera_source.device, "/dev/video2");
  EXPECT_EQ(b.camera_source.width, 1280);
  EXPECT_EQ(b.camera_source.height, 720);
  EXPECT_EQ(b.camera_source.frame_rate_hz, 30.0);
  EXPECT_EQ(b.camera_source.controls, a.camera_source.controls);
  EXPECT_EQ(settingsToJson(b), text);
  // A file's controls replace the defaults' (none) as a whole; a missing section keeps them.
  ASSERT_EQ(settingsFromJson(R"({"camera_source": {"controls": {"gain": 7}}})", b, err), Status::Ok) << err;
  EXPECT_EQ(b.camera_source.controls, (std::map<std::string, std::int64_t>{{"gain", 7}}));
  EXPECT_EQ(b.camera_source.device, "/dev/video2");
  // The defaults: the thesis's 25 frames/s at the camera model's size, no controls touched.
  const CameraSourceOptions defaults;
  EXPECT_EQ(defaults.width, 0);
  EXPECT_EQ(defaults.frame_rate_hz, 25.0);
  EXPECT_TRUE(defaults.controls.empty());
}

TEST(Settings, CameraSourceErrorsNameTheKey) {
  EXPECT_NE(loadError(R"({"camera_source": {"device": ""}})").find("camera_source.device: expected a non-empty string"),
            std::string::npos);
  EXPECT_NE(loadError(R"({"camera_source": {"device": 0}})").find("camera_source.device"), std::string::npos);
  EXPECT_NE(loadError(R"({"camera_source": {"width": -1}})").find("camera_source.width"), std::string::npos);
  EXPECT_NE(loadError(R"({"camera_source": {"frame_rate_hz": -5}})").find("camera_source.frame_rate_hz"),
            std::string::npos);
  EXPECT_NE(loadError(R"({"camera_source": {"controls": {"gain": 1.5}}})")
                .find("camera_source.controls.gain: expected a whole number"),
            std::string::npos);
  EXPECT_NE(loadError(R"({"camera_source": {"controls": {"Gain": 1}}})").find("camera_source.controls.Gain"),
            std::string::npos);
  EXPECT_NE(loadError(R"({"camera_source": {"controls": [1]}})").find("camera_source.controls: expected an object"),
            std::string::npos);
  EXPECT_NE(loadError(R"({"camera_source": {"fps": 30}})").find("camera_source.fps: unknown key"), std::string::npos);
}

TEST(Settings, StreamRoundTrip) {
  // Off by default; switched on it sends to 127.0.0.1:5005 as JSON.
  const StreamOptions defaults;
  EXPECT_FALSE(defaults.enabled);
  EXPECT_EQ(defaults.host, "127.0.0.1");
  EXPECT_EQ(defaults.port, 5005);
  EXPECT_EQ(defaults.format, StreamFormat::Json);
  Settings a;
  a.stream = {true, "::1", 4242, StreamFormat::OpenTrack};
  const std::string text = settingsToJson(a);
  Settings b;
  std::string err;
  ASSERT_EQ(settingsFromJson(text, b, err), Status::Ok) << err;
  EXPECT_EQ(b.stream, a.stream);
  EXPECT_EQ(settingsToJson(b), text);
  ASSERT_EQ(settingsFromJson(R"({"stream": {"enabled": true}})", b = Settings{}, err), Status::Ok) << err;
  EXPECT_EQ(b.stream.host, "127.0.0.1");
  EXPECT_EQ(b.stream.port, 5005);
}

// None is the re-threshold's by-pass: the frame's threshold refuses it by its key, and
// the values the error offers are those that key takes.
TEST(Settings, FrameThresholdIsNeverNone) {
  const std::string none = loadError(R"({"pipeline": {"threshold": {"method": "none"}}})");
  EXPECT_NE(none.find("pipeline.threshold.method: \"none\" is not allowed here (expected one of: manual, at-orig, at-mod)"),
            std::string::npos)
      << none;
  const std::string unknown = loadError(R"({"pipeline": {"threshold": {"method": "otsu"}}})");
  EXPECT_NE(unknown.find("pipeline.threshold.method: unknown value \"otsu\" (expected one of: manual, at-orig, at-mod)"),
            std::string::npos)
      << unknown;
  EXPECT_NE(loadError(R"({"pipeline": {"threshold": {"method": 3}}})")
                .find("pipeline.threshold.method: expected a string, one of: manual, at-orig, at-mod"),
            std::string::npos);
  EXPECT_NE(loadError(R"({"pipeline": {"rethreshold": {"method": "otsu"}}})")
                .find("(expected one of: none, manual, at-orig, at-mod)"),
            std::string::npos);
  Settings s;
  std::string err;
  ASSERT_EQ(settingsFromJson(R"({"pipeline": {"rethreshold": {"method": "none"}}})", s, err), Status::Ok) << err;
  EXPECT_EQ(s.pipeline.rethreshold.method, ThresholdMethod::None);
  // The settings table says the same to the GUI's lists and the Python module.
  const SettingKey* frame = findSettingKey("pipeline.threshold.method");
  ASSERT_NE(frame, nullptr);
  ASSERT_EQ(frame->choices.size(), 3u);
  EXPECT_EQ(frame->choices[0].key, "manual");
  EXPECT_EQ(frame->choices[2].key, "at-mod");
}

TEST(Settings, StreamErrorsNameTheKey) {
  EXPECT_NE(loadError(R"({"stream": {"port": 0}})").find("stream.port: value 0 out of range [1, 65535]"),
            std::string::npos);
  EXPECT_NE(loadError(R"({"stream": {"port": 65536}})").find("stream.port"), std::string::npos);
  EXPECT_NE(loadError(R"({"stream": {"host": ""}})").find("stream.host: expected a non-empty string"),
            std::string::npos);
  EXPECT_NE(loadError(R"({"stream": {"format": "xml"}})").find("stream.format: unknown value \"xml\" (expected one of: json, opentrack)"),
            std::string::npos);
  EXPECT_NE(loadError(R"({"stream": {"enabled": 1}})").find("stream.enabled: expected true or false"),
            std::string::npos);
  EXPECT_NE(loadError(R"({"stream": {"url": "udp://a:1"}})").find("stream.url: unknown key"), std::string::npos);
  const SettingKey* port = findSettingKey("stream.port");
  ASSERT_NE(port, nullptr);
  EXPECT_EQ(port->type, SettingKey::Type::WholeNumber);
  EXPECT_EQ(port->lo, 1);
  EXPECT_EQ(port->hi, 65535);
  ASSERT_NE(findSettingKey("stream.format"), nullptr);
  EXPECT_EQ(findSettingKey("stream.format")->choices.size(), 2u);
}

TEST(Settings, ArchitectureExampleLoads) {
  const char* text = R"({
    "camera": {"width": 640, "height": 480, "pixel_size_mm": [0.01, 0.01],
               "image_plane_distance_mm": 8.0, "principal_point_px": [319.5, 239.5],
               "distortion": {"k1": 0.0, "k2": 0.0, "p1": 0.0, "p2": 0.0}},
    "target": {"radius_mm": 50.0, "spot_radius_mm": 6.0, "spot_offset_mm": 25.0},
    "pattern": {"spot_spacing_mm": 25.0, "spot_radius_mm": 4.0, "columns": 61, "rows": 49, "card_size_mm": 130.0}
  })";
  Settings s;
  std::string err;
  ASSERT_EQ(settingsFromJson(text, s, err), Status::Ok) << err;
  EXPECT_EQ(s.pattern.columns, 61);
}

// A renamed key is read under its old name with a warning naming both, written under the
// new one; both names at once are refused, and the file's other keys still load.
TEST(Settings, ARenamedKeyIsReadUnderItsOldNameWithAWarning) {
  Settings s;
  std::string err;
  std::vector<std::string> warnings;
  ASSERT_EQ(settingsFromJson(R"({"pipeline": {"reconstruction": {"ambiguity_min_deg": 2.5, "ambiguity_ratio": 1.7}}})",
                             s, err, &warnings),
            Status::Ok)
      << err;
  EXPECT_DOUBLE_EQ(s.pipeline.reconstruction.ambiguity_tolerance_deg, 2.5);
  EXPECT_DOUBLE_EQ(s.pipeline.reconstruction.ambiguity_ratio, 1.7);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("pipeline.reconstruction.ambiguity_min_deg"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("pipeline.reconstruction.ambiguity_tolerance_deg"), std::string::npos) << warnings[0];
  const std::string saved = settingsToJson(s);
  EXPECT_EQ(saved.find("ambiguity_min_deg"), std::string::npos);
  EXPECT_NE(saved.find("\"ambiguity_tolerance_deg\": 2.5"), std::string::npos);

  // Its range is the new key's.
  EXPECT_NE(loadError(R"({"pipeline": {"reconstruction": {"ambiguity_min_deg": 500}}})")
                .find("pipeline.reconstruction.ambiguity_tolerance_deg"),
            std::string::npos);
  const std::string both =
      loadError(R"({"pipeline": {"reconstruction": {"ambiguity_min_deg": 1, "ambiguity_tolerance_deg": 2}}})");
  EXPECT_NE(both.find("ambiguity_min_deg"), std::string::npos) << both;
  EXPECT_NE(both.find("ambiguity_tolerance_deg"), std::string::npos) << both;

  // Without the old name, no warning.
  warnings.clear();
  ASSERT_EQ(settingsFromJson(saved, s, err, &warnings), Status::Ok) << err;
  EXPECT_TRUE(warnings.empty());
}

TEST(Settings, MissingKeysKeepDefaults) {
  Settings s;
  std::string err;
  ASSERT_EQ(settingsFromJson(R"({"target": {"radius_mm": 40}})", s, err), Status::Ok);
  EXPECT_DOUBLE_EQ(s.target.radius_mm, 40.0);
  EXPECT_DOUBLE_EQ(s.target.spot_offset_mm, TargetGeometry{}.spot_offset_mm);
  EXPECT_EQ(s.camera().width, 640);
}

TEST(Settings, ErrorsNameTheKey) {
  EXPECT_NE(loadError(R"({"camera": {"widht": 640}})").find("camera.widht: unknown key"), std::string::npos);
  EXPECT_NE(loadError(R"({"colour": 1})").find("colour: unknown key"), std::string::npos);
  EXPECT_NE(loadError(R"({"camera": {"width": "wide"}})").find("camera.width"), std::string::npos);
  EXPECT_NE(loadError(R"({"camera": {"width": 6.5}})").find("whole number"), std::string::npos);
  EXPECT_NE(loadError(R"({"camera": {"pixel_size_mm": [0.01]}})").find("camera.pixel_size_mm"), std::string::npos);
  EXPECT_NE(loadError(R"({"pipeline": {"threshold": {"method": "otsu"}}})").find("at-orig"), std::string::npos);
  EXPECT_NE(loadError(R"({"pipeline": {"threshold": {"value": 300}}})").find("pipeline.threshold.value"), std::string::npos);
  EXPECT_NE(loadError(R"({"target": 5})").find("target: expected an object"), std::string::npos);
  EXPECT_NE(loadError(R"({"camera": {"width": 640,)").find("not valid JSON"), std::string::npos);
  EXPECT_NE(loadError("[1,2]").find("JSON object"), std::string::npos);
  EXPECT_NE(loadError(R"({"pipeline": {"reconstruction": {"distortion_correction": 1}}})").find("true or false"), std::string::npos);
}

// A number JSON cannot hold (beyond a double) is the key's error, not an abort.
TEST(Settings, NumberBeyondADoubleNamesTheKey) {
  std::string err = loadError(R"({"camera": {"image_plane_distance_mm": 1e400}})");
  EXPECT_EQ(err.rfind("camera.image_plane_distance_mm: ", 0), 0u) << err;
  EXPECT_NE(err.find("1e400"), std::string::npos) << err;
  err = loadError(R"({"camera": {"principal_point_px": [1, -1e999]}})");
  EXPECT_EQ(err.rfind("camera.principal_point_px[1]: ", 0), 0u) << err;
  err = loadError(R"({"pipeline": {"tracking": {"min_r": 0.5, "degree": 1E+400}}})");
  EXPECT_EQ(err.rfind("pipeline.tracking.degree: ", 0), 0u) << err;
  // Through the file loader too, with the file's name first.
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(IMAGEPRO_TEST_TMP) / "settings_overflow";
  fs::create_directories(dir);
  const std::string path = (dir / "huge.json").string();
  ASSERT_TRUE(writeFileAtomically(path, "{\n  \"camera\": {\"image_plane_distance_mm\": 1e400}\n}\n", err)) << err;
  Settings s;
  s.camera().image_plane_distance_mm = 12.0;
  EXPECT_EQ(loadSettings(path, s, err), Status::InvalidSettings);
  EXPECT_EQ(err.rfind(path + ": camera.image_plane_distance_mm: ", 0), 0u) << err;
  EXPECT_DOUBLE_EQ(s.camera().image_plane_distance_mm, 12.0);
}

// A syntax error says where the document broke, by key as well as line and column.
TEST(Settings, SyntaxErrorNamesWhereItBroke) {
  const std::string err = loadError("{\"target\": {\"radius_mm\": 10,, }}");
  EXPECT_EQ(err.rfind("not valid JSON at target.radius_mm: ", 0), 0u) << err;
  EXPECT_NE(err.find("line 1"), std::string::npos) << err;
  EXPECT_EQ(err.find("[json.exception"), std::string::npos) << err;
  EXPECT_EQ(loadError("").rfind("not valid JSON: ", 0), 0u);
}

// A whole number beyond what the key takes is reported as written, not wrapped round.
TEST(Settings, HugeWholeNumbersAreReportedAsGiven) {
  std::string err = loadError(R"({"camera": {"width": 18446744073709551615}})");
  EXPECT_NE(err.find("camera.width: value 18446744073709551615 out of range"), std::string::npos) << err;
  err = loadError(R"({"camera_source": {"controls": {"gain": 9223372036854775808}}})");
  EXPECT_NE(err.find("camera_source.controls.gain: value 9223372036854775808 out of range"), std::string::npos) << err;
  err = loadError(R"({"virtual": {"seed": 4294967296}})");
  EXPECT_NE(err.find("virtual.seed: value 4294967296 out of range"), std::string::npos) << err;
}

// The camera's image is bounded by what a V4L2 camera delivers and a frame's buffers
// hold: each side by its key, and the two together.
TEST(Settings, ImageSizeIsBounded) {
  std::string err = loadError(R"({"camera": {"width": 100000, "height": 100000}})");
  EXPECT_NE(err.find("camera.width: value 100000 out of range [1, 16384]"), std::string::npos) << err;
  err = loadError(R"({"camera_source": {"height": 20000}})");
  EXPECT_NE(err.find("camera_source.height: value 20000 out of range [0, 16384]"), std::string::npos) << err;
  err = loadError(R"({"camera": {"width": 16384, "height": 16384}})");
  EXPECT_EQ(err.rfind("camera.width, camera.height: 16384x16384 is 256 megapixels", 0), 0u) << err;
  Settings s;
  ASSERT_EQ(settingsFromJson(R"({"camera": {"width": 8192, "height": 8192}})", s, err), Status::Ok) << err;
  EXPECT_EQ(s.camera().width, 8192);
}

TEST(Settings, FailedLoadLeavesSettingsUntouched) {
  Settings s;
  s.target.radius_mm = 42;
  std::string err;
  EXPECT_EQ(settingsFromJson(R"({"target": {"radius_mm": 10, "bogus": 1}})", s, err), Status::InvalidSettings);
  EXPECT_DOUBLE_EQ(s.target.radius_mm, 42.0);
}

TEST(Settings, SaveAndLoadFile) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(IMAGEPRO_TEST_TMP) / "settings";
  fs::create_directories(dir);
  const std::string path = (dir / "s.json").string();
  Settings a;
  a.pattern.rows = 7;
  std::string err;
  ASSERT_EQ(saveSettings(path, a, err), Status::Ok) << err;
  Settings b;
  ASSERT_EQ(loadSettings(path, b, err), Status::Ok) << err;
  EXPECT_EQ(b.pattern.rows, 7);
  // A malformed file is reported with its path and key.
  ASSERT_TRUE(writeFileAtomically(path, R"({"pattern": {"rows": -1}})", err));
  EXPECT_EQ(loadSettings(path, b, err), Status::InvalidSettings);
  EXPECT_NE(err.find("s.json"), std::string::npos);
  EXPECT_NE(err.find("pattern.rows"), std::string::npos);
  EXPECT_EQ(loadSettings((dir / "none.json").string(), b, err), Status::FileNotFound);
}

// A save that fails half-way (the disk full) reports the file and leaves the settings
// saved before exactly as they were.
TEST(Settings, FailedSaveKeepsThePreviousFile) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(IMAGEPRO_TEST_TMP) / "settings_full";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "s.json").string();
  Settings before;
  before.pattern.rows = 9;
  std::string err, saved;
  ASSERT_EQ(saveSettings(path, before, err), Status::Ok) << err;
  ASSERT_TRUE(readWholeFile(path, saved, err)) << err;
  Settings after;
  after.pattern.rows = 11;
  {
    test::FileSizeLimit limit(saved.size() / 2);
    ASSERT_TRUE(limit.active());
    EXPECT_NE(saveSettings(path, after, err), Status::Ok);
  }
  EXPECT_NE(err.find("s.json"), std::string::npos) << err;
  std::string now;
  ASSERT_TRUE(readWholeFile(path, now, err)) << err;
  EXPECT_EQ(now, saved);
  Settings loaded;
  ASSERT_EQ(loadSettings(path, loaded, err), Status::Ok) << err;
  EXPECT_EQ(loaded.pattern.rows, 9);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);  // no temporary left
}

TEST(Settings, ShippedDefaultFileMatchesDefaults) {
  Settings shipped;
  std::string err;
  ASSERT_EQ(loadSettings(std::string(IMAGEPRO_DATA_DIR) + "/settings.json", shipped, err), Status::Ok) << err;
  EXPECT_EQ(settingsToJson(shipped), settingsToJson(Settings{}));
}

TEST(EnumNames, EveryNameParsesBack) {
  for (const auto& e : enumEntries(ContourMode{})) EXPECT_EQ(parseEnum<ContourMode>(e.key), e.value);
  EXPECT_EQ(enumName(ThresholdMethod::AtOrig), "at-orig");
  EXPECT_FALSE(parseEnum<EdgeMethod>("canny").has_value());
}

TEST(EnumNames, EveryValueHasAKeyANameAndADescription) {
  const auto check = [](auto e) {
    using E = decltype(e);
    for (const auto& entry : enumEntries(E{})) {
      EXPECT_FALSE(entry.key.empty());
      EXPECT_FALSE(entry.label.empty()) << entry.key;
      EXPECT_FALSE(entry.description.empty()) << entry.key;
      EXPECT_EQ(entry.description.find('\n'), std::string_view::npos) << entry.key;
      EXPECT_EQ(enumLabel(entry.value), entry.label);
    }
  };
  check(ThresholdMethod{}), check(Binarization{}), check(EdgeMethod{}), check(ConnectivityMethod{});
  check(EllipseMethod{}), check(FitAcceptRule{}), check(ContourMode{}), check(TrackingMode{});
  check(ApplicationLevel{}), check(DisplayOptions::Background{}), check(DisplayOptions::Edges{});
  check(DisplayOptions::Target{}), check(RenderMode{}), check(MotionKind{}), check(PoseAxis{});
  check(StreamFormat{});
  // The thesis's names (appendix A), not the file's keys.
  EXPECT_EQ(enumLabel(ThresholdMethod::AtMod), "AT-Mod");
  EXPECT_EQ(enumLabel(ConnectivityMethod::CN1), "CN1");
  EXPECT_EQ(enumLabel(ContourMode::EightPointsOrg), "8 points ORG");
  EXPECT_EQ(enumLabel(TrackingMode::Corners2D), "2D Corners");
  EXPECT_EQ(enumLabel(static_cast<EdgeMethod>(99)), "?");
}

// {"a": {"b": value}} for the path "a.b".
std::string documentWith(const std::string& path, const std::string& value) {
  std::string open, close;
  std::size_t start = 0;
  for (;;) {
    const std::size_t dot = path.find('.', start);
    const std::string key = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    open += "{\"" + key + "\": ";
    close += "}";
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return open + value + close;
}

std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

TEST(SettingKeys, TheTableGivesEveryKeyItsRange) {
  const SettingKey* trace = findSettingKey("pipeline.ellipse.trace_inlier_px");
  ASSERT_NE(trace, nullptr);
  EXPECT_EQ(trace->type, SettingKey::Type::Number);
  EXPECT_EQ(trace->lo, 0.0);
  EXPECT_EQ(trace->hi, std::numeric_limits<double>::infinity());
  const SettingKey* value = findSettingKey("pipeline.threshold.value");
  ASSERT_NE(value, nullptr);
  EXPECT_EQ(value->type, SettingKey::Type::WholeNumber);
  EXPECT_EQ(value->lo, 0.0);
  EXPECT_EQ(value->hi, 255.0);
  EXPECT_EQ(findSettingKey("pipeline.ellipse"), nullptr);
  EXPECT_EQ(findSettingKey("pipeline.ellipse.no_such_key"), nullptr);

  const SettingKey* method = findSettingKey("pipeline.rethreshold.method");
  ASSERT_NE(method, nullptr);
  EXPECT_EQ(method->type, SettingKey::Type::Choice);
  EXPECT_EQ(method->choice, std::type_index(typeid(ThresholdMethod)));
  ASSERT_EQ(method->choices.size(), enumEntries(ThresholdMethod{}).size());
  EXPECT_EQ(method->choices[3].label, "AT-Mod");

  // Every number key accepts both ends of its range and refuses what lies beyond them.
  for (const SettingKey& k : settingKeys()) {
    if (k.type != SettingKey::Type::Number && k.type != SettingKey::Type::WholeNumber) continue;
    if (k.path.find('[') != std::string::npos) continue;  // array elements: written whole
    // A target's id must also name a target of the file (TargetSet.FramesOfReferenceNameTargetsOfTheFile).
    if (k.path == "frames.reference_target" || k.path == "frames.shown_target") continue;
    const double step = k.type == SettingKey::Type::WholeNumber ? 1.0 : 1e-3 * std::max(1.0, std::abs(k.lo));
    const double hi_step = k.type == SettingKey::Type::WholeNumber ? 1.0 : 1e-3 * std::max(1.0, std::abs(k.hi));
    const auto loads = [&k](double v) {
      Settings s;
      std::string err;
      return settingsFromJson(documentWith(k.path, number(v)), s, err);
    };
    for (const double v : {k.lo, k.hi}) {
      if (std::isfinite(v)) {
        EXPECT_EQ(loads(v), Status::Ok) << k.path << " at " << v;
      }
    }
    if (std::isfinite(k.lo)) {
      EXPECT_EQ(loads(k.lo - step), Status::InvalidSettings) << k.path;
    }
    if (std::isfinite(k.hi)) {
      EXPECT_EQ(loads(k.hi + hi_step), Status::InvalidSettings) << k.path;
    }
  }
}

TEST(SettingKeys, AFieldsAddressNamesItsKey) {
  Settings s;
  const SettingKey* trace = settingKeyOf(s, &s.pipeline.ellipse.trace_inlier_px);
  ASSERT_NE(trace, nullptr);
  EXPECT_EQ(trace->path, "pipeline.ellipse.trace_inlier_px");
  const SettingKey* v0 = settingKeyOf(s, &s.camera().principal_point_px[1]);
  ASSERT_NE(v0, nullptr);
  EXPECT_EQ(v0->path, "cameras.virtual.principal_point_px[1]");  // the source in use's: Virtual by default
  EXPECT_EQ(settingKeyOf(s, &s.pipeline.tracking.mode)->path, "pipeline.tracking.mode");
  // A value outside this Settings object, even the same field of another, has no key.
  Settings other;
  EXPECT_EQ(settingKeyOf(s, &other.pipeline.ellipse.trace_inlier_px), nullptr);
}

}  // namespace
}  // namespace imagepro
