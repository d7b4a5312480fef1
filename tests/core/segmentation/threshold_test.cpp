#include "core/segmentation/threshold.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <string>

namespace imagepro {
namespace {

// --- an independent reference: eqs. 2.4-2.7 evaluated directly in long double -------

struct ClassStats {
  long double count = 0, mean = 0, variance = 0;
  int levels = 0;  // populated grey levels
};

ClassStats classStats(const Histogram& h, int a, int b) {
  ClassStats s;
  long double sum = 0;
  for (int g = a; g <= b; ++g) {
    s.count += h[g];
    sum += static_cast<long double>(g) * h[g];
    if (h[g] != 0) ++s.levels;
  }
  if (s.count == 0) return s;
  s.mean = sum / s.count;
  long double centred = 0;
  for (int g = a; g <= b; ++g) centred += (g - s.mean) * (g - s.mean) * h[g];
  s.variance = centred / s.count;
  return s;
}

// J(t) of eq. 2.4, or nothing where a class is empty or has a single grey level.
std::optional<long double> referenceJ(const Histogram& h, int t) {
  const ClassStats c1 = classStats(h, 0, t), c2 = classStats(h, t + 1, 255);
  if (c1.levels < 2 || c2.levels < 2) return std::nullopt;
  return c1.count * std::log(c1.variance / (c1.count * c1.count)) +
         c2.count * std::log(c2.variance / (c2.count * c2.count));
}

// --- the same criterion as both variants evaluate it, from scratch ----------------------

// For every t, each class's count P, sum g h and sum g^2 h summed afresh, its scatter
// P^2 sigma^2 = P sum g^2 h - (sum g h)^2 exact, and eq. 2.4 in double as
// P ln(P^2 sigma^2 / P^4) per class. The smallest J wins, the smallest t on a tie;
// where no t has both classes of non-zero variance, the widest gap between populated
// levels (the first on a tie). 2^32 pixels or more: undefined.
struct Expected {
  Status status = Status::ThresholdUndefined;
  int t = -1;
};

Expected doubleEvaluation(const Histogram& h) {
  std::int64_t pixels = 0;
  for (const auto n : h) pixels += n;
  if (pixels >= (std::int64_t{1} << 32)) return {};
  const auto term = [&h](int a, int b) -> std::optional<double> {
    std::int64_t count = 0, first = 0, second = 0;
    for (int g = a; g <= b; ++g) {
      count += h[g];
      first += std::int64_t{g} * h[g];
      second += std::int64_t{g} * g * h[g];
    }
    const __int128 scatter = __int128{count} * second - __int128{first} * first;
    if (count == 0 || scatter <= 0) return std::nullopt;
    const double p = static_cast<double>(count);
    return p * std::log(static_cast<double>(scatter) / (p * p * p * p));
  };
  Expected e;
  double best = 0.0;
  for (int t = 0; t < 255; ++t) {
    const auto j1 = term(0, t), j2 = term(t + 1, 255);
    if (j1 && j2 && (e.t < 0 || *j1 + *j2 < best)) {
      e = {Status::Ok, t};
      best = *j1 + *j2;
    }
  }
  if (e.t >= 0) return e;
  int widest = 0;
  for (int a = 0, b = 1; b < 256; ++b) {
    if (h[b] == 0) continue;
    if (h[a] != 0 && b - a > widest) {
      widest = b - a;
      e = {Status::Ok, a};
    }
    a = b;
  }
  return e;
}

void expectTheDoubleEvaluation(const Histogram& h, const std::string& what) {
  const Expected expected = doubleEvaluation(h);
  int t = -7;
  ASSERT_EQ(thresholdAtMod(h, t), expected.status) << what;
  EXPECT_EQ(t, ok(expected.status) ? expected.t : -7) << what;
}

// AT-Mod gives the threshold of the double evaluation, both variants agree, and where J
// is defined anywhere the threshold minimises it.
void expectBothAgreeAndMinimise(const Histogram& h, const std::string& what) {
  expectTheDoubleEvaluation(h, what);
  int t_orig = -7, t_mod = -7;
  const Status s_orig = thresholdAtOrig(h, t_orig);
  const Status s_mod = thresholdAtMod(h, t_mod);
  ASSERT_EQ(s_orig, s_mod) << what;
  ASSERT_EQ(t_orig, t_mod) << what;
  if (!ok(s_orig)) {
    EXPECT_EQ(s_orig, Status::ThresholdUndefined) << what;
    EXPECT_EQ(t_orig, -7) << what << ": t changed on error";
    return;
  }
  ASSERT_GE(t_orig, 0) << what;
  ASSERT_LE(t_orig, 254) << what;
  std::optional<long double> best;
  for (int t = 0; t < 256; ++t)
    if (const auto j = referenceJ(h, t); j && (!best || *j < *best)) best = j;
  if (!best) return;  // the few-level fallback, tested separately
  const auto chosen = referenceJ(h, t_orig);
  ASSERT_TRUE(chosen.has_value()) << what << ": t = " << t_orig << " has J undefined";
  EXPECT_TRUE(std::isfinite(static_cast<double>(*chosen))) << what;
  EXPECT_LE(*chosen, *best + 1e-12L * std::fabs(*best) + 1e-9L) << what << ": t = " << t_orig;
}

Histogram levels(std::initializer_list<std::pair<int, std::uint32_t>> counts) {
  Histogram h{};
  for (const auto& [g, n] : counts) h[g] = n;
  return h;
}

// Expected counts of a two-Gaussian mixture over n pixels, optionally with Poisson noise.
Histogram mixture(double n, double p1, double mu1, double s1, double mu2, double s2,
                  std::mt19937* noise = nullptr) {
  Histogram h{};
  for (int g = 0; g < 256; ++g) {
    const auto pdf = [g](double mu, double s) {
      return std::exp(-0.5 * (g - mu) * (g - mu) / (s * s)) / (s * std::sqrt(2.0 * M_PI));
    };
    const double expected = n * (p1 * pdf(mu1, s1) + (1.0 - p1) * pdf(mu2, s2));
    if (noise && expected > 0) {
      h[g] = static_cast<std::uint32_t>(std::poisson_distribution<long>(expected)(*noise));
    } else {
      h[g] = static_cast<std::uint32_t>(std::lround(expected));
    }
  }
  return h;
}

// --- agreement of AT-Orig and AT-Mod (thesis table 2.1) -------------------------------

TEST(Threshold, VariantsAgreeOnRandomBimodalHistograms) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 3000; ++i) {
    const double mu1 = 5 + 120 * u(rng), mu2 = mu1 + 10 + (250 - mu1) * u(rng);
    const Histogram h = mixture(1000 + 400000 * u(rng), 0.05 + 0.9 * u(rng), mu1, 0.5 + 25 * u(rng), mu2,
                                0.5 + 25 * u(rng), &rng);
    expectBothAgreeAndMinimise(h, "mixture " + std::to_string(i));
  }
}

