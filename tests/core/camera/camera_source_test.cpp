#include "core/camera/camera_source.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "fake_device.h"

namespace imagepro {
namespace {

using test::FakeDevice;
using test::referenceLuma;

const std::uint32_t kYuyv = makeFourcc('Y', 'U', 'Y', 'V');
const std::uint32_t kMjpg = makeFourcc('M', 'J', 'P', 'G');
const std::uint32_t kGrey = makeFourcc('G', 'R', 'E', 'Y');

CameraRequest requestFor(const FakeDevice& device, int width = 640, int height = 480, double rate = 25.0) {
  CameraRequest r;
  r.device = device.path;
  r.width = width;
  r.height = height;
  r.frame_rate_hz = rate;
  r.timeout_ms = 500;
  return r;
}

// The frame of sequence number `sequence` as the fake device draws it.
cv::Mat referenceFrame(int width, int height, std::uint32_t sequence) {
  cv::Mat m(height, width, CV_8UC1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) m.at<std::uint8_t>(y, x) = referenceLuma(x, y, sequence);
  return m;
}

bool insideAnyBuffer(const FakeDevice& device, const std::uint8_t* p) {
  for (std::size_t i = 0; i < device.bufferCount(); ++i) {
    const auto& b = device.bufferData(i);
    if (p >= b.data() && p < b.data() + b.size()) return true;
  }
  return false;
}

class CameraFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    test::addStandardFormats(device);
    test::addStandardControls(device);
  }
  // The device is closed and nothing is left mapped.
  void expectReleased() const {
    EXPECT_EQ(device.openDescriptors(), 0);
    EXPECT_EQ(device.mappedBuffers(), 0);
    EXPECT_FALSE(device.streaming());
  }
  FakeDevice device;
};

TEST_F(CameraFixture, NegotiationAccepted) {
  CameraSource camera(requestFor(device), device);
  ASSERT_EQ(camera.start(), Status::Ok) << camera.lastError();
  const CameraFormat f = camera.format();
  EXPECT_EQ(f.fourcc, kYuyv);
  EXPECT_EQ(f.format, PixelFormat::Yuyv);
  EXPECT_EQ(f.width, 640);
  EXPECT_EQ(f.height, 480);
  EXPECT_EQ(f.bytes_per_line, 1280u);
  EXPECT_DOUBLE_EQ(f.nominal_rate_hz, 25.0);
  EXPECT_EQ(f.buffers, 4);
  EXPECT_EQ(f.card, "Fake Camera");
  EXPECT_FALSE(f.size_adjusted);
  EXPECT_FALSE(f.rate_adjusted);
  EXPECT_FALSE(f.format_adjusted);
  EXPECT_TRUE(camera.streaming());
  EXPECT_TRUE(device.streaming());
  EXPECT_EQ(device.mappedBuffers(), 4);
  EXPECT_EQ(camera.describe(), "camera /dev/video-fake 640x480 YUYV 25 Hz");
  EXPECT_EQ(camera.frameRateHz(), 0.0);  // the camera paces itself
  camera.stop();
  expectReleased();
}

TEST_F(CameraFixture, NegotiationAdjustedByTheChoice) {
  // 800x600 at 60 Hz is not offered: the nearest size, the fastest rate there.
  CameraSource camera(requestFor(device, 800, 600, 60.0), device);
  ASSERT_EQ(camera.start(), Status::Ok) << camera.lastError();
  const CameraFormat f = camera.format();
  EXPECT_EQ(f.width, 640);
  EXPECT_EQ(f.height, 480);
  EXPECT_DOUBLE_EQ(f.nominal_rate_hz, 30.0);
  EXPECT_TRUE(f.size_adjusted);
  EXPECT_TRUE(f.rate_adjusted);
}

TEST_F(CameraFixture, NegotiationAdjustedByTheDriver) {
  // The driver crops to 632x472 and pads every line to 1300 bytes; frames follow it.
  device.adjust_format = [](v4l2_pix_format& pix) {
    pix.width = 632;
    pix.height = 472;
    pix.bytesperline = 1300;
    pix.sizeimage = 1300 * 472;
  };
  CameraSource camera(requestFor(device), device);
  ASSERT_EQ(camera.start(), Status::Ok) << camera.lastError();
  const CameraFormat f = camera.format();
  EXPECT_EQ(f.width, 632);
  EXPECT_EQ(f.height, 472);
  EXPECT_EQ(f.bytes_per_line, 1300u);
  EXPECT_TRUE(f.size_adjusted);
  Frame frame;
  ASSERT_EQ(camera.next(frame), Status::Ok) << camera.lastError();
  ASSERT_EQ(frame.image.size(), cv::Size(632, 472));
  EXPECT_EQ(cv::norm(frame.image, referenceFrame(632, 472, 0), cv::NORM_INF), 0.0);
}

