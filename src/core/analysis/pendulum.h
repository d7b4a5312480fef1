#pragma once
// Pendulum and g (thesis 5.3.2): a target on a swinging pendulum is reconstructed frame
// by frame; from the poses and their times:
//
//  * the period, from the translations over time: the swing direction is the principal
//    axis of the positions; the motion along it is checked to be an oscillation by the
//    best sinusoid (share of variance it explains), whose period also numbers the
//    swings; the crossings of the mid-swing level (cubic interpolation between frames)
//    then give the period by least squares, t_j = t_rising|falling + k_j T / 2 with one
//    intercept per direction so that a misjudged level cancels. The thesis's own
//    method is offered beside it (estimatePeriodByMaxima): the time between the first
//    and the last maximum divided by the cycles between them, averaged over Tx, Ty, Tz.
//  * the pivot and the length by the constrained sphere fit of eqs. 5.2-5.6: the
//    positions lie on a sphere about the pivot whose radius vector is perpendicular to
//    the target's normal. Eq. 5.6 is solved by pseudo-inverse as in the thesis, then
//    refined by Gauss-Newton on geometric residuals (distance from the sphere in mm, and
//    the cosine of the angle between the radius vector and the normal), each kind
//    weighted by the inverse of its RMS, so that the two kinds of equation count by
//    their precision, not by their units, and a short arc gives no bias.
//  * g = 4 pi^2 l / T0^2 (eq. 5.1) with T0 the small-amplitude period. Eq. 5.1 holds
//    for small swings only: the exact period of a simple pendulum swinging theta0 to
//    either side is T = T0 2 K(k) / pi, k = sin(theta0 / 2) (K the complete elliptic
//    integral of the first kind), about T0 (1 + theta0^2 / 16); at 15 degrees eq. 5.1
//    alone would underestimate g by 0.9 %. theta0 is the amplitude of the swing angle
//    about the fitted pivot; the correction can be turned off (the thesis had none).
//
// As the thesis ran it, the length may come from a separate "still" recording, a few
// frames of the target held still at several places along its arc, and the period from
// the swing (analyzePendulumStillSwing): the thesis's camera could not follow a swing
// wide enough for the sphere fit (interlacing and motion blur, fig. 5.11).
//
// Uncertainties are one standard deviation from the least-squares residuals, propagated
// to the length, the period and g. Data that cannot give an answer gives a named
// status: TooFewFrames, TargetLost (no pose in half of the frames or more), NoSwing
// (no oscillation stands out), DegenerateFit (times not increasing, positions on a line).
#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/common/geometry.h"
#include "core/common/status.h"