TEST(Threshold, VariantsAgreeOnRandomImages) {
  std::mt19937 rng(77);
  std::uniform_int_distribution<int> level(0, 255), coordinate(0, 63);
  std::normal_distribution<double> noise(0.0, 1.0);
  cv::Mat image(48, 64, CV_8UC1);
  for (int i = 0; i < 1500; ++i) {
    // A background level, a few bright rectangles, Gaussian noise of random strength.
    const int dark = level(rng) / 2, bright = 128 + level(rng) / 2;
    image.setTo(dark);
    for (int k = 0; k < 1 + i % 4; ++k)
      cv::rectangle(image, cv::Point(coordinate(rng), coordinate(rng) % 48),
                    cv::Point(coordinate(rng), coordinate(rng) % 48), bright, cv::FILLED);
    const double sigma = (i % 7) * 3.0;
    for (auto it = image.begin<std::uint8_t>(); it != image.end<std::uint8_t>(); ++it)
      *it = cv::saturate_cast<std::uint8_t>(*it + sigma * noise(rng));
    Histogram h;
    computeHistogram(image, h);
    expectBothAgreeAndMinimise(h, "image " + std::to_string(i));
  }
}

TEST(Threshold, VariantsAgreeOnSparseAndArbitraryHistograms) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> level(0, 255), populated(1, 8);
  std::uniform_int_distribution<std::uint32_t> count(1, 3000000), small(0, 3);
  for (int i = 0; i < 3000; ++i) {
    Histogram h{};
    if (i % 2 == 0) {
      for (int k = populated(rng); k > 0; --k) h[level(rng)] = count(rng);
    } else {
      for (auto& bin : h) bin = small(rng) == 0 ? count(rng) : small(rng);
    }
    expectBothAgreeAndMinimise(h, "arbitrary " + std::to_string(i));
  }
}

