#include "core/segmentation/threshold.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>

#include "core/segmentation/image_buffer.h"

namespace imagepro {

namespace {

// Every class sum below is an exact integer: with fewer than 2^32 pixels, n * sum(g^2 h)
// stays below 2^80 and AT-Orig's centred sums below 2^120.
using Wide = __int128;
constexpr std::int64_t kMaxPixels = std::int64_t{1} << 32;

// One class's term of eq. 2.4, P ln (sigma / P)^2, from its pixel count P and its
// scatter P^2 sigma^2. False when J is undefined: an empty class or zero variance.
bool classTerm(std::int64_t count, Wide scatter, double& term) {
  if (count == 0 || scatter <= 0) return false;
  const double p = static_cast<double>(count);
  term = p * std::log(static_cast<double>(scatter) / (p * p * p * p));  // (sigma/P)^2 = P^2 sigma^2 / P^4
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
  std::array<std::int64_t, 256> first_moment;   // F, eq. 2.16
  std::array<std::int64_t, 256> second_moment;  // S, eq. 2.17
  std::int64_t count = 0, first = 0, second = 0;  // over the whole histogram
  for (int g = 0; g < 256; ++g) {
    first_moment[g] = std::int64_t{g} * h[g];
    second_moment[g] = g * first_moment[g];
    count += h[g];
    first += first_moment[g];
    second += second_moment[g];
  }
  if (count >= kMaxPixels) return Status::ThresholdUndefined;
  Minimum best;
  // Class 1 = [0, t] as P1, P1 mu1 and P1 (sigma1^2 + mu1^2); class 2 is the rest.
  std::int64_t count1 = 0, first1 = 0, second1 = 0;
  for (int candidate = 0; candidate <= 255; ++candidate) {
    // An empty level leaves both classes as they were for t - 1: the same J, which
    // never beats the smaller t (saves the logarithms on the empty ends of a histogram).
    if (h[candidate] == 0) continue;
    // Eqs. 2.13-2.15: grey level t joins class 1 and leaves class 2.
    count1 += h[candidate];
    first1 += first_moment[candidate];
    second1 += second_moment[candidate];
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
