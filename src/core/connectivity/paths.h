#pragma once
// The output of the connectivity analysis (thesis 2.5): the edge pixels regrouped so
// that every 8-connected path is one contiguous run of `pixels`.
// Path i is pixels[starts[i] .. starts[i + 1]); starts has pathCount() + 1 entries.
#include <cstdint>
#include <span>
#include <vector>

#include "core/common/contract.h"
#include "core/edges/edge_list.h"

namespace imagepro {

struct Paths {
  std::vector<EdgePixel> pixels;
  std::vector<std::uint32_t> starts{0};

  std::size_t pathCount() const { return starts.size() - 1; }
  std::span<const EdgePixel> path(std::size_t i) const {
    IMAGEPRO_EXPECTS(i + 1 < starts.size(), "path index below pathCount()");
    IMAGEPRO_EXPECTS(starts[i] <= starts[i + 1] && starts[i + 1] <= pixels.size(), "path bounds inside the pixels");
    return {pixels.data() + starts[i], pixels.data() + starts[i + 1]};
  }
  void clear() {
    pixels.clear();
    starts.assign(1, 0);
  }
};

}  // namespace imagepro
