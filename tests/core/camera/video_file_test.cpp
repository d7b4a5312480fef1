#include "core/camera/video_file.h"

#include <gtest/gtest.h>

#include <opencv2/videoio.hpp>

#include <filesystem>
#include <fstream>

namespace imagepro {
namespace {

namespace fs = std::filesystem;

// Frame i: a left half at 20 + 15 i and a right half at 230 - 15 i.
cv::Mat clipFrame(int i) {
  cv::Mat m(48, 64, CV_8UC1, cv::Scalar(230 - 15 * i));
  m(cv::Rect(0, 0, 32, 48)).setTo(20 + 15 * i);
  return m;
}

// A 12-frame Motion-JPEG AVI at 25 frames/s, written with OpenCV's own encoder.
fs::path writeClip(const std::string& name, int frames = 12) {
  const fs::path dir = fs::path(IMAGEPRO_TEST_TMP) / "camera";
  fs::create_directories(dir);
  const fs::path path = dir / name;
  fs::remove(path);
  cv::VideoWriter writer(path.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25.0, cv::Size(64, 48), false);
  EXPECT_TRUE(writer.isOpened()) << "Motion-JPEG AVI writing is not available";
  for (int i = 0; i < frames; ++i) writer.write(clipFrame(i));
  writer.release();
  return path;
}

TEST(VideoFile, DeliversEveryFrameWithIndexAndTime) {
  const fs::path path = writeClip("clip.avi");
  VideoFileSource video(path.string(), VideoPacing::FileRate);
  ASSERT_EQ(video.open(), Status::Ok) << video.lastError();
  EXPECT_DOUBLE_EQ(video.fileRateHz(), 25.0);
  EXPECT_DOUBLE_EQ(video.frameRateHz(), 25.0);
  EXPECT_EQ(video.frameCount(), 12);
  Frame frame;
  frame.name = "stale";
  for (int i = 0; i < 12; ++i) {
    ASSERT_EQ(video.next(frame), Status::Ok) << video.lastError();
    EXPECT_EQ(frame.index, i);
    EXPECT_NEAR(frame.timestamp_s, i / 25.0, 1e-9);
    EXPECT_TRUE(frame.name.empty());
    ASSERT_EQ(frame.image.type(), CV_8UC1);
    ASSERT_EQ(frame.image.size(), cv::Size(64, 48));
    // Flat areas survive JPEG within a grey level or two; away from the edge between them.
    EXPECT_NEAR(cv::mean(frame.image(cv::Rect(4, 4, 24, 40)))[0], 20 + 15 * i, 2.0);
    EXPECT_NEAR(cv::mean(frame.image(cv::Rect(36, 4, 24, 40)))[0], 230 - 15 * i, 2.0);
  }
  EXPECT_EQ(video.describe(), "video clip.avi 25 Hz, frame 11 of 12");
  EXPECT_EQ(video.next(frame), Status::EndOfStream);
  EXPECT_TRUE(frame.image.empty());
  EXPECT_EQ(video.next(frame), Status::EndOfStream);

  ASSERT_EQ(video.restart(), Status::Ok);
  ASSERT_EQ(video.next(frame), Status::Ok);
  EXPECT_EQ(frame.index, 0);
  EXPECT_NEAR(cv::mean(frame.image(cv::Rect(4, 4, 24, 40)))[0], 20, 2.0);
}

TEST(VideoFile, AsFastAsPossibleIsUnpaced) {
  const fs::path path = writeClip("fast.avi", 3);
  VideoFileSource video(path.string(), VideoPacing::AsFastAsPossible);
  Frame frame;
  ASSERT_EQ(video.next(frame), Status::Ok) << video.lastError();  // opens on the first frame
  EXPECT_EQ(video.frameRateHz(), 0.0);
  EXPECT_DOUBLE_EQ(video.fileRateHz(), 25.0);
  ASSERT_EQ(video.next(frame), Status::Ok);
  EXPECT_EQ(frame.index, 1);
  EXPECT_NEAR(frame.timestamp_s, 0.04, 1e-9);  // the file's time, not the wall clock
}

TEST(VideoFile, MissingAndUndecodableFilesAreNamed) {
  VideoFileSource missing((fs::path(IMAGEPRO_TEST_TMP) / "camera" / "gone.avi").string());
  EXPECT_EQ(missing.open(), Status::FileNotFound);
  EXPECT_NE(missing.lastError().find("gone.avi"), std::string::npos);
  Frame frame;
  EXPECT_EQ(missing.next(frame), Status::FileNotFound);

  const fs::path junk = fs::path(IMAGEPRO_TEST_TMP) / "camera" / "junk.avi";
  fs::create_directories(junk.parent_path());
  std::ofstream(junk.string()) << "this is not a video";
  VideoFileSource bad(junk.string());
  EXPECT_EQ(bad.open(), Status::FileUnreadable);
  EXPECT_NE(bad.lastError().find("junk.avi"), std::string::npos);
}

TEST(VideoFile, RecognisesVideoExtensions) {
  EXPECT_TRUE(isVideoFileName("a/b/run.AVI"));
  EXPECT_TRUE(isVideoFileName("run.mp4"));
  EXPECT_TRUE(isVideoFileName("run.mkv"));
  EXPECT_FALSE(isVideoFileName("frame.png"));
  EXPECT_FALSE(isVideoFileName("list.txt"));
  EXPECT_FALSE(isVideoFileName("avi"));
}

}  // namespace
}  // namespace imagepro
