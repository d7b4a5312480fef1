#include "core/camera/camera_info.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "fake_device.h"

namespace imagepro {
namespace {

using test::FakeDevice;

const std::uint32_t kYuyv = makeFourcc('Y', 'U', 'Y', 'V');
const std::uint32_t kMjpg = makeFourcc('M', 'J', 'P', 'G');
const std::uint32_t kGrey = makeFourcc('G', 'R', 'E', 'Y');
const std::uint32_t kNv12 = makeFourcc('N', 'V', '1', '2');
const std::uint32_t kBayer = makeFourcc('B', 'A', '8', '1');

FrameSize size(int w, int h, std::vector<FrameInterval> intervals) {
  FrameSize s;
  s.width = s.min_width = w;
  s.height = s.min_height = h;
  s.rates.discrete = std::move(intervals);
  return s;
}

FormatInfo format(std::uint32_t fourcc, std::vector<FrameSize> sizes, bool emulated = false) {
  FormatInfo f;
  f.fourcc = fourcc;
  f.format = pixelFormatFromFourcc(fourcc);
  f.sizes = std::move(sizes);
  f.emulated = emulated;
  return f;
}

// A typical USB camera: YUYV is slow at the large size, MJPG fast everywhere.
std::vector<FormatInfo> usbCamera() {
  return {format(kYuyv, {size(640, 480, {{1, 30}, {1, 25}, {1, 15}}), size(1280, 720, {{1, 10}, {1, 5}})}),
          format(kMjpg, {size(640, 480, {{1, 30}}), size(1280, 720, {{1, 30}, {1, 25}}), size(1920, 1080, {{1, 30}})})};
}

TEST(ChooseCapture, ExactSizeAndRateWithTheCheapestFormat) {
  CaptureChoice c;
  std::string error;
  ASSERT_EQ(chooseCapture(usbCamera(), 640, 480, 25.0, c, error), Status::Ok) << error;
  EXPECT_EQ(c.fourcc, kYuyv);  // both reach 25 Hz at 640x480; copying luma beats decoding JPEG
  EXPECT_EQ(c.format, PixelFormat::Yuyv);
  EXPECT_EQ(c.width, 640);
  EXPECT_EQ(c.height, 480);
  EXPECT_EQ(c.interval, (FrameInterval{1, 25}));
}

TEST(ChooseCapture, TheRateDecidesBetweenFormatsOfTheSameSize) {
  CaptureChoice c;
  std::string error;
  ASSERT_EQ(chooseCapture(usbCamera(), 1280, 720, 25.0, c, error), Status::Ok);
  EXPECT_EQ(c.fourcc, kMjpg);  // YUYV reaches only 10 Hz at this size
  EXPECT_EQ(c.interval, (FrameInterval{1, 25}));
  ASSERT_EQ(chooseCapture(usbCamera(), 1280, 720, 8.0, c, error), Status::Ok);
  EXPECT_EQ(c.fourcc, kYuyv);  // 8 Hz: both reach it, YUYV is cheaper
  EXPECT_EQ(c.interval, (FrameInterval{1, 10}));  // the nearest listed rate
}

TEST(ChooseCapture, TheNearestSizeWinsOverTheRate) {
  CaptureChoice c;
  std::string error;
  ASSERT_EQ(chooseCapture(usbCamera(), 1900, 1000, 60.0, c, error), Status::Ok);
  EXPECT_EQ(c.width, 1920);
  EXPECT_EQ(c.height, 1080);
  EXPECT_EQ(c.interval, (FrameInterval{1, 30}));  // the fastest there is
}

TEST(ChooseCapture, NoSizeAskedTakesTheLargestThatReachesTheRate) {
  const std::vector<FormatInfo> formats{
      format(kYuyv, {size(640, 480, {{1, 30}}), size(2592, 1944, {{1, 5}})}),
  };
  CaptureChoice c;
  std::string error;
  ASSERT_EQ(chooseCapture(formats, 0, 0, 25.0, c, error), Status::Ok);
  EXPECT_EQ(c.width, 640);
  ASSERT_EQ(chooseCapture(formats, 0, 0, 5.0, c, error), Status::Ok);
  EXPECT_EQ(c.width, 2592);
  EXPECT_EQ(c.interval, (FrameInterval{1, 5}));
}

TEST(ChooseCapture, PlanarLumaBeatsPackedAndLibraryConversionsComeLast) {
  std::vector<FormatInfo> formats{format(kYuyv, {size(640, 480, {{1, 25}})}),
                                  format(kNv12, {size(640, 480, {{1, 25}})}, true),
                                  format(kGrey, {size(640, 480, {{1, 25}})})};
  CaptureChoice c;
  std::string error;
  ASSERT_EQ(chooseCapture(formats, 640, 480, 25.0, c, error), Status::Ok);
  EXPECT_EQ(c.fourcc, kGrey);
  formats.pop_back();
  ASSERT_EQ(chooseCapture(formats, 640, 480, 25.0, c, error), Status::Ok);
  EXPECT_EQ(c.fourcc, kYuyv);  // the native format, not libv4l2's converted NV12
}

TEST(ChooseCapture, RangesAreSnappedToTheirSteps) {
  FormatInfo f = format(kGrey, {});
  FrameSize range;
  range.is_range = true;
  range.min_width = 16;
  range.min_height = 16;
  range.width = 1024;
  range.height = 768;
  range.step_width = 16;
  range.step_height = 8;
  range.rates.is_range = true;
  range.rates.shortest = {1, 60};
  range.rates.longest = {1, 1};
  f.sizes = {range};
  CaptureChoice c;
  std::string error;
  ASSERT_EQ(chooseCapture({f}, 650, 483, 25.0, c, error), Status::Ok);
  EXPECT_EQ(c.width, 656);  // 16 + 40 * 16
  EXPECT_EQ(c.height, 480);
  EXPECT_EQ(c.interval, (FrameInterval{1, 25}));
  ASSERT_EQ(chooseCapture({f}, 4000, 4000, 100.0, c, error), Status::Ok);
  EXPECT_EQ(c.width, 1024);
  EXPECT_EQ(c.height, 768);
  EXPECT_EQ(c.interval, (FrameInterval{1, 60}));  // clamped to the fastest
  ASSERT_EQ(chooseCapture({f}, 640, 480, 0.0, c, error), Status::Ok);
  EXPECT_EQ(c.interval, FrameInterval{});  // rate left to the driver
}

TEST(ChooseCapture, UnlistedSizesAreAskedForAsRequested) {
  CaptureChoice c;
  std::string error;
  ASSERT_EQ(chooseCapture({format(kGrey, {})}, 720, 576, 25.0, c, error), Status::Ok);
  EXPECT_EQ(c.width, 720);
  EXPECT_EQ(c.height, 576);
  EXPECT_EQ(c.interval, (FrameInterval{1, 25}));
}

TEST(ChooseCapture, NoReadableFormatIsNamed) {
  CaptureChoice c;
  std::string error;
  EXPECT_EQ(chooseCapture({format(kBayer, {size(640, 480, {{1, 30}})}), format(makeFourcc('H', '2', '6', '4'), {})},
                          640, 480, 25.0, c, error),
            Status::CameraNoSupportedFormat);
  EXPECT_NE(error.find("BA81"), std::string::npos) << error;
  EXPECT_NE(error.find("H264"), std::string::npos) << error;
  EXPECT_EQ(chooseCapture({}, 640, 480, 25.0, c, error), Status::CameraNoSupportedFormat);
}

TEST(Controls, KeysAndValueChecks) {
  EXPECT_EQ(controlKey("Exposure Time, Absolute"), "exposure_time_absolute");
  EXPECT_EQ(controlKey("  White Balance (Auto) "), "white_balance_auto");
  EXPECT_EQ(controlKey("Gain"), "gain");
  CameraControl c;
  c.type = ControlType::Integer;
  c.minimum = -10;
  c.maximum = 20;
  c.step = 5;
  EXPECT_EQ(controlValueProblem(c, -10), "");
  EXPECT_EQ(controlValueProblem(c, 15), "");
  EXPECT_NE(controlValueProblem(c, 12), "");  // off the steps
  EXPECT_NE(controlValueProblem(c, 25), "");
  c.read_only = true;
  EXPECT_EQ(controlValueProblem(c, 15), "read-only");
  CameraControl menu;
  menu.type = ControlType::Menu;
  menu.menu = {{1, "Manual Mode"}, {3, "Aperture Priority Mode"}};
  EXPECT_EQ(controlValueProblem(menu, 3), "");
  EXPECT_NE(controlValueProblem(menu, 2).find("1 (Manual Mode)"), std::string::npos);
  CameraControl boolean;
  boolean.type = ControlType::Boolean;
  EXPECT_EQ(controlValueProblem(boolean, 1), "");
  EXPECT_NE(controlValueProblem(boolean, 2), "");
}

TEST(QueryDevice, ListsFormatsSizesRatesAndControls) {
  FakeDevice device;
  test::addStandardFormats(device);
  test::addStandardControls(device);
  device.formats.push_back({kBayer, "8-bit Bayer BGBG/GRGR", {{640, 480, {{1, 30}}}}, false});
  device.formats.push_back({kNv12, "NV12 (converted)", {{640, 480, {{1, 25}}}}, true});
  DeviceInfo info;
  std::string error;
  ASSERT_EQ(queryDevice(device, device.path, info, error), Status::Ok) << error;
  EXPECT_EQ(device.openDescriptors(), 0);  // closed again
  EXPECT_EQ(info.card, "Fake Camera");
  EXPECT_EQ(info.driver, "fakecam");
  EXPECT_TRUE(info.video_capture);
  EXPECT_TRUE(info.streaming);
  ASSERT_EQ(info.formats.size(), 4u);
  const FormatInfo& yuyv = info.formats[0];
  EXPECT_EQ(yuyv.fourcc, kYuyv);
  EXPECT_EQ(yuyv.description, "YUYV 4:2:2");
  EXPECT_EQ(yuyv.format, PixelFormat::Yuyv);
  ASSERT_EQ(yuyv.sizes.size(), 2u);
  EXPECT_EQ(yuyv.sizes[0].width, 640);
  EXPECT_EQ(yuyv.sizes[0].height, 480);
  ASSERT_EQ(yuyv.sizes[0].rates.discrete.size(), 3u);
  EXPECT_DOUBLE_EQ(yuyv.sizes[0].rates.discrete[1].rateHz(), 25.0);
  EXPECT_EQ(yuyv.sizes[1].width, 320);
  EXPECT_FALSE(info.formats[1].emulated);
  EXPECT_FALSE(info.formats[2].format.has_value());  // Bayer is listed, but not readable
  EXPECT_TRUE(info.formats[3].emulated);

  // The control-class heading and the disabled contrast are left out.
  ASSERT_EQ(info.controls.size(), 5u);
  EXPECT_EQ(info.controls[0].key, "brightness");
  EXPECT_EQ(info.controls[0].minimum, -64);
  EXPECT_EQ(info.controls[0].maximum, 64);
  EXPECT_EQ(info.controls[1].key, "gain");
  EXPECT_EQ(info.controls[1].value, 32);
  const CameraControl& mode = info.controls[2];
  EXPECT_EQ(mode.key, "auto_exposure");
  EXPECT_EQ(mode.type, ControlType::Menu);
  ASSERT_EQ(mode.menu.size(), 2u);  // index 0 and 2 are gaps
  EXPECT_EQ(mode.menu[0].value, 1);
  EXPECT_EQ(mode.menu[0].name, "Manual Mode");
  EXPECT_EQ(mode.menu[1].value, 3);
  EXPECT_EQ(info.controls[3].key, "exposure_time_absolute");
  EXPECT_TRUE(info.controls[3].inactive);
  EXPECT_EQ(info.controls[4].type, ControlType::Boolean);
}

TEST(QueryDevice, ACaptureCardsInputsAndStandards) {
  FakeDevice device;
  test::addCaptureCard(device);
  DeviceInfo info;
  std::string error;
  ASSERT_EQ(queryDevice(device, device.path, info, error), Status::Ok) << error;
  ASSERT_EQ(info.inputs.size(), 3u);
  EXPECT_EQ(info.inputs[0].name, "Composite0");
  EXPECT_EQ(info.inputs[2].index, 2u);
  EXPECT_EQ(info.inputs[2].name, "S-Video");
  EXPECT_EQ(info.inputs[2].standards, V4L2_STD_NTSC);
  EXPECT_EQ(info.current_input, 0);
  // The standards of the current input, as the driver lists them.
  ASSERT_EQ(info.standards.size(), 3u);
  EXPECT_EQ(info.standards[0].name, "PAL-BG");
  EXPECT_DOUBLE_EQ(info.standards[0].frame_rate_hz, 25.0);
  EXPECT_EQ(info.standards[1].name, "NTSC-M");
  EXPECT_NEAR(info.standards[1].frame_rate_hz, 29.97, 1e-3);
  EXPECT_EQ(info.current_standard, V4L2_STD_PAL_BG);
  EXPECT_EQ(tvStandardsOffered(info), (std::vector<TvStandard>{TvStandard::Pal, TvStandard::Ntsc, TvStandard::Secam}));
  EXPECT_EQ(tvStandardsOffered(info, 1), (std::vector<TvStandard>{TvStandard::Pal, TvStandard::Ntsc}));
  EXPECT_EQ(tvStandardsOffered(info, 2), (std::vector<TvStandard>{TvStandard::Ntsc}));
}

TEST(QueryDevice, ACameraWithoutInputsOrStandardsListsNone) {
  FakeDevice device;
  test::addStandardFormats(device);
  DeviceInfo info;
  std::string error;
  ASSERT_EQ(queryDevice(device, device.path, info, error), Status::Ok) << error;
  EXPECT_TRUE(info.inputs.empty());
  EXPECT_EQ(info.current_input, -1);
  EXPECT_TRUE(info.standards.empty());
  EXPECT_TRUE(tvStandardsOffered(info).empty());
}

TEST(SelectInputAndStandard, ChosenInThatOrder) {
  FakeDevice device;
  test::addCaptureCard(device);
  const int fd = device.open(device.path.c_str());
  std::string error;
  ASSERT_EQ(selectInputAndStandard(device, fd, device.path, 1, TvStandard::Ntsc, error), Status::Ok) << error;
  EXPECT_EQ(device.input, 1u);
  EXPECT_EQ(device.standard, V4L2_STD_NTSC_M);
  ASSERT_EQ(device.selections.size(), 2u);
  EXPECT_EQ(device.selections[0], "input 1");  // the standards are the input's: it comes first
  // Neither asked for: nothing set.
  ASSERT_EQ(selectInputAndStandard(device, fd, device.path, -1, TvStandard::Keep, error), Status::Ok);
  EXPECT_EQ(device.selections.size(), 2u);
  device.close(fd);
}

TEST(SelectInputAndStandard, BadValuesAreNamed) {
  FakeDevice device;
  test::addCaptureCard(device);
  const int fd = device.open(device.path.c_str());
  std::string error;
  EXPECT_EQ(selectInputAndStandard(device, fd, device.path, 3, TvStandard::Keep, error), Status::CameraNoSuchInput);
  EXPECT_EQ(error, "/dev/video-fake: no input 3 (its inputs: 0 Composite0, 1 Composite1, 2 S-Video)");
  // S-Video takes NTSC only.
  EXPECT_EQ(selectInputAndStandard(device, fd, device.path, 2, TvStandard::Secam, error),
            Status::CameraStandardRefused);
  EXPECT_EQ(error, "/dev/video-fake: input 2 (S-Video) takes no SECAM (it takes NTSC-M)");
  EXPECT_EQ(device.standard, V4L2_STD_PAL_BG);  // unchanged
  device.close(fd);

  // A camera has neither.
  FakeDevice camera;
  test::addStandardFormats(camera);
  const int cfd = camera.open(camera.path.c_str());
  EXPECT_EQ(selectInputAndStandard(camera, cfd, camera.path, 0, TvStandard::Keep, error), Status::CameraNoSuchInput);
  EXPECT_EQ(error, "/dev/video-fake: no input 0 (the device lists no inputs)");
  EXPECT_EQ(selectInputAndStandard(camera, cfd, camera.path, -1, TvStandard::Pal, error),
            Status::CameraStandardRefused);
  EXPECT_EQ(error, "/dev/video-fake: the device takes no PAL (it takes no TV standard)");
  camera.close(cfd);
}

TEST(QueryDevice, OpenErrorsAreNamed) {
  FakeDevice device;
  test::addStandardFormats(device);
  DeviceInfo info;
  std::string error;
  EXPECT_EQ(queryDevice(device, "/dev/video9", info, error), Status::CameraNotFound);
  EXPECT_NE(error.find("/dev/video9"), std::string::npos);
  device.open_errno = EACCES;
  EXPECT_EQ(queryDevice(device, device.path, info, error), Status::CameraPermissionDenied);
  EXPECT_NE(error.find("video' group"), std::string::npos) << error;
  device.open_errno = EBUSY;
  EXPECT_EQ(queryDevice(device, device.path, info, error), Status::CameraBusy);
}

TEST(SetDeviceControl, ByKeyOrName) {
  FakeDevice device;
  test::addStandardControls(device);
  std::string error;
  ASSERT_EQ(setDeviceControl(device, device.path, "Brightness", -20, error), Status::Ok) << error;
  EXPECT_EQ(device.controls[1].value, -20);
  EXPECT_EQ(setDeviceControl(device, device.path, "gain", 33, error), Status::InvalidSettings);  // steps of 16
  EXPECT_NE(error.find("steps of 16"), std::string::npos) << error;
  EXPECT_EQ(device.controls[3].value, 32);
  EXPECT_EQ(setDeviceControl(device, device.path, "zoom", 1, error), Status::InvalidSettings);
  EXPECT_NE(error.find("zoom"), std::string::npos);
  // Exposure time while exposure is automatic: the driver refuses.
  EXPECT_EQ(setDeviceControl(device, device.path, "exposure_time_absolute", 100, error), Status::InvalidSettings);
  EXPECT_NE(error.find("automatic"), std::string::npos) << error;
  EXPECT_EQ(device.openDescriptors(), 0);
}

TEST(ListVideoDevices, NaturalOrderOfVideoNodesOnly) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(IMAGEPRO_TEST_TMP) / "camera" / "dev";
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* name : {"video10", "video2", "video0", "vbi0", "videox", "video", "media0"})
    std::ofstream((dir / name).string()) << "";
  const std::vector<std::string> devices = listVideoDevices(dir.string());
  ASSERT_EQ(devices.size(), 3u);
  EXPECT_EQ(fs::path(devices[0]).filename(), "video0");
  EXPECT_EQ(fs::path(devices[1]).filename(), "video2");
  EXPECT_EQ(fs::path(devices[2]).filename(), "video10");
  EXPECT_TRUE(listVideoDevices((dir / "missing").string()).empty());
}

TEST(SystemDevice, AMissingDeviceIsCameraNotFound) {
  DeviceInfo info;
  std::string error;
  EXPECT_EQ(queryDevice(systemDeviceIo(), "/dev/video-does-not-exist", info, error), Status::CameraNotFound);
  EXPECT_NE(error.find("/dev/video-does-not-exist"), std::string::npos) << error;
}

TEST(SystemDevice, AFileThatIsNoDeviceIsCameraNotFound) {
  namespace fs = std::filesystem;
  const fs::path file = fs::path(IMAGEPRO_TEST_TMP) / "camera" / "not-a-device";
  fs::create_directories(file.parent_path());
  std::ofstream(file.string()) << "plain file";
  DeviceInfo info;
  std::string error;
  EXPECT_EQ(queryDevice(systemDeviceIo(), file.string(), info, error), Status::CameraNotFound);
  EXPECT_NE(error.find("not a V4L2 device"), std::string::npos) << error;
}

}  // namespace
}  // namespace imagepro
