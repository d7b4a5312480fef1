#include "core/segmentation/reduce.h"

#include <algorithm>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/segmentation/image_buffer.h"

namespace imagepro {

namespace {

// Factor 2, the common case (640 x 480), straight from the two rows: 16 outputs per step
// from 32 bytes of each row, the pairs summed in 16-bit lanes (even bytes masked, odd
// bytes shifted down). The scalar loop finishes the row, and does it all without SSE2.
void reduceRowPairBy2(const std::uint8_t* top, const std::uint8_t* bottom, int cols, std::uint8_t* dst) {
  int x = 0;
#if defined(__SSE2__)
  const __m128i low = _mm_set1_epi16(0x00FF), two = _mm_set1_epi16(2);
  auto sums = [&](const std::uint8_t* a, const std::uint8_t* b) {
    const __m128i va = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a));
    const __m128i vb = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b));
    const __m128i pairs = _mm_add_epi16(_mm_add_epi16(_mm_and_si128(va, low), _mm_srli_epi16(va, 8)),
                                        _mm_add_epi16(_mm_and_si128(vb, low), _mm_srli_epi16(vb, 8)));
    return _mm_srli_epi16(_mm_add_epi16(pairs, two), 2);
  };
  for (; x + 16 <= cols; x += 16) {
    const __m128i first = sums(top + 2 * x, bottom + 2 * x);
    const __m128i second = sums(top + 2 * x + 16, bottom + 2 * x + 16);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(dst + x), _mm_packus_epi16(first, second));
  }
#endif
  for (; x < cols; ++x) {
    const unsigned s = top[2 * x] + top[2 * x + 1] + bottom[2 * x] + bottom[2 * x + 1];
    dst[x] = static_cast<std::uint8_t>((s + 2) >> 2);
  }
}

// One reduced row from the column sums of its block's rows: each output the sum of K
// adjacent column sums, divided as reduceByBlockMean describes.
template <int K>
void blockSums(const std::uint16_t* sums, int cols, std::uint32_t n, std::uint32_t m, std::uint8_t* dst) {
  for (int x = 0; x < cols; ++x) {
    std::uint32_t sum = 0;
    for (int c = 0; c < K; ++c) sum += sums[x * K + c];
    dst[x] = static_cast<std::uint8_t>(((sum + n / 2) * m) >> 24);
  }
}

}  // namespace

int coarseFactor(int width) {
  const int factor = std::min(width / kCoarseWidthPx, kMaxReduceFactor);
  return factor >= 2 ? factor : 1;
}

void reduceByBlockMean(const cv::Mat& grey, int factor, cv::Mat& out, std::vector<std::uint16_t>& rowSums) {
  if (grey.empty() || grey.type() != CV_8UC1 || factor < 1 || factor > kMaxReduceFactor ||
      grey.cols / factor == 0 || grey.rows / factor == 0) {
    out = cv::Mat();
    return;
  }
  const int cols = grey.cols / factor, rows = grey.rows / factor;
  const int used = cols * factor;
  // Room for the frame grey is a view into: then every buffer sized after this image
  // (binarize, binarizeLocal) gets room for the full-size passes too.
  reuseBuffer(out, {cols, rows}, allocationSize(grey));
  if (factor == 2) {
    for (int y = 0; y < rows; ++y)
      reduceRowPairBy2(grey.ptr<std::uint8_t>(2 * y), grey.ptr<std::uint8_t>(2 * y + 1), cols, out.ptr<std::uint8_t>(y));
    return;
  }
  // Each row's column sums over the block's rows, then the block sums along it. A
  // division per pixel would cost more than the sums: the block's sum s (at most
  // 15 * 15 * 255 < 2^16) is divided by n = factor^2 as (s + n / 2) * m >> 24 with
  // m = ceil(2^24 / n), which rounds like the exact division for every such s (the
  // test checks all of them).
  const std::uint32_t n = static_cast<std::uint32_t>(factor * factor);
  const std::uint32_t m = ((1u << 24) + n - 1) / n;
  rowSums.resize(static_cast<std::size_t>(used));
  std::uint16_t* sums = rowSums.data();
  for (int y = 0; y < rows; ++y) {
    const std::uint8_t* first = grey.ptr<std::uint8_t>(y * factor);
    for (int x = 0; x < used; ++x) sums[x] = first[x];
    for (int r = 1; r < factor; ++r) {
      const std::uint8_t* row = grey.ptr<std::uint8_t>(y * factor + r);
      for (int x = 0; x < used; ++x) sums[x] = static_cast<std::uint16_t>(sums[x] + row[x]);
    }
    std::uint8_t* dst = out.ptr<std::uint8_t>(y);
    // The factors of the common frame widths with the block's width known to the compiler
    // (unrolled, in vector lanes where it can); any other in the plain loop.
    switch (factor) {
      case 3: blockSums<3>(sums, cols, n, m, dst); break;
      case 4: blockSums<4>(sums, cols, n, m, dst); break;
      case 6: blockSums<6>(sums, cols, n, m, dst); break;
      case 8: blockSums<8>(sums, cols, n, m, dst); break;
      default:
        for (int x = 0; x < cols; ++x) {
          std::uint32_t sum = 0;
          for (int c = 0; c < factor; ++c) sum += sums[x * factor + c];
          dst[x] = static_cast<std::uint8_t>(((sum + n / 2) * m) >> 24);
        }
    }
  }
}

}  // namespace imagepro
