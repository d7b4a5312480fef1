#include "core/source/image_file.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) { return test::freshDir("source/" + name); }

cv::Mat testPattern(int type) {
  cv::Mat img(48, 64, type);
  cv::randu(img, cv::Scalar::all(0), cv::Scalar::all(256));
  return img;
}

void writeBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

TEST(ImageFile, LosslessFormatsRoundTrip) {
  const fs::path dir = scratch("roundtrip");
  const cv::Mat grey = testPattern(CV_8UC1);
  for (const char* ext : {".png", ".pgm", ".bmp", ".tif", ".tiff"}) {
    const std::string path = (dir / (std::string("grey") + ext)).string();
    ASSERT_TRUE(cv::imwrite(path, grey)) << ext;
    cv::Mat read;
    std::string error;
    ASSERT_EQ(readGreyImage(path, read, error), Status::Ok) << ext << ": " << error;
    ASSERT_EQ(read.type(), CV_8UC1);
    EXPECT_EQ(cv::norm(read, grey, cv::NORM_INF), 0.0) << ext;
  }
}

TEST(ImageFile, JpegIsReadWithinItsLoss) {
  const fs::path dir = scratch("jpeg");
  cv::Mat grey(48, 64, CV_8UC1);
  for (int v = 0; v < grey.rows; ++v)
    for (int u = 0; u < grey.cols; ++u) grey.at<std::uint8_t>(v, u) = static_cast<std::uint8_t>(2 * u + v);
  for (const char* ext : {".jpg", ".jpeg"}) {
    const std::string path = (dir / (std::string("smooth") + ext)).string();
    ASSERT_TRUE(cv::imwrite(path, grey, {cv::IMWRITE_JPEG_QUALITY, 95}));
    cv::Mat read;
    std::string error;
    ASSERT_EQ(readGreyImage(path, read, error), Status::Ok) << error;
    ASSERT_EQ(read.type(), CV_8UC1);
    EXPECT_LT(cv::norm(read, grey, cv::NORM_L1) / grey.total(), 2.0);
  }
}

TEST(ImageFile, ColourBecomesGrey) {
  const fs::path dir = scratch("colour");
  const cv::Mat colour = testPattern(CV_8UC3);
  cv::Mat expected;
  cv::cvtColor(colour, expected, cv::COLOR_BGR2GRAY);
  for (const char* ext : {".png", ".ppm", ".bmp", ".tif"}) {
    const std::string path = (dir / (std::string("colour") + ext)).string();
    ASSERT_TRUE(cv::imwrite(path, colour));
    cv::Mat read;
    std::string error;
    ASSERT_EQ(readGreyImage(path, read, error), Status::Ok) << error;
    ASSERT_EQ(read.type(), CV_8UC1);
    EXPECT_EQ(cv::norm(read, expected, cv::NORM_INF), 0.0) << ext;
  }
  // Pure red, green, blue: ITU-R 601 weights.
  cv::Mat rgb(1, 3, CV_8UC3);
  rgb.at<cv::Vec3b>(0, 0) = {0, 0, 255};
  rgb.at<cv::Vec3b>(0, 1) = {0, 255, 0};
  rgb.at<cv::Vec3b>(0, 2) = {255, 0, 0};
  const std::string path = (dir / "rgb.png").string();
  ASSERT_TRUE(cv::imwrite(path, rgb));
  cv::Mat read;
  std::string error;
  ASSERT_EQ(readGreyImage(path, read, error), Status::Ok);
  EXPECT_EQ(read.at<std::uint8_t>(0, 0), 76);
  EXPECT_EQ(read.at<std::uint8_t>(0, 1), 150);
  EXPECT_EQ(read.at<std::uint8_t>(0, 2), 29);
  // With an alpha channel.
  cv::Mat bgra;
  cv::cvtColor(colour, bgra, cv::COLOR_BGR2BGRA);
  const std::string alpha = (dir / "alpha.png").string();
  ASSERT_TRUE(cv::imwrite(alpha, bgra));
  ASSERT_EQ(readGreyImage(alpha, read, error), Status::Ok) << error;
  EXPECT_EQ(cv::norm(read, expected, cv::NORM_INF), 0.0);
}

