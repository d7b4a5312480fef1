#include "core/camera/pixel_format.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <vector>

namespace imagepro {
namespace {

std::uint8_t luma(int x, int y) { return static_cast<std::uint8_t>((x * 37 + y * 101 + 11) & 0xff); }

// A captured buffer of `format` at width x height with `padding` extra bytes per
// line, carrying luma(x, y); chroma and padding hold other values.
struct TestBuffer {
  BufferLayout layout;
  std::vector<std::uint8_t> bytes;
};

TestBuffer makeBuffer(PixelFormat format, int width, int height, std::size_t padding) {
  TestBuffer t;
  const std::size_t bpl = minimumBytesPerLine(format, width) + padding;
  t.layout = {format, width, height, bpl};
  const auto h = static_cast<std::size_t>(height);
  const auto half = static_cast<std::size_t>((height + 1) / 2);
  std::size_t size = bpl * h;
  if (format == PixelFormat::Nv12 || format == PixelFormat::Nv21) size += bpl * half;
  if (format == PixelFormat::Yuv420 || format == PixelFormat::Yvu420) size += 2 * (bpl / 2) * half;
  t.bytes.assign(size, 0xEE);
  for (int y = 0; y < height; ++y) {
    std::uint8_t* line = t.bytes.data() + static_cast<std::size_t>(y) * bpl;
    for (int x = 0; x < width; ++x) {
      const std::uint8_t v = luma(x, y);
      switch (format) {
        case PixelFormat::Yuyv:
          line[2 * x] = v;
          line[2 * x + 1] = static_cast<std::uint8_t>(x % 2 ? 0x10 : 0xF0);
          break;
        case PixelFormat::Uyvy:
          line[2 * x] = static_cast<std::uint8_t>(x % 2 ? 0x10 : 0xF0);
          line[2 * x + 1] = v;
          break;
        case PixelFormat::Rgb24:
        case PixelFormat::Bgr24: line[3 * x] = line[3 * x + 1] = line[3 * x + 2] = v; break;
        default: line[x] = v;
      }
    }
  }
  for (std::size_t i = bpl * h; i < size; ++i) t.bytes[i] = static_cast<std::uint8_t>(0x40 + i % 7);  // chroma
  return t;
}

cv::Mat expectedGrey(int width, int height) {
  cv::Mat m(height, width, CV_8UC1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) m.at<std::uint8_t>(y, x) = luma(x, y);
  return m;
}

TEST(PixelFormat, FourccCodesRoundTrip) {
  EXPECT_EQ(fourccOf(PixelFormat::Yuyv), 0x56595559u);  // 'Y' 'U' 'Y' 'V', little-endian
  EXPECT_EQ(fourccText(fourccOf(PixelFormat::Yuyv)), "YUYV");
  EXPECT_EQ(fourccText(makeFourcc('G', 'R', 'E', 'Y') | (1u << 31)), "GREY");  // big-endian marker dropped
  EXPECT_EQ(fourccText(0x01020304u), "????");
  for (PixelFormat f : kPixelFormats) {
    ASSERT_TRUE(pixelFormatFromFourcc(fourccOf(f)).has_value());
    EXPECT_EQ(*pixelFormatFromFourcc(fourccOf(f)), f);
  }
  EXPECT_EQ(pixelFormatFromFourcc(makeFourcc('J', 'P', 'E', 'G')), PixelFormat::Mjpeg);
  EXPECT_FALSE(pixelFormatFromFourcc(makeFourcc('B', 'A', '8', '1')).has_value());  // Bayer: not read
  EXPECT_FALSE(pixelFormatFromFourcc(makeFourcc('H', '2', '6', '4')).has_value());
}

TEST(PixelFormat, PlanarLumaIsCheapestAndJpegDearest) {
  EXPECT_TRUE(lumaInPlace(PixelFormat::Grey));
  EXPECT_TRUE(lumaInPlace(PixelFormat::Nv12));
  EXPECT_TRUE(lumaInPlace(PixelFormat::Yvu420));
  EXPECT_FALSE(lumaInPlace(PixelFormat::Yuyv));
  EXPECT_FALSE(lumaInPlace(PixelFormat::Mjpeg));
  EXPECT_LT(conversionCost(PixelFormat::Grey), conversionCost(PixelFormat::Yuyv));
  EXPECT_LT(conversionCost(PixelFormat::Yuyv), conversionCost(PixelFormat::Rgb24));
  EXPECT_LT(conversionCost(PixelFormat::Rgb24), conversionCost(PixelFormat::Mjpeg));
}

TEST(PixelFormat, BytesNeededReachTheLastLumaSample) {
  EXPECT_EQ(minimumBytesPerLine(PixelFormat::Yuyv, 7), 14u);
  EXPECT_EQ(minimumBytesPerLine(PixelFormat::Bgr24, 7), 21u);
  EXPECT_EQ(minimumBytesPerLine(PixelFormat::Nv12, 7), 7u);
  EXPECT_EQ(bytesNeeded({PixelFormat::Grey, 7, 5, 10}), 4u * 10u + 7u);
  EXPECT_EQ(bytesNeeded({PixelFormat::Yuyv, 6, 3, 15}), 2u * 15u + 12u);
  EXPECT_EQ(bytesNeeded({PixelFormat::Mjpeg, 640, 480, 0}), 0u);
}

// Every raw format, odd line strides (and odd widths where the format allows them).
class RawFormat : public ::testing::TestWithParam<PixelFormat> {};

TEST_P(RawFormat, GivesTheLumaExactlyWithOddStrides) {
  const PixelFormat format = GetParam();
  const bool packed422 = format == PixelFormat::Yuyv || format == PixelFormat::Uyvy;
  for (const int width : {packed422 ? 6 : 7, packed422 ? 10 : 13}) {
    for (const std::size_t padding : {std::size_t{0}, std::size_t{3}, std::size_t{17}}) {
      SCOPED_TRACE(std::string(pixelFormatName(format)) + " width " + std::to_string(width) + " padding " +
                   std::to_string(padding));
      const int height = 5;
      TestBuffer t = makeBuffer(format, width, height, padding);
      cv::Mat scratch, grey;
      std::string error;
      ASSERT_EQ(bufferToGrey(t.layout, t.bytes.data(), t.bytes.size(), scratch, grey, error), Status::Ok) << error;
      ASSERT_EQ(grey.type(), CV_8UC1);
      ASSERT_EQ(grey.size(), cv::Size(width, height));
      EXPECT_EQ(cv::norm(grey, expectedGrey(width, height), cv::NORM_INF), 0.0);
      const bool inside = grey.data >= t.bytes.data() && grey.data < t.bytes.data() + t.bytes.size();
      if (lumaInPlace(format)) {
        EXPECT_TRUE(inside) << "the luma plane should be used where it lies";
        EXPECT_EQ(grey.data, t.bytes.data());
        EXPECT_EQ(grey.step[0], t.layout.bytes_per_line);
      } else {
        EXPECT_FALSE(inside);
        EXPECT_EQ(grey.data, scratch.data);
        // The next frame reuses the conversion buffer.
        const std::uint8_t* before = scratch.data;
        grey.release();
        ASSERT_EQ(bufferToGrey(t.layout, t.bytes.data(), t.bytes.size(), scratch, grey, error), Status::Ok);
        EXPECT_EQ(scratch.data, before);
      }
    }
  }
}

TEST_P(RawFormat, RefusesTruncatedBuffersAndShortStrides) {
  const PixelFormat format = GetParam();
  TestBuffer t = makeBuffer(format, 8, 4, 2);
  cv::Mat scratch, grey = cv::Mat(3, 3, CV_8UC1);
  std::string error;
  const std::size_t needed = bytesNeeded(t.layout);
  EXPECT_EQ(bufferToGrey(t.layout, t.bytes.data(), needed, scratch, grey, error), Status::Ok);
  EXPECT_EQ(bufferToGrey(t.layout, t.bytes.data(), needed - 1, scratch, grey, error), Status::EmptyFrame);
  EXPECT_TRUE(grey.empty());
  EXPECT_NE(error.find("truncated"), std::string::npos) << error;
  BufferLayout narrow = t.layout;
  narrow.bytes_per_line = minimumBytesPerLine(format, narrow.width) - 1;
  EXPECT_EQ(bufferToGrey(narrow, t.bytes.data(), t.bytes.size(), scratch, grey, error), Status::EmptyFrame);
  EXPECT_NE(error.find("stride"), std::string::npos) << error;
  BufferLayout empty = t.layout;
  empty.height = 0;
  EXPECT_EQ(bufferToGrey(empty, t.bytes.data(), t.bytes.size(), scratch, grey, error), Status::EmptyFrame);
  EXPECT_EQ(bufferToGrey(t.layout, nullptr, t.bytes.size(), scratch, grey, error), Status::EmptyFrame);
  EXPECT_EQ(bufferToGrey(t.layout, t.bytes.data(), 0, scratch, grey, error), Status::EmptyFrame);
}

INSTANTIATE_TEST_SUITE_P(AllRaw, RawFormat,
                         ::testing::Values(PixelFormat::Grey, PixelFormat::Yuyv, PixelFormat::Uyvy, PixelFormat::Nv12,
                                           PixelFormat::Nv21, PixelFormat::Yuv420, PixelFormat::Yvu420,
                                           PixelFormat::Rgb24, PixelFormat::Bgr24),
                         [](const auto& info) {
                           std::string name(pixelFormatName(info.param));
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

TEST(PixelFormat, RgbAndBgrUseTheItuWeightsInTheirOwnChannelOrder) {
  // Pure primaries: 0.299 * 255 = 76.2, 0.587 * 255 = 149.7, 0.114 * 255 = 29.1.
  const std::uint8_t pixels[] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255, 0, 0, 0, 9, 9, 9};
  cv::Mat scratch, grey;
  std::string error;
  ASSERT_EQ(bufferToGrey({PixelFormat::Rgb24, 6, 1, 18}, pixels, sizeof pixels, scratch, grey, error), Status::Ok);
  const std::vector<int> rgb_expected{76, 150, 29, 255, 0, 9};
  for (int x = 0; x < 6; ++x) EXPECT_EQ(grey.at<std::uint8_t>(0, x), rgb_expected[static_cast<std::size_t>(x)]) << x;
  ASSERT_EQ(bufferToGrey({PixelFormat::Bgr24, 6, 1, 18}, pixels, sizeof pixels, scratch, grey, error), Status::Ok);
  const std::vector<int> bgr_expected{29, 150, 76, 255, 0, 9};
  for (int x = 0; x < 6; ++x) EXPECT_EQ(grey.at<std::uint8_t>(0, x), bgr_expected[static_cast<std::size_t>(x)]) << x;
}

// A smooth image JPEG reproduces closely: the grey image decoded straight from it.
cv::Mat smoothImage(int width, int height) {
  cv::Mat m(height, width, CV_8UC1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) m.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(40 + x + y);
  return m;
}

TEST(PixelFormat, MotionJpegIsDecodedToGrey) {
  const cv::Mat original = smoothImage(64, 48);
  std::vector<std::uint8_t> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", original, jpeg, {cv::IMWRITE_JPEG_QUALITY, 95}));
  cv::Mat scratch, grey;
  std::string error;
  // The layout's size and stride do not matter for JPEG: the image carries its own.
  ASSERT_EQ(bufferToGrey({PixelFormat::Mjpeg, 64, 48, 0}, jpeg.data(), jpeg.size(), scratch, grey, error), Status::Ok)
      << error;
  ASSERT_EQ(grey.type(), CV_8UC1);
  ASSERT_EQ(grey.size(), original.size());
  EXPECT_LE(cv::norm(grey, original, cv::NORM_INF), 3.0);
  const std::uint8_t* before = scratch.data;
  ASSERT_EQ(bufferToGrey({PixelFormat::Mjpeg, 64, 48, 0}, jpeg.data(), jpeg.size(), scratch, grey, error), Status::Ok);
  EXPECT_EQ(scratch.data, before);  // decoded into the same memory
}

// Removes every DHT (Huffman table) segment, as UVC cameras send Motion-JPEG.
std::vector<std::uint8_t> withoutHuffmanTables(const std::vector<std::uint8_t>& jpeg) {
  std::vector<std::uint8_t> out(jpeg.begin(), jpeg.begin() + 2);  // SOI
  std::size_t i = 2;
  while (i + 4 <= jpeg.size() && jpeg[i] == 0xFF) {
    const std::uint8_t marker = jpeg[i + 1];
    const std::size_t length = (static_cast<std::size_t>(jpeg[i + 2]) << 8) | jpeg[i + 3];
    if (marker == 0xDA) break;  // start of scan: the rest is entropy-coded data
    if (marker != 0xC4) out.insert(out.end(), jpeg.begin() + static_cast<std::ptrdiff_t>(i),
                                   jpeg.begin() + static_cast<std::ptrdiff_t>(i + 2 + length));
    i += 2 + length;
  }
  out.insert(out.end(), jpeg.begin() + static_cast<std::ptrdiff_t>(i), jpeg.end());
  return out;
}

TEST(PixelFormat, MotionJpegWithoutHuffmanTablesDecodesTheSame) {
  const cv::Mat original = smoothImage(32, 24);
  std::vector<std::uint8_t> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", original, jpeg, {cv::IMWRITE_JPEG_QUALITY, 90}));  // standard tables
  const std::vector<std::uint8_t> bare = withoutHuffmanTables(jpeg);
  ASSERT_LT(bare.size(), jpeg.size());
  cv::Mat scratch_full, full, scratch_bare, decoded;
  std::string error;
  ASSERT_EQ(bufferToGrey({PixelFormat::Mjpeg, 32, 24, 0}, jpeg.data(), jpeg.size(), scratch_full, full, error),
            Status::Ok);
  ASSERT_EQ(bufferToGrey({PixelFormat::Mjpeg, 32, 24, 0}, bare.data(), bare.size(), scratch_bare, decoded, error),
            Status::Ok)
      << error;
  EXPECT_EQ(cv::norm(full, decoded, cv::NORM_INF), 0.0);
}

TEST(PixelFormat, DamagedMotionJpegIsAnEmptyFrame) {
  const std::uint8_t garbage[] = {0xFF, 0xD8, 0x00, 0x11, 0x22, 0x33, 0x44};
  cv::Mat scratch, grey = cv::Mat(2, 2, CV_8UC1);
  std::string error;
  EXPECT_EQ(bufferToGrey({PixelFormat::Mjpeg, 64, 48, 0}, garbage, sizeof garbage, scratch, grey, error),
            Status::EmptyFrame);
  EXPECT_TRUE(grey.empty());
  EXPECT_NE(error.find("Motion-JPEG"), std::string::npos);
}

}  // namespace
}  // namespace imagepro