namespace imagepro {

// One frame of a reconstructed sequence.
struct PoseSample {
  double t_s = 0.0;
  bool valid = false;  // the frame has a pose
  Pose pose;
};

// Fewest frames with a pose the analysis works with.
inline constexpr int kPendulumMinFrames = 10;

struct PeriodEstimate {
  double period_s = 0.0;
  double period_sigma_s = 0.0;
  int crossings = 0;                                      // mid-swing crossings used
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // unit swing direction
  double amplitude_mm = 0.0;     // of the best sinusoid along the direction
  double sine_fraction = 0.0;    // share of the variance along the direction it explains
};

// Period of the motion of `positions_mm` (camera frame) at strictly increasing `times_s`.
// TooFewFrames: fewer than kPendulumMinFrames samples; NoSwing: no motion, the best
// sinusoid explains less than half of the variance, or fewer than four crossings (not
// even one and a half swings); DegenerateFit: sizes differ or times do not increase.
Status estimatePeriod(std::span<const double> times_s, std::span<const Eigen::Vector3d> positions_mm,
                      PeriodEstimate& out);

// The thesis's period (5.3.2): for each of Tx, Ty and Tz, the time between its first
// and its last maximum divided by the cycles between them; the mean over the axes.
// An axis counts when it moves at the swing's period (its sinusoid at `swing_period_s`
// explains at least half of its motion) with two maxima or more: in the camera frame
// the height of a swing rises at both ends, so it moves at twice the frequency and the
// thesis's rule would halve the period; an axis across the line of sight may not move.
// A maximum is a frame more than a third of the amplitude above the mid level and the
// highest within a quarter period either side (one a cycle; noise makes no other).
struct MaximaPeriod {
  double period_s = 0.0;  // mean over the axes used
  // One sigma: the spread over the axes divided by sqrt(axes), and no less than the
  // frame time's share (each maximum is a frame: dt / sqrt(6) over the cycles).
  double period_sigma_s = 0.0;
  std::array<double, 3> axis_period_s{};  // 0 for an axis not used
  std::array<int, 3> axis_cycles{};
  int axes = 0;
};

// TooFewFrames below kPendulumMinFrames samples; NoSwing when no axis qualifies;
// DegenerateFit when sizes differ, times do not increase or swing_period_s <= 0.
Status estimatePeriodByMaxima(std::span<const double> times_s, std::span<const Eigen::Vector3d> positions_mm,
                              double swing_period_s, MaximaPeriod& out);

enum class PeriodMethod : std::uint8_t {
  Crossings,  // mid-swing crossings by least squares (the default)
  Maxima      // the thesis's: first to last maximum, averaged over Tx, Ty, Tz
};

struct SphereFit {
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();  // the pivot
  Eigen::Vector3d centre_sigma_mm = Eigen::Vector3d::Zero();
  double radius_mm = 0.0;  // the length
  double radius_sigma_mm = 0.0;
  double radial_rms_mm = 0.0;  // RMS of |p - centre| - radius
  double normal_rms_mm = 0.0;  // RMS of (centre - p) . u3 (eq. 5.3)
  int points = 0;
};

// Eqs. 5.2-5.6 over the positions and the unit normals of the target (rotation's third
// column). TooFewFrames below four points; DegenerateFit when the equations do not fix
// the centre (e.g. every position on a line) or the sizes differ.
Status fitConstrainedSphere(std::span<const Eigen::Vector3d> positions_mm, std::span<const Eigen::Vector3d> normals,
                            SphereFit& out);

// T / T0 for a simple pendulum swinging `amplitude_rad` to either side: 2 K(sin(a/2)) / pi.
double pendulumPeriodFactor(double amplitude_rad);

struct PendulumAnalysisOptions {
  bool amplitude_correction = true;  // g from the small-amplitude period (see above)
  PeriodMethod period_method = PeriodMethod::Crossings;  // the period g is computed from
};

struct PendulumAnalysis {
  int frames = 0, valid_frames = 0;
  PeriodEstimate period;              // mid-swing crossings
  Status maxima_status = Status::Stopped;  // of the thesis's period (Ok: `maxima` holds it)
  MaximaPeriod maxima;
  SphereFit sphere;
  // The length from a still recording (analyzePendulumStillSwing): its frames, those
  // with a pose, and whether the analysis failed on it.
  bool length_from_still = false;
  int still_frames = 0, still_valid_frames = 0;
  bool still_failed = false;
  double length_mm = 0.0, length_sigma_mm = 0.0;
  double period_s = 0.0, period_sigma_s = 0.0;  // measured, by the options' method
  double amplitude_deg = 0.0, amplitude_sigma_deg = 0.0;  // swing angle to either side
  double small_amplitude_period_s = 0.0, small_amplitude_period_sigma_s = 0.0;  // T0 (= period without correction)
  double g_m_s2 = 0.0, g_sigma_m_s2 = 0.0;
  double g_uncorrected_m_s2 = 0.0;  // eq. 5.1 with the measured period, as in the thesis
  std::vector<double> swing_angle_deg;  // per valid frame, about the fitted pivot
};

Status analyzePendulum(std::span<const PoseSample> samples, const PendulumAnalysisOptions& options,
                       PendulumAnalysis& out);

// The period from `swing`, the pivot and the length from `still` (at least four frames
// with a pose, not all in one place: TooFewFrames or DegenerateFit with still_failed),
// the amplitude from the swing about that pivot.
Status analyzePendulumStillSwing(std::span<const PoseSample> still, std::span<const PoseSample> swing,
                                 const PendulumAnalysisOptions& options, PendulumAnalysis& out);

}  // namespace imagepro
