#pragma once
// Captured camera buffers to 8-bit grey (thesis 2.2 and 5.2.1: the frame grabber
// delivers 8-bit grey frames, "Monochrome: Y8"). Today's V4L2 devices deliver grey,
// luma-chroma (4:2:2 packed, 4:2:0 planar), Motion-JPEG or RGB; all the pipeline needs
// is the luma. Planar formats keep the luma as one plane, so a frame is used in place
// as a cv::Mat header over the driver's buffer with the driver's line stride; the
// others cost one pass (luma copied out of packed 4:2:2, JPEG decoded straight to
// grey, RGB weighted with the ITU-R 601 coefficients as for image files).
// No V4L2 header is needed here: formats are named by their four-character codes.
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/common/status.h"

namespace imagepro {

enum class PixelFormat : std::uint8_t {
  Grey,    // 'GREY' 8-bit luma
  Yuyv,    // 'YUYV' packed 4:2:2, Y0 U Y1 V
  Uyvy,    // 'UYVY' packed 4:2:2, U Y0 V Y1
  Nv12,    // 'NV12' Y plane, then interleaved Cb Cr at half resolution
  Nv21,    // 'NV21' Y plane, then interleaved Cr Cb
  Yuv420,  // 'YU12' Y plane, then Cb and Cr planes (lines of half the Y stride)
  Yvu420,  // 'YV12' Y plane, then Cr and Cb planes
  Mjpeg,   // 'MJPG' (or 'JPEG') one JPEG image per buffer
  Rgb24,   // 'RGB3' R G B
  Bgr24,   // 'BGR3' B G R
};

inline constexpr PixelFormat kPixelFormats[] = {PixelFormat::Grey,   PixelFormat::Yuyv,   PixelFormat::Uyvy,
                                                PixelFormat::Nv12,   PixelFormat::Nv21,   PixelFormat::Yuv420,
                                                PixelFormat::Yvu420, PixelFormat::Mjpeg,  PixelFormat::Rgb24,
                                                PixelFormat::Bgr24};

constexpr std::uint32_t makeFourcc(char a, char b, char c, char d) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(a)) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(b)) << 8) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(c)) << 16) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(d)) << 24);
}

// The V4L2 code of a format ('JPEG' is read as Mjpeg but not produced here).
std::uint32_t fourccOf(PixelFormat format);
// nullopt for a format ImagePro cannot read.
std::optional<PixelFormat> pixelFormatFromFourcc(std::uint32_t fourcc);
// "YUYV"; unprintable bytes become '?'. A big-endian marker (bit 31) is dropped.
std::string fourccText(std::uint32_t fourcc);
std::string_view pixelFormatName(PixelFormat format);

// True when the luma is one plane of 8-bit samples, so a frame needs no copy.
bool lumaInPlace(PixelFormat format);
// Work per frame to get grey, used to choose between the formats a device offers:
// 0 in place, 1 one copying pass, 2 colour weighting, 3 JPEG decoding.
int conversionCost(PixelFormat format);

// Shape of one captured buffer as the driver reports it (VIDIOC_S_FMT / G_FMT).
struct BufferLayout {
  PixelFormat format = PixelFormat::Grey;
  int width = 0;
  int height = 0;
  // Bytes from one line of the first (luma or only) plane to the next; ignored for
  // Mjpeg. Drivers may pad lines, so this can exceed width x bytes per pixel.
  std::size_t bytes_per_line = 0;
};

// The smallest line stride the format allows at `width` (0 for Mjpeg).
std::size_t minimumBytesPerLine(PixelFormat format, int width);
// Bytes of a buffer read to make the grey frame: up to the last luma sample of the last
// line (0 for Mjpeg, whose size varies). A shorter buffer is a truncated frame.
std::size_t bytesNeeded(const BufferLayout& layout);

// The grey frame of one captured buffer of `bytes_used` bytes at `data`.
// In-place formats: `grey` becomes a header over `data` (no copy; it is valid only
// as long as the buffer). Others: converted into `scratch`, whose memory is reused
// from frame to frame, and `grey` shares `scratch`. Never throws: a bad layout, a
// truncated buffer or an undecodable JPEG gives EmptyFrame with `error` saying
// which; `grey` is then released. A JPEG of another size than the layout is kept at
// its own size (a driver may change it).
Status bufferToGrey(const BufferLayout& layout, const std::uint8_t* data, std::size_t bytes_used, cv::Mat& scratch,
                    cv::Mat& grey, std::string& error);

}  // namespace imagepro