TEST(Threshold, VariantsAgreeAtTheLimitOfExactArithmetic) {
  Histogram h;
  h.fill((1u << 24) - 1);  // 2^32 - 256 pixels in all
  expectBothAgreeAndMinimise(h, "uniform, full");
  h = mixture(4.0e9, 0.5, 60, 10, 190, 15);
  expectBothAgreeAndMinimise(h, "mixture of 4e9 pixels");
  // 2^32 pixels or more are outside the exact range: a named error, never overflow.
  h = levels({{10, 0xFFFFFFFFu}, {11, 5}, {200, 7}, {201, 0xFFFFFFFFu}});
  int t = -7;
  EXPECT_EQ(thresholdAtOrig(h, t), Status::ThresholdUndefined);
  EXPECT_EQ(thresholdAtMod(h, t), Status::ThresholdUndefined);
  EXPECT_EQ(t, -7);
}

// --- AT-Mod is the double evaluation on histograms made to test it --------------------

// A mirror-symmetric histogram, h(g) = h(255 - g), gives J(t) = J(254 - t) to the last
// bit (the two class terms swap), so each t has an exact twin; a few pixels moved make
// the twins differ by less than the single-precision pass can tell apart.
TEST(ThresholdAtMod, IsTheDoubleEvaluationOnTiesAndNearTies) {
  std::mt19937 rng(91);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> level(0, 255), nudge(1, 3);
  int twins = 0;
  for (int i = 0; i < 1500; ++i) {
    Histogram half;
    switch (i % 3) {
      case 0:  // two modes per side: three or four modes in all
        half = mixture(20000 + 200000 * u(rng), 0.1 + 0.8 * u(rng), 10 + 60 * u(rng), 1 + 12 * u(rng),
                       80 + 60 * u(rng), 1 + 12 * u(rng), &rng);
        break;
      case 1:  // flat, plus noise
        for (auto& bin : half) bin = 50 + static_cast<std::uint32_t>(level(rng) % 7);
        break;
      default:  // sparse spikes
        half.fill(0);
        for (int k = 0; k < 6; ++k) half[level(rng)] = 1 + static_cast<std::uint32_t>(level(rng)) * 1000;
    }
    Histogram h;
    for (int g = 0; g < 128; ++g) h[g] = h[255 - g] = half[g] + half[255 - g];
    expectBothAgreeAndMinimise(h, "symmetric " + std::to_string(i));
    int t = -1;
    if (ok(thresholdAtMod(h, t)) && t < 127) ++twins;  // its twin 254 - t was not taken
    for (int k = 1 + i % 3; k > 0; --k) {
      const int g = level(rng);
      h[g] += static_cast<std::uint32_t>(nudge(rng));
      if (h[255 - g] > 3) h[255 - g] -= static_cast<std::uint32_t>(nudge(rng));
    }
    expectBothAgreeAndMinimise(h, "nearly symmetric " + std::to_string(i));
  }
  EXPECT_GT(twins, 1000);  // the tie rule was exercised (1427 of 1500 here), not only single minima
}

