#pragma once
// The largest image ImagePro accepts, from the camera model, a V4L2 format or a frame
// to allocate. A V4L2 format carries 32-bit sizes, but the largest sensors its drivers
// stream from stay well under 16384 pixels a side; and the pipeline holds about 16
// bytes per pixel in its buffers (grey, binary, edge and index images, the crop), so
// 64 megapixels keep one frame's working set near 1 GB. A size beyond either is
// refused by name before anything is allocated, instead of failing gigabytes later.
#include <cstdint>
#include <string>

namespace imagepro {

inline constexpr std::int64_t kMaxImageSide = 16384;
inline constexpr std::int64_t kMaxImagePixels = std::int64_t{64} << 20;

// Empty when width x height (each at least 1) is within the bounds above; otherwise
// the problem in words, e.g. "100000x100000 is more than 16384 pixels a side".
std::string imageSizeProblem(std::int64_t width, std::int64_t height);

}  // namespace imagepro