TEST_F(CameraFixture, NegotiationAdjustedToAnotherReadableFormat) {
  device.adjust_format = [](v4l2_pix_format& pix) {
    pix.pixelformat = makeFourcc('G', 'R', 'E', 'Y');
    pix.bytesperline = pix.width;
    pix.sizeimage = pix.width * pix.height;
  };
  CameraSource camera(requestFor(device), device);
  ASSERT_EQ(camera.start(), Status::Ok) << camera.lastError();
  EXPECT_TRUE(camera.format().format_adjusted);
  EXPECT_EQ(camera.format().format, PixelFormat::Grey);
  Frame frame;
  ASSERT_EQ(camera.next(frame), Status::Ok);
  EXPECT_EQ(cv::norm(frame.image, referenceFrame(640, 480, 0), cv::NORM_INF), 0.0);
}

TEST_F(CameraFixture, NegotiationRefused) {
  {
    device.s_fmt_errno = EINVAL;
    CameraSource camera(requestFor(device), device);
    EXPECT_EQ(camera.start(), Status::CameraFormatRefused);
    EXPECT_NE(camera.lastError().find("/dev/video-fake"), std::string::npos) << camera.lastError();
    EXPECT_NE(camera.lastError().find("YUYV 640x480"), std::string::npos) << camera.lastError();
    EXPECT_FALSE(camera.streaming());
    expectReleased();
    Frame frame;
    EXPECT_EQ(camera.next(frame), Status::CameraFormatRefused);  // stays failed, no retry
    EXPECT_EQ(device.opens, 1);
  }
  {
    device.s_fmt_errno = 0;
    device.adjust_format = [](v4l2_pix_format& pix) { pix.pixelformat = makeFourcc('B', 'A', '8', '1'); };
    CameraSource camera(requestFor(device), device);
    EXPECT_EQ(camera.start(), Status::CameraFormatRefused);
    EXPECT_NE(camera.lastError().find("BA81"), std::string::npos) << camera.lastError();
    expectReleased();
  }
  {
    device.adjust_format = nullptr;
    device.s_fmt_errno = EBUSY;  // another program streams from it
    CameraSource camera(requestFor(device), device);
    EXPECT_EQ(camera.start(), Status::CameraBusy);
    expectReleased();
  }
}

// A size beyond what a frame may hold is refused by name before any buffer is mapped:
// whether it is the one asked for (a device that lists it) or the driver's answer.
TEST_F(CameraFixture, ImageTooLargeIsRefusedBeforeStreaming) {
  device.formats[0].sizes.push_back({100000, 100000, {{1, 25}}});
  {
    CameraSource camera(requestFor(device, 100000, 100000), device);
    EXPECT_EQ(camera.start(), Status::ImageTooLarge);
    EXPECT_NE(camera.lastError().find("100000x100000 is more than 16384 pixels a side"), std::string::npos)
        << camera.lastError();
    EXPECT_NE(camera.lastError().find(device.path), std::string::npos) << camera.lastError();
    EXPECT_NE(device.current.width, 100000u);  // never asked of the driver
  }
  expectReleased();
  device.adjust_format = [](v4l2_pix_format& pix) {
    pix.width = 12000;
    pix.height = 9000;
    pix.bytesperline = 24000;
    pix.sizeimage = 24000 * 9000;
  };
  {
    CameraSource camera(requestFor(device), device);
    EXPECT_EQ(camera.start(), Status::ImageTooLarge);
    EXPECT_NE(camera.lastError().find("with a size beyond what a frame may hold: 12000x9000 is 102 megapixels"), std::string::npos)
        << camera.lastError();
  }
  expectReleased();
}

TEST_F(CameraFixture, TooFewBuffersOrNoBandwidth) {
  {
    device.max_buffers = 1;
    CameraSource camera(requestFor(device), device);
    EXPECT_EQ(camera.start(), Status::CameraFormatRefused);
    EXPECT_NE(camera.lastError().find("granted 1 buffer"), std::string::npos) << camera.lastError();
    expectReleased();
  }
  {
    device.max_buffers = 8;
    device.streamon_errno = ENOSPC;
    CameraSource camera(requestFor(device), device);
    EXPECT_EQ(camera.start(), Status::CameraBusy);
    EXPECT_NE(camera.lastError().find("USB bandwidth"), std::string::npos) << camera.lastError();
    expectReleased();
  }
}