TEST(ThresholdAtMod, IsTheDoubleEvaluationOnFewPopulatedLevels) {
  std::mt19937 rng(17);
  std::uniform_int_distribution<int> level(0, 255), populated(1, 6);
  std::uniform_int_distribution<std::uint32_t> small(1, 20), any(1, 0xFFFFFFFFu);
  for (int i = 0; i < 3000; ++i) {
    Histogram h{};
    const int levels_wanted = populated(rng);
    for (int k = 0; k < levels_wanted; ++k) {
      const int g = i % 4 == 0 ? 100 + level(rng) % 4 : level(rng);  // neighbouring levels too
      h[g] = i % 3 == 0 ? any(rng) >> (level(rng) % 32) : small(rng);
      if (h[g] == 0) h[g] = 1;
    }
    expectTheDoubleEvaluation(h, "few levels " + std::to_string(i));
  }
  // All pixels in one bin, or all but one.
  for (const std::uint32_t n : {1u, 2u, 1000u, (1u << 23) - 1, 1u << 23, 0xFFFFFFFFu}) {
    for (const int g : {0, 1, 128, 254, 255}) {
      Histogram h{};
      h[g] = n;
      expectTheDoubleEvaluation(h, "one bin of " + std::to_string(n));
      h[g == 255 ? 0 : g + 1] = 1;
      expectTheDoubleEvaluation(h, "one bin and one pixel, " + std::to_string(n));
      h[g == 0 ? 255 : g - 1] = 1;
      h[g < 128 ? 255 : 0] = 1;
      expectTheDoubleEvaluation(h, "one bin and three pixels, " + std::to_string(n));
    }
  }
}

// 2^23 pixels is where AT-Mod leaves 64-bit integers for 128-bit ones.
TEST(ThresholdAtMod, IsTheDoubleEvaluationOnEitherSideOfThe64BitLimit) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> level(0, 255);
  constexpr std::int64_t kLimit = std::int64_t{1} << 23;
  for (int i = 0; i < 200; ++i) {
    const double mu1 = 10 + 100 * u(rng), mu2 = mu1 + 20 + (235 - mu1) * u(rng);
    Histogram h = mixture(static_cast<double>(kLimit), 0.1 + 0.8 * u(rng), mu1, 1 + 20 * u(rng), mu2,
                          1 + 20 * u(rng), &rng);
    std::int64_t pixels = 0;
    for (const auto n : h) pixels += n;
    // Exactly kLimit - 1, kLimit and kLimit + 1 pixels, the difference in one busy bin.
    const int busy = static_cast<int>(mu1);
    for (const std::int64_t target : {kLimit - 1, kLimit, kLimit + 1}) {
      Histogram exact = h;
      exact[busy] = static_cast<std::uint32_t>(exact[busy] + (target - pixels));
      expectBothAgreeAndMinimise(exact, std::to_string(target) + " pixels, " + std::to_string(i));
    }
  }
  // Up to the limit of exact arithmetic, 2^32 pixels, with noise in every bin.
  for (int i = 0; i < 300; ++i) {
    Histogram h = mixture(1.0e7 + 4.2e9 * u(rng), 0.1 + 0.8 * u(rng), 20 + 80 * u(rng), 2 + 15 * u(rng),
                          140 + 100 * u(rng), 2 + 15 * u(rng));
    for (auto& bin : h) bin += static_cast<std::uint32_t>(level(rng));
    expectTheDoubleEvaluation(h, "large " + std::to_string(i));
  }
}

// The range of x = sigma^2 / P^2 at its ends: a class of one busy level and one pixel
// beside it (the smallest variance for its size) and classes spread over 0..255.
TEST(ThresholdAtMod, IsTheDoubleEvaluationAtExtremeVariances) {
  for (const std::uint32_t busy : {2u, 1000u, (1u << 22), (1u << 23) - 8}) {
    expectTheDoubleEvaluation(levels({{40, busy}, {41, 1}, {200, 1}, {201, 1}}), "tight dark class");
    expectTheDoubleEvaluation(levels({{40, 1}, {41, 1}, {200, 1}, {201, busy}}), "tight bright class");
    expectTheDoubleEvaluation(levels({{0, busy}, {1, 1}, {2, 1}, {254, 1}, {255, busy}}), "two spikes");
    expectTheDoubleEvaluation(levels({{0, 1}, {127, busy}, {128, busy}, {255, 1}}), "wide tails");
  }
  Histogram h;
  h.fill((1u << 23) / 256 - 1);  // flat, just under the limit
  expectBothAgreeAndMinimise(h, "flat");
  h.fill(1);
  expectBothAgreeAndMinimise(h, "one pixel per level");
}