TEST(ImageFile, SixteenBitIsScaledToEightBit) {
  const fs::path dir = scratch("sixteen");
  cv::Mat deep(2, 4, CV_16UC1);
  const std::uint16_t values[] = {0, 257, 100 * 257, 200 * 257 + 128, 65535, 65535 - 128, 1000, 30000};
  for (int i = 0; i < 8; ++i) deep.at<std::uint16_t>(i / 4, i % 4) = values[i];
  for (const char* ext : {".png", ".tif", ".pgm"}) {
    const std::string path = (dir / (std::string("deep") + ext)).string();
    ASSERT_TRUE(cv::imwrite(path, deep)) << ext;
    cv::Mat read;
    std::string error;
    ASSERT_EQ(readGreyImage(path, read, error), Status::Ok) << ext << ": " << error;
    ASSERT_EQ(read.type(), CV_8UC1);
    for (int i = 0; i < 8; ++i)
      EXPECT_EQ(read.at<std::uint8_t>(i / 4, i % 4), static_cast<int>(std::lround(values[i] / 257.0)))
          << ext << " " << values[i];
  }
  // 16-bit colour.
  cv::Mat deep_colour(1, 1, CV_16UC3, cv::Scalar(0, 0, 65535));
  const std::string path = (dir / "deep_colour.png").string();
  ASSERT_TRUE(cv::imwrite(path, deep_colour));
  cv::Mat read;
  std::string error;
  ASSERT_EQ(readGreyImage(path, read, error), Status::Ok) << error;
  EXPECT_EQ(read.at<std::uint8_t>(0, 0), 76);
}

TEST(ImageFile, FloatTiffIsTakenAsZeroToOne) {
  const fs::path dir = scratch("float");
  cv::Mat f(1, 3, CV_32FC1);
  f.at<float>(0, 0) = 0.0f;
  f.at<float>(0, 1) = 0.25f;
  f.at<float>(0, 2) = 1.0f;
  const std::string path = (dir / "float.tif").string();
  ASSERT_TRUE(cv::imwrite(path, f));
  cv::Mat read;
  std::string error;
  ASSERT_EQ(readGreyImage(path, read, error), Status::Ok) << error;
  EXPECT_EQ(read.at<std::uint8_t>(0, 0), 0);
  EXPECT_EQ(read.at<std::uint8_t>(0, 1), 64);
  EXPECT_EQ(read.at<std::uint8_t>(0, 2), 255);
}

TEST(ImageFile, MissingFileIsNamed) {
  const fs::path dir = scratch("missing");
  cv::Mat read = testPattern(CV_8UC1);
  std::string error;
  const std::string path = (dir / "nothing_here.png").string();
  EXPECT_EQ(readGreyImage(path, read, error), Status::FileNotFound);
  EXPECT_NE(error.find("nothing_here.png"), std::string::npos);
  EXPECT_TRUE(read.empty());
}

// A PNG or JPEG cut off anywhere (in its header, its pixels, or just before its end
// marker) is FileTruncated, named, with no image: decoders would hand back a partial
// image (libjpeg fills the rest with grey) as if it were whole. The same bytes whole,
// or with bytes after the end marker, read as usual.
TEST(ImageFile, CutOffPngAndJpegAreTruncated) {
  const fs::path dir = scratch("truncated");
  cv::Mat smooth(96, 128, CV_8UC1);
  for (int v = 0; v < smooth.rows; ++v)
    for (int u = 0; u < smooth.cols; ++u) smooth.at<std::uint8_t>(v, u) = static_cast<std::uint8_t>(u + v);
  for (const char* ext : {".png", ".jpg"}) {
    std::vector<unsigned char> encoded;
    ASSERT_TRUE(cv::imencode(ext, smooth, encoded));
    cv::Mat read;
    std::string error;
    for (const std::size_t keep : {std::size_t{20}, encoded.size() / 3, encoded.size() * 9 / 10, encoded.size() - 1}) {
      const fs::path cut = dir / ("cut" + std::to_string(keep) + ext);
      writeBytes(cut, std::string(encoded.begin(), encoded.begin() + static_cast<long>(keep)));
      EXPECT_EQ(readGreyImage(cut.string(), read, error), Status::FileTruncated) << cut;
      EXPECT_NE(error.find(cut.string() + ": the file ends before its image does"), std::string::npos) << error;
      EXPECT_TRUE(read.empty());
    }
    const fs::path whole = dir / (std::string("whole") + ext);
    writeBytes(whole, std::string(encoded.begin(), encoded.end()) + "trailing bytes");
    ASSERT_EQ(readGreyImage(whole.string(), read, error), Status::Ok) << error;
    EXPECT_EQ(read.size(), smooth.size());
  }
}