TEST_F(CameraFixture, OpenAndCapabilityErrorsAreNamed) {
  CameraRequest missing = requestFor(device);
  missing.device = "/dev/video-missing";
  CameraSource absent(missing, device);
  EXPECT_EQ(absent.start(), Status::CameraNotFound);
  EXPECT_NE(absent.lastError().find("/dev/video-missing"), std::string::npos);
  EXPECT_EQ(absent.describe(), "camera /dev/video-missing (CameraNotFound)");

  device.open_errno = EACCES;
  CameraSource barred(requestFor(device), device);
  EXPECT_EQ(barred.start(), Status::CameraPermissionDenied);
  device.open_errno = EBUSY;
  CameraSource busy(requestFor(device), device);
  EXPECT_EQ(busy.start(), Status::CameraBusy);
  device.open_errno = 0;

  device.device_caps = V4L2_CAP_META_CAPTURE | V4L2_CAP_STREAMING;  // a camera's metadata node
  CameraSource metadata(requestFor(device), device);
  EXPECT_EQ(metadata.start(), Status::CameraNotFound);
  EXPECT_NE(metadata.lastError().find("not a video capture node"), std::string::npos);
  device.device_caps = V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_READWRITE;  // read() only
  CameraSource read_only(requestFor(device), device);
  EXPECT_EQ(read_only.start(), Status::CameraNoSupportedFormat);
  device.device_caps = V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_STREAMING;

  device.formats = {{makeFourcc('B', 'A', '8', '1'), "Bayer", {{640, 480, {{1, 30}}}}, false}};
  CameraSource bayer(requestFor(device), device);
  EXPECT_EQ(bayer.start(), Status::CameraNoSupportedFormat);
  EXPECT_NE(bayer.lastError().find("BA81"), std::string::npos);
  expectReleased();
}

TEST_F(CameraFixture, ACaptureCardsInputAndStandardBeforeTheFormat) {
  FakeDevice card;
  test::addCaptureCard(card);
  CameraRequest r = requestFor(card, 0, 0, 0.0);
  r.input = 1;
  r.standard = TvStandard::Ntsc;
  CameraSource camera(r, card);
  ASSERT_EQ(camera.start(), Status::Ok) << camera.lastError();
  EXPECT_EQ(card.input, 1u);
  EXPECT_EQ(card.standard, V4L2_STD_NTSC_M);
  EXPECT_EQ(camera.format().fourcc, kGrey);
  Frame frame;
  EXPECT_EQ(camera.next(frame), Status::Ok) << camera.lastError();
  camera.stop();

  // A bad input stops the start, named, and leaves the device closed.
  r.input = 7;
  CameraSource wrong(r, card);
  EXPECT_EQ(wrong.start(), Status::CameraNoSuchInput);
  EXPECT_NE(wrong.lastError().find("no input 7"), std::string::npos) << wrong.lastError();
  EXPECT_EQ(card.openDescriptors(), 0);
  // A camera without inputs takes the default request as before.
  CameraSource plain(requestFor(device), device);
  EXPECT_EQ(plain.start(), Status::Ok) << plain.lastError();
  EXPECT_TRUE(device.selections.empty());
}

TEST_F(CameraFixture, StreamsFramesInPlaceWithDriverTimes) {
  device.formats = {{kGrey, "Grey", {{640, 480, {{1, 25}}}}, false}};
  device.line_padding = 64;  // the driver pads lines: the view keeps its stride
  CameraSource camera(requestFor(device), device);
  ASSERT_EQ(camera.start(), Status::Ok) << camera.lastError();
  Frame frame;
  frame.name = "left over";
  for (int i = 0; i < 10; ++i) {
    ASSERT_EQ(camera.next(frame), Status::Ok) << camera.lastError();
    EXPECT_EQ(frame.index, i);
    EXPECT_NEAR(frame.timestamp_s, 0.04 * i, 1e-6);  // driver time after the first frame
    EXPECT_TRUE(frame.name.empty());
    ASSERT_EQ(frame.image.type(), CV_8UC1);
    ASSERT_EQ(frame.image.size(), cv::Size(640, 480));
    EXPECT_EQ(frame.image.step[0], 704u);
    EXPECT_TRUE(insideAnyBuffer(device, frame.image.data)) << "no copy for grey";
    EXPECT_EQ(cv::norm(frame.image, referenceFrame(640, 480, static_cast<std::uint32_t>(i)), cv::NORM_INF), 0.0);
  }
  const CaptureStats s = camera.stats();
  EXPECT_EQ(s.frames, 10);
  EXPECT_EQ(s.dropped, 0);
  EXPECT_NEAR(s.achieved_rate_hz, 25.0, 1e-6);
  EXPECT_EQ(camera.describe(), "camera /dev/video-fake 640x480 GREY 25 Hz (25 Hz achieved)");
  // Every wait used the request's time-out.
  for (int t : device.wait_timeouts) EXPECT_LE(t, 500);
  EXPECT_GE(device.wait_timeouts.front(), 400);
}