// --- the threshold separates the modes -----------------------------------------------

TEST(Threshold, LiesBetweenTheModesOfClearlyBimodalMixtures) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 500; ++i) {
    const double mu1 = 20 + 60 * u(rng), s1 = 3 + 7 * u(rng);
    const double mu2 = 150 + 80 * u(rng), s2 = 3 + 7 * u(rng);
    const Histogram h = mixture(640 * 480, 0.2 + 0.6 * u(rng), mu1, s1, mu2, s2, &rng);
    int t = -1;
    ASSERT_EQ(thresholdAtMod(h, t), Status::Ok);
    EXPECT_GT(t, mu1 + 2 * s1) << i;
    EXPECT_LT(t, mu2 - 2 * s2) << i;
  }
}

TEST(Threshold, TieAcrossAnEmptyGapTakesTheTopOfTheDarkClass) {
  // Every t from 12 to 199 gives the same two classes, hence the same J.
  const Histogram h = levels({{10, 5}, {11, 9}, {12, 4}, {200, 3}, {201, 8}, {202, 6}});
  int t = -1;
  ASSERT_EQ(thresholdAtOrig(h, t), Status::Ok);
  EXPECT_EQ(t, 12);
  ASSERT_EQ(thresholdAtMod(h, t), Status::Ok);
  EXPECT_EQ(t, 12);
}

// --- degenerate histograms -----------------------------------------------------------

void expectThreshold(const Histogram& h, Status status, int expected_t, const char* what) {
  for (const auto variant : {thresholdAtOrig, thresholdAtMod}) {
    int t = -7;
    EXPECT_EQ(variant(h, t), status) << what;
    EXPECT_EQ(t, expected_t) << what;
  }
}

TEST(Threshold, EmptyAndSingleLevelHistogramsAreUndefined) {
  expectThreshold(Histogram{}, Status::ThresholdUndefined, -7, "empty");
  expectThreshold(levels({{0, 307200}}), Status::ThresholdUndefined, -7, "all black");
  expectThreshold(levels({{255, 307200}}), Status::ThresholdUndefined, -7, "all white");
  expectThreshold(levels({{97, 1}}), Status::ThresholdUndefined, -7, "one pixel");
}

TEST(Threshold, FewLevelsSplitAtTheWidestGap) {
  expectThreshold(levels({{0, 1000}, {255, 20}}), Status::Ok, 0, "binary frame");
  expectThreshold(levels({{30, 1}, {200, 1}}), Status::Ok, 30, "two levels");
  expectThreshold(levels({{10, 50}, {20, 50}, {100, 50}}), Status::Ok, 20, "three levels");
  expectThreshold(levels({{10, 50}, {50, 5}, {90, 50}}), Status::Ok, 10, "three levels, equal gaps");
}

TEST(Threshold, FourLevelsLeaveOneDefinedPartition) {
  // Only t in [6, 199] gives both classes two levels; the smallest is 6.
  expectThreshold(levels({{5, 100}, {6, 1}, {200, 1}, {201, 100}}), Status::Ok, 6, "four levels");
}

TEST(Threshold, SkipsThresholdsThatLeaveASpikeAlone) {
  // Clipped black pixels at 0 beside two flat modes: every t < 100 leaves the spike
  // alone in class 1 (zero variance, ln sigma undefined), so none of them may win.
  Histogram h{};
  h[0] = 1000;
  for (int g = 100; g <= 110; ++g) h[g] = 40;
  for (int g = 200; g <= 210; ++g) h[g] = 30;
  int t = -1;
  ASSERT_EQ(thresholdAtOrig(h, t), Status::Ok);
  EXPECT_GE(t, 100);
  EXPECT_LE(t, 209);
  expectBothAgreeAndMinimise(h, "spike at 0");
  // Saturated at both ends of a realistic scene.
  h = mixture(200000, 0.6, 60, 8, 170, 10);
  h[0] = 50000;
  h[255] = 50000;
  expectBothAgreeAndMinimise(h, "spikes at 0 and 255");
}

// --- options and binarization --------------------------------------------------------