// The container's size is checked before decoding: a PNG that claims 100000 x 100000
// pixels is ImageTooLarge at once, not gigabytes later.
TEST(ImageFile, HugeDeclaredSizeIsImageTooLarge) {
  const fs::path dir = scratch("too_large");
  std::vector<unsigned char> encoded;
  ASSERT_TRUE(cv::imencode(".png", testPattern(CV_8UC1), encoded));
  // IHDR's width and height are the first 8 bytes of its data (offset 16); the CRC no
  // longer matches, which is never looked at because the size is refused first.
  for (int i = 0; i < 2; ++i) {
    const std::uint32_t side = 100000;
    for (int k = 0; k < 4; ++k) encoded[16 + 4 * i + k] = static_cast<unsigned char>(side >> (24 - 8 * k));
  }
  const fs::path huge = dir / "huge.png";
  writeBytes(huge, std::string(encoded.begin(), encoded.end()));
  cv::Mat read;
  std::string error;
  EXPECT_EQ(readGreyImage(huge.string(), read, error), Status::ImageTooLarge);
  EXPECT_NE(error.find("huge.png: 100000x100000 is more than 16384 pixels a side"), std::string::npos) << error;
}

TEST(ImageFile, CorruptEmptyAndFolderAreUnreadable) {
  const fs::path dir = scratch("bad");
  cv::Mat read;
  std::string error;
  // Garbage bytes under an image name.
  const fs::path garbage = dir / "x.png";
  writeBytes(garbage, std::string("this is not an image at all \x01\x02\x03\xff\xfe", 34));
  EXPECT_EQ(readGreyImage(garbage.string(), read, error), Status::FileUnreadable);
  EXPECT_NE(error.find("x.png"), std::string::npos);
  // A PNG signature followed by garbage.
  const fs::path fake = dir / "fake.png";
  writeBytes(fake, std::string("\x89PNG\r\n\x1a\n", 8) + std::string(200, '\x55'));
  EXPECT_EQ(readGreyImage(fake.string(), read, error), Status::FileUnreadable);
  EXPECT_NE(error.find("fake.png"), std::string::npos);
  // An empty file.
  const fs::path empty = dir / "empty.png";
  writeBytes(empty, "");
  EXPECT_EQ(readGreyImage(empty.string(), read, error), Status::FileUnreadable);
  EXPECT_NE(error.find("empty"), std::string::npos);
  // A folder passed as a file.
  const fs::path folder = dir / "folder.png";
  fs::create_directories(folder);
  EXPECT_EQ(readGreyImage(folder.string(), read, error), Status::FileUnreadable);
  EXPECT_NE(error.find("folder"), std::string::npos);
  EXPECT_TRUE(read.empty());
}

TEST(ImageFile, ToGrey8RejectsWhatItCannotConvert) {
  cv::Mat grey;
  std::string error;
  EXPECT_EQ(toGrey8(cv::Mat(), grey, error), Status::FileUnreadable);
  EXPECT_EQ(toGrey8(cv::Mat(2, 2, CV_32SC1, cv::Scalar(5)), grey, error), Status::FileUnreadable);
  EXPECT_EQ(toGrey8(cv::Mat(2, 2, CV_8UC2, cv::Scalar(7, 200)), grey, error), Status::Ok);
  EXPECT_EQ(grey.at<std::uint8_t>(1, 1), 7);
}