TEST_F(CameraFixture, EveryFormatThroughTheStream) {
  struct Case {
    std::uint32_t fourcc;
    double max_mean_error;  // grey levels; raw formats are exact
  };
  for (const Case& c : {Case{kGrey, 0.0}, Case{kYuyv, 0.0}, Case{makeFourcc('U', 'Y', 'V', 'Y'), 0.0},
                        Case{makeFourcc('N', 'V', '1', '2'), 0.0}, Case{makeFourcc('N', 'V', '2', '1'), 0.0},
                        Case{makeFourcc('Y', 'U', '1', '2'), 0.0}, Case{makeFourcc('Y', 'V', '1', '2'), 0.0},
                        Case{makeFourcc('R', 'G', 'B', '3'), 0.0}, Case{makeFourcc('B', 'G', 'R', '3'), 0.0},
                        Case{kMjpg, 2.0}}) {
    SCOPED_TRACE(fourccText(c.fourcc));
    FakeDevice fake;
    fake.formats = {{c.fourcc, fourccText(c.fourcc), {{162, 122, {{1, 25}}}}, false}};
    fake.line_padding = 5;  // odd stride
    CameraSource camera(requestFor(fake, 162, 122), fake);
    ASSERT_EQ(camera.start(), Status::Ok) << camera.lastError();
    Frame frame;
    for (std::uint32_t i = 0; i < 3; ++i) {
      ASSERT_EQ(camera.next(frame), Status::Ok) << camera.lastError();
      ASSERT_EQ(frame.image.size(), cv::Size(162, 122));
      const cv::Mat expected = referenceFrame(162, 122, i);
      if (c.max_mean_error == 0.0) {
        EXPECT_EQ(cv::norm(frame.image, expected, cv::NORM_INF), 0.0);
      } else {  // JPEG smooths the pattern's sharp steps
        EXPECT_LE(cv::norm(frame.image, expected, cv::NORM_L1) / (162.0 * 122.0), c.max_mean_error);
      }
      EXPECT_EQ(insideAnyBuffer(fake, frame.image.data), lumaInPlace(*pixelFormatFromFourcc(c.fourcc)));
    }
  }
}

TEST_F(CameraFixture, BuffersCirculate) {
  CameraSource camera(requestFor(device), device);
  ASSERT_EQ(camera.start(), Status::Ok);
  Frame frame;
  // Far more frames than buffers: each is given back to the driver.
  for (int i = 0; i < 50; ++i) ASSERT_EQ(camera.next(frame), Status::Ok) << i << ": " << camera.lastError();
  EXPECT_EQ(device.delivered, 50u);
}

TEST_F(CameraFixture, LostAndDamagedFramesAreCounted) {
  device.lost_sequences = {3, 4};
  device.damaged_sequences = {6};
  CameraSource camera(requestFor(device), device);
  ASSERT_EQ(camera.start(), Status::Ok);
  Frame frame;
  std::vector<double> times;
  for (int i = 0; i < 4; ++i) {
    ASSERT_EQ(camera.next(frame), Status::Ok) << camera.lastError();
    times.push_back(frame.timestamp_s);
  }
  // Sequences 0 1 2 5 6 (damaged) 7: the gap shows in the times too.
  EXPECT_NEAR(times[3], 5 * 0.04, 1e-6);
  EXPECT_EQ(camera.next(frame), Status::EmptyFrame);
  EXPECT_TRUE(frame.image.empty());
  EXPECT_EQ(frame.index, 4);
  EXPECT_NEAR(frame.timestamp_s, 6 * 0.04, 1e-6);
  EXPECT_NE(camera.lastError().find("frame 6 as damaged"), std::string::npos) << camera.lastError();
  ASSERT_EQ(camera.next(frame), Status::Ok);  // streaming goes on
  EXPECT_EQ(frame.index, 5);
  EXPECT_EQ(cv::norm(frame.image, referenceFrame(640, 480, 7), cv::NORM_INF), 0.0);
  const CaptureStats s = camera.stats();
  EXPECT_EQ(s.frames, 5);
  EXPECT_EQ(s.dropped, 2);
  EXPECT_EQ(s.corrupt, 1);
}

