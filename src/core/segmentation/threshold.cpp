#include "core/segmentation/threshold.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "core/segmentation/image_buffer.h"

namespace imagepro {

namespace {

// Every class sum below is an exact integer: with fewer than 2^32 pixels, n * sum(g^2 h)
// stays below 2^80 and AT-Orig's centred sums below 2^120.
using Wide = __int128;
constexpr std::int64_t kMaxPixels = std::int64_t{1} << 32;
// Below 2^23 pixels AT-Mod's sums fit 64 bits and every class count a float exactly.
constexpr std::int64_t kMaxPixelsNarrow = std::int64_t{1} << 23;

// One class's term of eq. 2.4, P ln (sigma / P)^2, from its pixel count P and its
// scatter P^2 sigma^2 > 0, rounded to double. Both variants evaluate J(t) = term of
// class 1 + term of class 2 by this one expression.
double classTerm(std::int64_t count, double scatter) {
  const double p = static_cast<double>(count);
  return p * std::log(scatter / (p * p * p * p));  // (sigma/P)^2 = P^2 sigma^2 / P^4
}

// The same, false when J is undefined: an empty class or zero variance.
bool classTerm(std::int64_t count, Wide scatter, double& term) {
  if (count == 0 || scatter <= 0) return false;
  term = classTerm(count, static_cast<double>(scatter));
  return true;
}

// The smallest J(t) seen, and the smallest t that reached it.
struct Minimum {
  int t = -1;
  double j = 0.0;
  void offer(int candidate, double j_candidate) {
    if (t < 0 || j_candidate < j) {
      t = candidate;
      j = j_candidate;
    }
  }
};

// For histograms on which J is defined for no t (two or three populated grey levels):
// split at the widest gap between neighbouring populated levels, the first on a tie.
Status splitAtWidestGap(const Histogram& h, int& t) {
  int previous = -1;
  int widest = 0;
  for (int g = 0; g < 256; ++g) {
    if (h[g] == 0) continue;
    if (previous >= 0 && g - previous > widest) {
      widest = g - previous;
      t = previous;
    }
    previous = g;
  }
  return widest > 0 ? Status::Ok : Status::ThresholdUndefined;
}

Status result(const Histogram& h, const Minimum& best, int& t) {
  if (best.t < 0) return splitAtWidestGap(h, t);
  t = best.t;
  return Status::Ok;
}

// Eqs. 2.5-2.7 over the grey levels [a, b], from scratch. Eq. 2.7's centred sum is
// scaled by P^2 to stay in integers: sum (P g - sum g h)^2 h = P^3 sigma^2.
bool classTermFromScratch(const Histogram& h, int a, int b, double& term) {
  std::int64_t count = 0;
  std::int64_t first = 0;
  for (int g = a; g <= b; ++g) {
    count += h[g];                     // eq. 2.5
    first += std::int64_t{g} * h[g];   // eq. 2.6, times P
  }
  if (count == 0) return false;
  Wide centred = 0;
  for (int g = a; g <= b; ++g) {
    const Wide deviation = Wide{count} * g - first;  // P (g - mu)
    centred += deviation * deviation * h[g];         // eq. 2.7, times P^3
  }
  return classTerm(count, centred / count, term);
}

// AT-Mod for histograms of 2^23 pixels or more, in 128-bit products: the class sums
// P, P mu, P (sigma^2 + mu^2) carried from t to t + 1 (eqs. 2.13-2.15) with F and S
// (eqs. 2.16-2.17), J(t) in double for every t.
Status thresholdAtModWide(const Histogram& h, int& t) {
  std::int64_t count = 0, first = 0, second = 0;  // over the whole histogram
  for (int g = 0; g < 256; ++g) {
    count += h[g];
    first += std::int64_t{g} * h[g];
    second += std::int64_t{g} * g * h[g];
  }
  Minimum best;
  std::int64_t count1 = 0, first1 = 0, second1 = 0;  // class 1 = [0, t]
  for (int candidate = 0; candidate <= 255; ++candidate) {
    // An empty level leaves both classes as they were for t - 1: the same J, which
    // never beats the smaller t.
    if (h[candidate] == 0) continue;
    const std::int64_t f = std::int64_t{candidate} * h[candidate];  // F, eq. 2.16
    count1 += h[candidate];
    first1 += f;
    second1 += candidate * f;  // S, eq. 2.17
    const std::int64_t count2 = count - count1, first2 = first - first1, second2 = second - second1;
    // Eq. 2.12 times P^2: P^2 sigma^2 = P sum(g^2 h) - (sum g h)^2.
    double j1 = 0.0;
    double j2 = 0.0;
    if (classTerm(count1, Wide{count1} * second1 - Wide{first1} * first1, j1) &&
        classTerm(count2, Wide{count2} * second2 - Wide{first2} * first2, j2))
      best.offer(candidate, j1 + j2);  // eq. 2.4
  }
  return result(h, best, t);
}

// ln x in single precision for the x = P^2 sigma^2 / P^4 of a class of 2 to 2^23 pixels
// (over at least two grey levels), which lie in (2^-70, 2^12): P^2 sigma^2 >= P - 1 and
// sigma <= 127.5. Plain arithmetic on the bits of x, so that a loop of it vectorises:
// x = 2^e m with m in [sqrt(1/2), sqrt 2), and ln m = 2 atanh s = 2 (s + s^3/3 + s^5/5 + ...)
// with s = (m - 1)/(m + 1), |s| < 0.1716. The series stops after s^3/3.
inline float cheapLog(float x) {
  constexpr std::int32_t kSqrtHalf = 0x3F3504F3;  // the bits of sqrt(1/2)
  const std::int32_t bits = std::bit_cast<std::int32_t>(x);
  const std::int32_t e = (bits - kSqrtHalf) >> 23;  // octaves of x above sqrt(1/2)
  const float m = std::bit_cast<float>(bits - e * (1 << 23));
  const float s = (m - 1.0f) / (m + 1.0f);
  return static_cast<float>(e) * std::numbers::ln2_v<float> + 2.0f * s * (1.0f + s * s * (1.0f / 3.0f));
}

// How far cheap J, below, may be from J as classTerm evaluates it, per pixel. With
// u = 2^-24, |e| <= 70, |ln x| < 48.6 and float values below 64 in cheapLog:
//   6.14e-5  the series' remainder, 2 |s|^5 / (5 (1 - s^2))
//   1.1e-7   s, s^2 and the series in float, (m - 1) being exact: about 5 u |ln m|
//   4.0e-6   e ln 2 with ln 2 rounded, the product and the sum: 70 * 1.9e-9 + 2 * 2^-19
//   3.6e-7   x from P and P^2 sigma^2 in float: 6 u
//   5.9e-6   J = P1 L1 + P2 L2 in float: 2 u * 48.9
//   2e-14    classTerm's own rounding and std::log's 1 ulp, in double
// in all < 7.2e-5. kCheapError = 1e-4 leaves room for the rounding of the float sum
// that compares with it.
constexpr float kCheapError = 1.0e-4f;

}  // namespace

Status thresholdAtOrig(const Histogram& h, int& t) {
  std::int64_t pixels = 0;
  for (const auto count : h) pixels += count;
  if (pixels >= kMaxPixels) return Status::ThresholdUndefined;
  Minimum best;
  for (int candidate = 0; candidate <= 255; ++candidate) {  // eq. 2.10
    double j1 = 0.0;
    double j2 = 0.0;
    if (classTermFromScratch(h, 0, candidate, j1) && classTermFromScratch(h, candidate + 1, 255, j2))
      best.offer(candidate, j1 + j2);  // eq. 2.4
  }
  return result(h, best, t);
}

Status thresholdAtMod(const Histogram& h, int& t) {
  // J is defined exactly for t in [lo, hi]: from the second populated grey level up
  // (class 1 holds two levels) to below the second-highest (so does class 2).
  int lo = 0, second_highest = 255;
  for (int seen = 0; lo < 256; ++lo)
    if (h[lo] != 0 && ++seen == 2) break;
  for (int seen = 0; second_highest >= 0; --second_highest)
    if (h[second_highest] != 0 && ++seen == 2) break;
  const int hi = second_highest - 1;
  if (hi < lo) {
    std::int64_t pixels = 0;
    for (const auto count : h) pixels += count;
    return pixels < kMaxPixels ? splitAtWidestGap(h, t) : Status::ThresholdUndefined;
  }

  // Each class's scatter P^2 sigma^2 carried from one grey level to the next in exact
  // integers: eqs. 2.13-2.15 times P(t+1)^2 give
  //   P^2 sigma^2 (t+1) = P^2 sigma^2 (t) + h(t+1) sum_{g<=t} h(g) (t + 1 - g)^2,
  // and that sum about t + 1 follows from the one about t and the first moment about t:
  //   sum h (t+1-g)^2 = sum h (t-g)^2 + 2 sum h (t-g) + P.
  // Class 1 = [0, t] grows upwards, class 2 = [t+1, 255] downwards. Below 2^23 pixels
  // every term stays below 2^62; above, the unsigned sums wrap harmlessly and the
  // histogram goes to the wide path instead.
  std::array<std::int32_t, 256> count1;
  std::array<std::int64_t, 256> scatter1, scatter2;
  std::array<float, 256> x1, x2, cheap;
  std::uint64_t n = 0, moment = 0, spread = 0, scatter = 0;  // P, sum h |g - r|, sum h (g - r)^2
  const auto join = [&](int g) {  // the class's reference grey level r is g
    scatter += h[g] * spread;
    n += h[g];
  };
  const auto next = [&] {  // r moves one grey level away from the class
    spread += 2 * moment + n;
    moment += n;
  };
  for (int g = 0; g < lo; ++g) {
    join(g);
    next();
  }
  for (int c = lo; c <= hi; ++c) {
    join(c);
    count1[c] = static_cast<std::int32_t>(n);
    scatter1[c] = static_cast<std::int64_t>(scatter);
    x1[c] = static_cast<float>(scatter1[c]);
    next();
  }
  const std::uint64_t below = n;  // the pixels at or below hi
  n = moment = spread = scatter = 0;
  for (int g = 255; g > hi; --g) {
    join(g);
    next();
  }
  const auto count = static_cast<std::int64_t>(below + n);
  if (count >= kMaxPixels) return Status::ThresholdUndefined;
  if (count >= kMaxPixelsNarrow) return thresholdAtModWide(h, t);
  for (int c = hi; c >= lo; --c) {
    scatter2[c] = static_cast<std::int64_t>(scatter);
    x2[c] = static_cast<float>(scatter2[c]);
    join(c);
    next();
  }

  // Stage 1: J(t) of eq. 2.4 for every candidate, in float with cheapLog.
  const auto pixels = static_cast<float>(count);
  for (int c = lo; c <= hi; ++c) {
    const auto p1 = static_cast<float>(count1[c]);
    const float p2 = pixels - p1;
    const float p1_squared = p1 * p1, p2_squared = p2 * p2;
    cheap[c] = p1 * cheapLog(x1[c] / (p1_squared * p1_squared)) + p2 * cheapLog(x2[c] / (p2_squared * p2_squared));
  }
  // Read in blocks of four grey levels [lo4, hi4]; the levels outside [lo, hi] never count.
  const int lo4 = lo & ~3, hi4 = hi | 3;
  constexpr float kNever = std::numeric_limits<float>::infinity();
  for (int c = lo4; c < lo; ++c) cheap[c] = kNever;
  for (int c = hi + 1; c <= hi4; ++c) cheap[c] = kNever;
  std::array<float, 4> lane = {kNever, kNever, kNever, kNever};
  for (int block = lo4; block <= hi4; block += 4)
    for (int k = 0; k < 4; ++k) lane[k] = std::min(cheap[block + k], lane[k]);
  const float cheapest = std::min(std::min(lane[0], lane[1]), std::min(lane[2], lane[3]));

  // Stage 2: J(t) by classTerm, as AT-Orig evaluates it, for the candidates that can
  // still be the smallest. Cheap J is within B = kCheapError * P of J for every t, so
  // a t with cheap J above cheapest + 2 B has J above the J of the cheapest t: it is
  // neither the minimum nor tied with it. The others are taken in order, ties to the
  // smallest t as before.
  const float keep = cheapest + 2.0f * kCheapError * pixels;
  Minimum best;
  for (int block = lo4; block <= hi4; block += 4) {
    const float j0 = cheap[block], j1 = cheap[block + 1], j2 = cheap[block + 2], j3 = cheap[block + 3];
    if (std::min(std::min(j0, j1), std::min(j2, j3)) > keep) continue;
    for (int c = block; c < block + 4; ++c) {
      if (cheap[c] > keep || h[c] == 0) continue;  // an empty level repeats J(t - 1)
      best.offer(c, classTerm(count1[c], static_cast<double>(scatter1[c])) +
                        classTerm(count - count1[c], static_cast<double>(scatter2[c])));  // eq. 2.4
    }
  }
  return result(h, best, t);
}

Status computeThreshold(const ThresholdOptions& o, const Histogram& h, int& t) {
  switch (o.method) {
    case ThresholdMethod::Manual:
      if (o.manual_value < 0 || o.manual_value > 255) return Status::InvalidSettings;
      t = o.manual_value;
      return Status::Ok;
    case ThresholdMethod::AtOrig: return thresholdAtOrig(h, t);
    case ThresholdMethod::AtMod: return thresholdAtMod(h, t);
    case ThresholdMethod::None: break;
  }
  return Status::InvalidSettings;
}

void binarize(const cv::Mat& grey, int t, cv::Mat& binary) {
  if (grey.empty() || grey.type() != CV_8UC1) {
    binary = cv::Mat();
    return;
  }
  // Only exact in-place use may share grey's allocation; any other view of it would be
  // overwritten while it is read.
  const bool in_place = binary.data == grey.data && binary.size() == grey.size();
  if (!binary.empty() && binary.datastart == grey.datastart && !in_place) binary = cv::Mat();
  reuseBuffer(binary, grey.size(), allocationSize(grey));
  cv::threshold(grey, binary, t, 255, cv::THRESH_BINARY);  // 255 where grey > t
}

}  // namespace imagepro