TEST(ImageFile, NaturalOrder) {
  EXPECT_TRUE(naturalLess("img2.png", "img10.png"));
  EXPECT_FALSE(naturalLess("img10.png", "img2.png"));
  EXPECT_TRUE(naturalLess("frame_00009.png", "frame_00010.png"));
  EXPECT_TRUE(naturalLess("a.png", "B.png"));
  EXPECT_TRUE(naturalLess("img", "img1"));
  EXPECT_TRUE(naturalLess("x2y3", "x2y12"));
  EXPECT_TRUE(naturalLess("9", "10"));
  EXPECT_TRUE(naturalLess("99999999999999999999999", "100000000000000000000000"));  // beyond 64 bits
  // A total order: of two names equal but for case or leading zeros, exactly one is first.
  EXPECT_NE(naturalLess("x02", "x2"), naturalLess("x2", "x02"));
  EXPECT_NE(naturalLess("Img1", "img1"), naturalLess("img1", "Img1"));
  EXPECT_FALSE(naturalLess("same", "same"));
  std::vector<std::string> names{"img10.png", "img2.png", "IMG3.png", "img1.png", "img1a.png", "img01b.png", "img100.png"};
  std::sort(names.begin(), names.end(), naturalLess);
  EXPECT_EQ(names, (std::vector<std::string>{"img1.png", "img1a.png", "img01b.png", "img2.png", "IMG3.png", "img10.png",
                                             "img100.png"}));
}

TEST(ImageFile, FolderSequenceInNaturalOrder) {
  const fs::path dir = scratch("sequence");
  const cv::Mat img = testPattern(CV_8UC1);
  for (const char* name : {"img10.png", "img2.png", "img1.png", "IMG3.bmp", "img11.JPG"}) cv::imwrite((dir / name).string(), img);
  writeBytes(dir / "notes.txt", "not an image\n");
  fs::create_directories(dir / "sub.png");  // a folder with an image name is not an image
  std::vector<std::string> paths;
  std::string error;
  ASSERT_EQ(listImageSequence(dir.string(), paths, error), Status::Ok) << error;
  std::vector<std::string> names;
  for (const auto& p : paths) names.push_back(fs::path(p).filename().string());
  EXPECT_EQ(names, (std::vector<std::string>{"img1.png", "img2.png", "IMG3.bmp", "img10.png", "img11.JPG"}));
  for (const auto& p : paths) EXPECT_TRUE(fs::exists(p)) << p;
}

TEST(ImageFile, ListFileSequenceKeepsItsOrder) {
  const fs::path dir = scratch("list");
  fs::create_directories(dir / "frames");
  const cv::Mat img = testPattern(CV_8UC1);
  cv::imwrite((dir / "frames" / "b.png").string(), img);
  cv::imwrite((dir / "a.png").string(), img);
  const std::string absolute = (dir / "a.png").string();
  writeBytes(dir / "list.txt", "# two frames\nframes/b.png\n\n  a.png  \r\n" + absolute + "\n");
  std::vector<std::string> paths;
  std::string error;
  ASSERT_EQ(listImageSequence((dir / "list.txt").string(), paths, error), Status::Ok) << error;
  ASSERT_EQ(paths.size(), 3u);
  EXPECT_EQ(fs::path(paths[0]), dir / "frames" / "b.png");
  EXPECT_EQ(fs::path(paths[1]), dir / "a.png");
  EXPECT_EQ(paths[2], absolute);
  // A single image is a sequence of one.
  ASSERT_EQ(listImageSequence(absolute, paths, error), Status::Ok);
  EXPECT_EQ(paths, std::vector<std::string>{absolute});
}

TEST(ImageFile, SequenceErrors) {
  const fs::path dir = scratch("sequence_errors");
  std::vector<std::string> paths{"stale"};
  std::string error;
  EXPECT_EQ(listImageSequence((dir / "absent").string(), paths, error), Status::FileNotFound);
  EXPECT_NE(error.find("absent"), std::string::npos);
  EXPECT_TRUE(paths.empty());
  fs::create_directories(dir / "empty");
  EXPECT_EQ(listImageSequence((dir / "empty").string(), paths, error), Status::FileNotFound);
  writeBytes(dir / "blank.txt", "# nothing\n\n");
  EXPECT_EQ(listImageSequence((dir / "blank.txt").string(), paths, error), Status::FileNotFound);
}

}  // namespace
}  // namespace imagepro
