#pragma once
// The output of edge detection (thesis 2.4): a list of edge pixels, each with the
// Sobel gradient of the binary image at that pixel (eqs. 2.19-2.20), ready for the
// connectivity analysis.
#include <cstdint>
#include <vector>

namespace imagepro {

struct EdgePixel {
  std::int16_t x = 0;   // column (u)
  std::int16_t y = 0;   // row (v)
  std::int16_t gx = 0;  // horizontal Sobel response on the 0/1 binary image
  std::int16_t gy = 0;  // vertical Sobel response
};

using EdgeList = std::vector<EdgePixel>;

}  // namespace imagepro