TEST_F(CameraFixture, TimeoutThenFramesAgain) {
  CameraSource camera(requestFor(device), device);
  ASSERT_EQ(camera.start(), Status::Ok);
  Frame frame;
  ASSERT_EQ(camera.next(frame), Status::Ok);
  device.stalled = true;
  device.wait_timeouts.clear();
  EXPECT_EQ(camera.next(frame), Status::CameraTimeout);
  EXPECT_TRUE(frame.image.empty());  // no view of a buffer the driver has again
  EXPECT_NE(camera.lastError().find("no frame within 500 ms"), std::string::npos) << camera.lastError();
  ASSERT_FALSE(device.wait_timeouts.empty());
  EXPECT_TRUE(camera.streaming());
  EXPECT_EQ(camera.stats().timeouts, 1);
  device.stalled = false;
  ASSERT_EQ(camera.next(frame), Status::Ok) << camera.lastError();
  EXPECT_EQ(frame.index, 1);
}

TEST_F(CameraFixture, DisconnectMidStreamAndReconnect) {
  for (const int err : {ENODEV, EIO}) {
    SCOPED_TRACE(err);
    FakeDevice fake;
    test::addStandardFormats(fake);
    fake.vanish_after = 5;
    fake.vanish_errno = err;
    CameraSource camera(requestFor(fake), fake);
    ASSERT_EQ(camera.start(), Status::Ok);
    Frame frame;
    for (int i = 0; i < 5; ++i) ASSERT_EQ(camera.next(frame), Status::Ok);
    const double last_time = frame.timestamp_s;
    EXPECT_EQ(camera.next(frame), Status::CameraDisconnected);
    EXPECT_TRUE(frame.image.empty());  // its buffers are unmapped
    EXPECT_NE(camera.lastError().find("/dev/video-fake"), std::string::npos);
    EXPECT_NE(camera.lastError().find("restart"), std::string::npos);
    EXPECT_FALSE(camera.streaming());
    EXPECT_EQ(fake.openDescriptors(), 0);  // closed cleanly, nothing left mapped
    EXPECT_EQ(fake.mappedBuffers(), 0);
    EXPECT_EQ(camera.describe(), "camera /dev/video-fake (CameraDisconnected)");
    // The loop may ask again: the same answer, without touching the device.
    const int opens = fake.opens;
    EXPECT_EQ(camera.next(frame), Status::CameraDisconnected);
    EXPECT_EQ(fake.opens, opens);
    // Still unplugged.
    EXPECT_EQ(camera.restart(), Status::CameraNotFound);
    // Back again.
    fake.vanish_after = -1;
    fake.reappear();
    ASSERT_EQ(camera.restart(), Status::Ok) << camera.lastError();
    ASSERT_EQ(camera.next(frame), Status::Ok) << camera.lastError();
    EXPECT_EQ(frame.index, 5);  // indices go on
    EXPECT_GT(frame.timestamp_s, last_time);
    EXPECT_EQ(camera.stats().restarts, 1);
    EXPECT_EQ(camera.stats().frames, 6);
  }
}

TEST_F(CameraFixture, StartsOnTheFirstFrameAndEndsAfterStop) {
  CameraSource camera(requestFor(device), device);
  Frame frame;
  ASSERT_EQ(camera.next(frame), Status::Ok) << camera.lastError();
  EXPECT_EQ(frame.index, 0);
  camera.stop();
  expectReleased();
  EXPECT_EQ(camera.next(frame), Status::EndOfStream);
  ASSERT_EQ(camera.restart(), Status::Ok);
  ASSERT_EQ(camera.next(frame), Status::Ok);
  EXPECT_EQ(frame.index, 1);
}

