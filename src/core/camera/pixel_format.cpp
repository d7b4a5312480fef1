#include "core/camera/pixel_format.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace imagepro {

namespace {

// Bytes per pixel of the first plane, as stored in a line.
std::size_t lineBytesPerPixel(PixelFormat format) {
  switch (format) {
    case PixelFormat::Yuyv:
    case PixelFormat::Uyvy: return 2;
    case PixelFormat::Rgb24:
    case PixelFormat::Bgr24: return 3;
    case PixelFormat::Mjpeg: return 0;
    default: return 1;
  }
}

Status fail(std::string& error, cv::Mat& grey, std::string message) {
  grey.release();
  error = std::move(message);
  return Status::EmptyFrame;
}

}  // namespace

std::uint32_t fourccOf(PixelFormat format) {
  switch (format) {
    case PixelFormat::Grey: return makeFourcc('G', 'R', 'E', 'Y');
    case PixelFormat::Yuyv: return makeFourcc('Y', 'U', 'Y', 'V');
    case PixelFormat::Uyvy: return makeFourcc('U', 'Y', 'V', 'Y');
    case PixelFormat::Nv12: return makeFourcc('N', 'V', '1', '2');
    case PixelFormat::Nv21: return makeFourcc('N', 'V', '2', '1');
    case PixelFormat::Yuv420: return makeFourcc('Y', 'U', '1', '2');
    case PixelFormat::Yvu420: return makeFourcc('Y', 'V', '1', '2');
    case PixelFormat::Mjpeg: return makeFourcc('M', 'J', 'P', 'G');
    case PixelFormat::Rgb24: return makeFourcc('R', 'G', 'B', '3');
    case PixelFormat::Bgr24: return makeFourcc('B', 'G', 'R', '3');
  }
  return 0;
}

std::optional<PixelFormat> pixelFormatFromFourcc(std::uint32_t fourcc) {
  if (fourcc == makeFourcc('J', 'P', 'E', 'G')) return PixelFormat::Mjpeg;
  for (PixelFormat f : kPixelFormats)
    if (fourccOf(f) == fourcc) return f;
  return std::nullopt;
}

std::string fourccText(std::uint32_t fourcc) {
  std::string text(4, '?');
  for (int i = 0; i < 4; ++i) {
    const auto c = static_cast<char>((fourcc >> (8 * i)) & (i == 3 ? 0x7f : 0xff));
    if (c >= 0x20 && c < 0x7f) text[static_cast<std::size_t>(i)] = c;
  }
  return text;
}

std::string_view pixelFormatName(PixelFormat format) {
  switch (format) {
    case PixelFormat::Grey: return "grey 8-bit";
    case PixelFormat::Yuyv: return "YUYV 4:2:2";
    case PixelFormat::Uyvy: return "UYVY 4:2:2";
    case PixelFormat::Nv12: return "NV12 4:2:0";
    case PixelFormat::Nv21: return "NV21 4:2:0";
    case PixelFormat::Yuv420: return "YUV 4:2:0 planar";
    case PixelFormat::Yvu420: return "YVU 4:2:0 planar";
    case PixelFormat::Mjpeg: return "Motion-JPEG";
    case PixelFormat::Rgb24: return "RGB 24-bit";
    case PixelFormat::Bgr24: return "BGR 24-bit";
  }
  return "?";
}

bool lumaInPlace(PixelFormat format) { return conversionCost(format) == 0; }

int conversionCost(PixelFormat format) {
  switch (format) {
    case PixelFormat::Grey:
    case PixelFormat::Nv12:
    case PixelFormat::Nv21:
    case PixelFormat::Yuv420:
    case PixelFormat::Yvu420: return 0;
    case PixelFormat::Yuyv:
    case PixelFormat::Uyvy: return 1;
    case PixelFormat::Rgb24:
    case PixelFormat::Bgr24: return 2;
    case PixelFormat::Mjpeg: return 3;
  }
  return 3;
}

std::size_t minimumBytesPerLine(PixelFormat format, int width) {
  return width <= 0 ? 0 : lineBytesPerPixel(format) * static_cast<std::size_t>(width);
}

std::size_t bytesNeeded(const BufferLayout& layout) {
  if (layout.format == PixelFormat::Mjpeg || layout.width <= 0 || layout.height <= 0) return 0;
  return layout.bytes_per_line * static_cast<std::size_t>(layout.height - 1) +
         minimumBytesPerLine(layout.format, layout.width);
}

Status bufferToGrey(const BufferLayout& layout, const std::uint8_t* data, std::size_t bytes_used, cv::Mat& scratch,
                    cv::Mat& grey, std::string& error) {
  if (data == nullptr || bytes_used == 0) return fail(error, grey, "empty camera buffer");
  if (layout.format == PixelFormat::Mjpeg) {
    // OpenCV's JPEG reader supplies the standard Huffman tables that Motion-JPEG
    // frames of UVC cameras leave out.
    const cv::Mat encoded(1, static_cast<int>(bytes_used), CV_8UC1, const_cast<std::uint8_t*>(data));
    try {
      cv::imdecode(encoded, cv::IMREAD_GRAYSCALE, &scratch);
    } catch (const cv::Exception&) {
      scratch.release();
    }
    if (scratch.empty() || scratch.type() != CV_8UC1) return fail(error, grey, "undecodable Motion-JPEG frame");
    grey = scratch;
    return Status::Ok;
  }
  if (layout.width <= 0 || layout.height <= 0) return fail(error, grey, "camera frame of zero size");
  if (layout.bytes_per_line < minimumBytesPerLine(layout.format, layout.width))
    return fail(error, grey,
                "line stride " + std::to_string(layout.bytes_per_line) + " too small for " +
                    std::to_string(layout.width) + " pixels of " + std::string(pixelFormatName(layout.format)));
  const std::size_t needed = bytesNeeded(layout);
  if (bytes_used < needed)
    return fail(error, grey,
                "truncated camera frame: " + std::to_string(bytes_used) + " of " + std::to_string(needed) + " bytes");

  auto* pixels = const_cast<std::uint8_t*>(data);  // cv::Mat headers are not const-aware; nothing writes here
  const int h = layout.height;
  const int w = layout.width;
  const std::size_t step = layout.bytes_per_line;
  switch (layout.format) {
    case PixelFormat::Grey:
    case PixelFormat::Nv12:
    case PixelFormat::Nv21:
    case PixelFormat::Yuv420:
    case PixelFormat::Yvu420:
      grey = cv::Mat(h, w, CV_8UC1, pixels, step);
      return Status::Ok;
    case PixelFormat::Yuyv:
    case PixelFormat::Uyvy: {
      // Every second byte; a plain loop the compiler vectorises beats cv::extractChannel.
      scratch.create(h, w, CV_8UC1);
      const std::size_t first = layout.format == PixelFormat::Yuyv ? 0 : 1;
      for (int y = 0; y < h; ++y) {
        const std::uint8_t* src = data + static_cast<std::size_t>(y) * step + first;
        std::uint8_t* dst = scratch.ptr<std::uint8_t>(y);
        for (int x = 0; x < w; ++x) dst[x] = src[2 * x];
      }
      break;
    }
    case PixelFormat::Rgb24:
    case PixelFormat::Bgr24:
      cv::cvtColor(cv::Mat(h, w, CV_8UC3, pixels, step), scratch,
                   layout.format == PixelFormat::Rgb24 ? cv::COLOR_RGB2GRAY : cv::COLOR_BGR2GRAY);
      break;
    case PixelFormat::Mjpeg:
      break;  // handled above
  }
  grey = scratch;
  return Status::Ok;
}

}  // namespace imagepro