TEST(ComputeThreshold, DispatchesOnTheMethod) {
  const Histogram h = mixture(10000, 0.4, 50, 5, 150, 9);
  int expected = -1;
  ASSERT_EQ(thresholdAtMod(h, expected), Status::Ok);
  int t = -1;
  EXPECT_EQ(computeThreshold({ThresholdMethod::AtMod, 0}, h, t), Status::Ok);
  EXPECT_EQ(t, expected);
  t = -1;
  EXPECT_EQ(computeThreshold({ThresholdMethod::AtOrig, 0}, h, t), Status::Ok);
  EXPECT_EQ(t, expected);
  EXPECT_EQ(computeThreshold({ThresholdMethod::Manual, 77}, h, t), Status::Ok);
  EXPECT_EQ(t, 77);
  // Manual needs no histogram at all.
  EXPECT_EQ(computeThreshold({ThresholdMethod::Manual, 0}, Histogram{}, t), Status::Ok);
  EXPECT_EQ(t, 0);
  t = 5;
  EXPECT_EQ(computeThreshold({ThresholdMethod::Manual, 256}, h, t), Status::InvalidSettings);
  EXPECT_EQ(computeThreshold({ThresholdMethod::Manual, -1}, h, t), Status::InvalidSettings);
  EXPECT_EQ(computeThreshold({ThresholdMethod::None, 0}, h, t), Status::InvalidSettings);
  EXPECT_EQ(t, 5);
}

cv::Mat allLevels() {
  cv::Mat grey(16, 16, CV_8UC1);
  for (int g = 0; g < 256; ++g) grey.at<std::uint8_t>(g / 16, g % 16) = static_cast<std::uint8_t>(g);
  return grey;
}

TEST(Binarize, WhiteAboveTheThresholdBlackAtAndBelow) {
  const cv::Mat grey = allLevels();
  cv::Mat binary;
  for (const int t : {-1, 0, 1, 61, 127, 254, 255}) {
    binarize(grey, t, binary);
    ASSERT_EQ(binary.type(), CV_8UC1);
    ASSERT_EQ(binary.size(), grey.size());
    for (int g = 0; g < 256; ++g)
      EXPECT_EQ(binary.at<std::uint8_t>(g / 16, g % 16), g > t ? 255 : 0) << "t = " << t << ", g = " << g;
  }
}

TEST(Binarize, ThresholdOfABinaryFrameReproducesIt) {
  cv::Mat frame(48, 64, CV_8UC1, cv::Scalar(0));
  cv::circle(frame, {30, 20}, 12, 255, cv::FILLED);
  Histogram h;
  computeHistogram(frame, h);
  int t = -1;
  ASSERT_EQ(thresholdAtMod(h, t), Status::Ok);
  cv::Mat binary;
  binarize(frame, t, binary);
  EXPECT_EQ(cv::countNonZero(binary != frame), 0);
}

TEST(Binarize, ReusesItsBufferAndWorksInPlace) {
  cv::Mat frame = allLevels();
  cv::Mat binary;
  binarize(frame, 100, binary);
  const std::uint8_t* allocation = binary.datastart;
  binarize(frame(cv::Rect(2, 3, 9, 5)), 100, binary);
  EXPECT_EQ(binary.datastart, allocation);
  EXPECT_EQ(binary.size(), cv::Size(9, 5));
  EXPECT_EQ(cv::countNonZero(binary != (frame(cv::Rect(2, 3, 9, 5)) > 100)), 0);

  cv::Mat in_place = allLevels();
  binarize(in_place, 100, in_place);
  EXPECT_EQ(cv::countNonZero(in_place != (allLevels() > 100)), 0);
}

TEST(Binarize, EmptyOrWrongTypeGivesAnEmptyImage) {
  cv::Mat binary(4, 4, CV_8UC1);
  binarize(cv::Mat(), 10, binary);
  EXPECT_TRUE(binary.empty());
  binary.create(4, 4, CV_8UC1);
  binarize(cv::Mat(4, 4, CV_16UC1), 10, binary);
  EXPECT_TRUE(binary.empty());
}

}  // namespace
}  // namespace imagepro