TEST_F(CameraFixture, DestructionReleasesTheDevice) {
  {
    CameraSource camera(requestFor(device), device);
    ASSERT_EQ(camera.start(), Status::Ok);
    Frame frame;
    ASSERT_EQ(camera.next(frame), Status::Ok);
  }
  expectReleased();
}

TEST_F(CameraFixture, ControlsWhileStreamingAndWhileClosed) {
  CameraSource camera(requestFor(device), device);
  std::vector<CameraControl> controls;
  ASSERT_EQ(camera.controls(controls), Status::Ok);  // not streaming: opened just for this
  EXPECT_EQ(device.openDescriptors(), 0);
  ASSERT_EQ(controls.size(), 5u);
  const std::uint32_t brightness = controls[0].id;
  const std::uint32_t exposure_time = controls[3].id;
  EXPECT_EQ(camera.setControl(brightness, 12), Status::Ok) << camera.lastError();

  ASSERT_EQ(camera.start(), Status::Ok);
  Frame frame;
  ASSERT_EQ(camera.next(frame), Status::Ok);
  EXPECT_EQ(camera.setControl(brightness, 40), Status::Ok);
  ASSERT_EQ(camera.controls(controls), Status::Ok);
  EXPECT_EQ(controls[0].value, 40);
  EXPECT_EQ(device.openDescriptors(), 1);  // the streaming descriptor was used
  EXPECT_EQ(camera.setControl(brightness, 65), Status::InvalidSettings);
  EXPECT_NE(camera.lastError().find("-64..64"), std::string::npos) << camera.lastError();
  EXPECT_EQ(camera.setControl(exposure_time, 100), Status::InvalidSettings);
  EXPECT_EQ(camera.setControl(0x12345, 1), Status::InvalidSettings);
  ASSERT_EQ(camera.next(frame), Status::Ok);  // streaming unaffected
}

// Opt-in: IMAGEPRO_TEST_CAMERA=/dev/videoN captures 100 frames from a real device.
TEST(RealCamera, Captures100Frames) {
  const char* device = std::getenv("IMAGEPRO_TEST_CAMERA");
  if (device == nullptr || *device == '\0')
    GTEST_SKIP() << "no camera test: set IMAGEPRO_TEST_CAMERA=/dev/videoN to capture from a real device";
  if (!std::filesystem::exists(device)) GTEST_SKIP() << "no camera at " << device;
  CameraRequest request;
  request.device = device;
  request.width = 640;
  request.height = 480;
  CameraSource camera(request);
  ASSERT_EQ(camera.start(), Status::Ok) << camera.lastError();
  const CameraFormat f = camera.format();
  Frame frame;
  double last_time = -1.0;
  int good = 0;
  for (int i = 0; i < 100; ++i) {
    const Status s = camera.next(frame);
    ASSERT_TRUE(s == Status::Ok || s == Status::EmptyFrame) << statusName(s) << ": " << camera.lastError();
    if (s != Status::Ok) continue;
    ++good;
    EXPECT_EQ(frame.index, i);
    ASSERT_EQ(frame.image.type(), CV_8UC1);
    EXPECT_EQ(frame.image.cols, f.width);
    EXPECT_EQ(frame.image.rows, f.height);
    EXPECT_GT(frame.timestamp_s, last_time);
    last_time = frame.timestamp_s;
  }
  EXPECT_GE(good, 95);
  const CaptureStats s = camera.stats();
  EXPECT_GT(s.achieved_rate_hz, 0.0);
  std::printf("%s: %dx%d %s, nominal %.2f Hz, achieved %.2f Hz, %lld dropped\n", device, f.width, f.height,
              fourccText(f.fourcc).c_str(), f.nominal_rate_hz, s.achieved_rate_hz,
              static_cast<long long>(s.dropped));
}

TEST(SystemCamera, AMissingDeviceIsCameraNotFound) {
  CameraRequest request;
  request.device = "/dev/video-does-not-exist";
  CameraSource camera(request);
  EXPECT_EQ(camera.start(), Status::CameraNotFound);
  EXPECT_NE(camera.lastError().find("/dev/video-does-not-exist"), std::string::npos) << camera.lastError();
  Frame frame;
  EXPECT_EQ(camera.next(frame), Status::CameraNotFound);
  EXPECT_TRUE(isCameraFailure(Status::CameraNotFound));
  EXPECT_FALSE(isCameraFailure(Status::CameraTimeout));
  EXPECT_FALSE(isCameraFailure(Status::EmptyFrame));
}

}  // namespace
}  // namespace imagepro
