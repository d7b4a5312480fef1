#include "core/common/image_limits.h"

namespace imagepro {

std::string imageSizeProblem(std::int64_t width, std::int64_t height) {
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (width < 1 || height < 1) return size + " has no pixels";
  if (width > kMaxImageSide || height > kMaxImageSide)
    return size + " is more than " + std::to_string(kMaxImageSide) + " pixels a side";
  if (width * height > kMaxImagePixels)
    return size + " is " + std::to_string(width * height / (1 << 20)) + " megapixels, more than the " +
           std::to_string(kMaxImagePixels >> 20) + " a frame may hold";
  return {};
}

}  // namespace imagepro
