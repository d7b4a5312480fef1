#include "core/camera/camera_settings.h"

#include <gtest/gtest.h>

#include "fake_device.h"

namespace imagepro {
namespace {

using test::FakeControl;
using test::FakeDevice;

std::int64_t valueOf(const FakeDevice& device, std::uint32_t id) {
  for (const FakeControl& c : device.controls)
    if (c.query.id == id) return c.value;
  ADD_FAILURE() << "no control " << id;
  return -1;
}

class CameraSettingsFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    test::addStandardFormats(device);
    test::addStandardControls(device);
    // A focus distance that, as with UVC cameras, comes before its automatic mode and
    // can be set only once that is off; the exposure time likewise needs manual exposure.
    FakeControl focus;
    focus.query.id = V4L2_CID_FOCUS_ABSOLUTE;
    focus.query.type = V4L2_CTRL_TYPE_INTEGER;
    std::snprintf(reinterpret_cast<char*>(focus.query.name), sizeof focus.query.name, "Focus, Absolute");
    focus.query.minimum = 0;
    focus.query.maximum = 255;
    focus.query.step = 5;
    focus.query.flags = V4L2_CTRL_FLAG_INACTIVE;
    device.controls.insert(device.controls.end() - 1, focus);
    device.after_set = [this](std::uint32_t id, std::int64_t value) {
      const auto activate = [this](std::uint32_t dependent, bool active) {
        for (FakeControl& c : device.controls)
          if (c.query.id == dependent)
            c.query.flags = active ? (c.query.flags & ~V4L2_CTRL_FLAG_INACTIVE) : (c.query.flags | V4L2_CTRL_FLAG_INACTIVE);
      };
      if (id == V4L2_CID_FOCUS_AUTO) activate(V4L2_CID_FOCUS_ABSOLUTE, value == 0);
      if (id == V4L2_CID_EXPOSURE_AUTO) activate(V4L2_CID_EXPOSURE_ABSOLUTE, value == V4L2_EXPOSURE_MANUAL);
    };
  }
  CameraRequest request() const {
    CameraRequest r;
    r.device = device.path;
    r.width = 640;
    r.height = 480;
    r.timeout_ms = 500;
    return r;
  }
  FakeDevice device;
};

TEST(CameraRequest, FromTheSettings) {
  Settings s;
  CameraRequest r = cameraRequest(s);
  EXPECT_EQ(r.device, "/dev/video0");
  EXPECT_EQ(r.width, s.camera().width);  // the camera model's size by default
  EXPECT_EQ(r.height, s.camera().height);
  EXPECT_EQ(r.frame_rate_hz, 25.0);
  EXPECT_EQ(r.input, -1);  // a capture card's input and standard: the device's own
  EXPECT_EQ(r.standard, TvStandard::Keep);
  // The Camera source's camera model, whichever source is in use.
  s.camera(SourceKind::Camera).width = 800;
  s.camera(SourceKind::Camera).height = 600;
  s.camera(SourceKind::File).width = 320;
  s.source = SourceKind::File;
  s.camera_source.width = 1280;  // one side alone is no size
  EXPECT_EQ(cameraRequest(s).width, 800);
  EXPECT_EQ(cameraRequest(s).height, 600);
  s.camera_source.height = 720;
  s.camera_source.device = "/dev/video4";
  s.camera_source.frame_rate_hz = 60.0;
  s.camera_source.input = 1;
  s.camera_source.standard = TvStandard::Secam;
  r = cameraRequest(s);
  EXPECT_EQ(r.device, "/dev/video4");
  EXPECT_EQ(r.width, 1280);
  EXPECT_EQ(r.height, 720);
  EXPECT_EQ(r.frame_rate_hz, 60.0);
  EXPECT_EQ(r.input, 1);
  EXPECT_EQ(r.standard, TvStandard::Secam);
}

TEST_F(CameraSettingsFixture, StoredControlsAreSetDependentOnesAfterTheirMode) {
  CameraSource camera(request(), device);
  ASSERT_EQ(camera.start(), Status::Ok) << camera.lastError();
  const std::map<std::string, std::int64_t> stored{
      {"brightness", -20}, {"gain", 48}, {"auto_exposure", V4L2_EXPOSURE_MANUAL}, {"exposure_time_absolute", 500},
      {"focus_absolute", 120}, {"focus_automatic_continuous", 0}};
  std::vector<std::string> problems;
  applyStoredControls(camera, stored, problems);
  EXPECT_TRUE(problems.empty()) << problems.front();
  EXPECT_EQ(valueOf(device, V4L2_CID_BRIGHTNESS), -20);
  EXPECT_EQ(valueOf(device, V4L2_CID_GAIN), 48);
  EXPECT_EQ(valueOf(device, V4L2_CID_EXPOSURE_AUTO), V4L2_EXPOSURE_MANUAL);
  EXPECT_EQ(valueOf(device, V4L2_CID_EXPOSURE_ABSOLUTE), 500);
  EXPECT_EQ(valueOf(device, V4L2_CID_FOCUS_ABSOLUTE), 120);  // listed first, set on the second try
  EXPECT_EQ(valueOf(device, V4L2_CID_FOCUS_AUTO), 0);
  EXPECT_EQ(device.openDescriptors(), 1);  // through the streaming descriptor
  Frame frame;
  EXPECT_EQ(camera.next(frame), Status::Ok);  // streaming goes on
}

TEST_F(CameraSettingsFixture, MissingAndRefusedControlsAreReportedTheOthersSet) {
  CameraSource camera(request(), device);
  ASSERT_EQ(camera.start(), Status::Ok) << camera.lastError();
  std::vector<std::string> problems;
  applyStoredControls(camera, {{"zoom_absolute", 3}, {"brightness", 100}, {"gain", 64}, {"focus_absolute", 50}},
                      problems);
  ASSERT_EQ(problems.size(), 3u);
  std::string all;
  for (const std::string& p : problems) {
    EXPECT_NE(p.find(device.path), std::string::npos) << p;
    all += p + "\n";
  }
  EXPECT_NE(all.find("no control \"zoom_absolute\""), std::string::npos) << all;
  EXPECT_NE(all.find("-64..64"), std::string::npos) << all;       // out of range
  EXPECT_NE(all.find("focus_absolute"), std::string::npos) << all;  // inactive: automatic focus is on
  EXPECT_EQ(valueOf(device, V4L2_CID_GAIN), 64);
  EXPECT_EQ(valueOf(device, V4L2_CID_BRIGHTNESS), 0);
  Frame frame;
  EXPECT_EQ(camera.next(frame), Status::Ok);
}

TEST_F(CameraSettingsFixture, OneControlByKeyOrName) {
  CameraSource camera(request(), device);
  std::string error;
  EXPECT_EQ(setControlByKey(camera, "Gain", 80, error), Status::Ok) << error;  // not streaming: opened for it
  EXPECT_EQ(valueOf(device, V4L2_CID_GAIN), 80);
  EXPECT_EQ(device.openDescriptors(), 0);
  EXPECT_EQ(setControlByKey(camera, "gain", 81, error), Status::InvalidSettings);  // not a step of 16
  EXPECT_NE(error.find("gain"), std::string::npos) << error;
  EXPECT_EQ(setControlByKey(camera, "hue", 1, error), Status::InvalidSettings);
  EXPECT_NE(error.find(device.path + ": no control \"hue\""), std::string::npos) << error;
  device.vanish();
  EXPECT_EQ(setControlByKey(camera, "gain", 96, error), Status::CameraNotFound);
  EXPECT_NE(error.find(device.path), std::string::npos) << error;
}

}  // namespace
}  // namespace imagepro
