#pragma once
// PipelineOptions: every control of the thesis's appendix A panels, one field each,
// with its default. This struct is the one place a default lives; the GUI, the CLI
// and the settings file (settings.h) all read and write it.
#include <array>
#include <cstdint>
#include <map>
#include <string>

#include "core/common/geometry.h"

namespace imagepro {

// Thresholding and Re-Thresholding panels (thesis 2.3). None is a re-threshold choice only.
enum class ThresholdMethod : std::uint8_t {
  None,     // re-threshold: by-pass
  Manual,   // constant value "Val"
  AtOrig,   // Kittler-Illingworth minimum error, eqs. 2.4-2.10, sums recomputed per t
  AtMod,    // the same criterion, incremental moment vectors, eqs. 2.11-2.17
};

// Edge Detection panel (thesis 2.4).
enum class EdgeMethod : std::uint8_t {
  SobelThinning,  // eq. 2.21 + three-pixel thinning (older method, kept for comparison)
  Laplace,        // eq. 2.25 with Sobel gradients at edge pixels only
};

// Connectivity panel (thesis 2.5).
enum class ConnectivityMethod : std::uint8_t {
  CN0,  // corrected grouping of the earlier study, O(n^2)
  CN1,  // one-pass grouping, O(n)
};

// Ellipse Detection panel (thesis 2.6).
enum class EllipseMethod : std::uint8_t {
  Bennett,    // per-path accumulator, score/quality/symmetry rules (2.6.1)
  DirectFit,  // Fitzgibbon direct least-squares fit (2.6.2)
};

// Which measure the direct fit is accepted by.
enum class FitAcceptRule : std::uint8_t {
  RelativeError,    // thesis E_rel (eq. 2.42) below a threshold
  SampsonDistance,  // mean Sampson distance in pixels below a threshold (scale invariant)
};

// Reconstruction panel: which contour points feed the ellipse of the reconstruction.
enum class ContourMode : std::uint8_t {
  EightPointsOrg,
  EightPointsMod,
  FullPathOrg,
  FullPathMod,
  SubPixel,  // grey-level edge along the gradient (beyond the thesis, its rec. 6.3)
};

// Target Tracking panel (thesis ch. 3).
enum class TrackingMode : std::uint8_t {
  Off,
  Corners2D,
  Parameters3D,
};

// Application panel: process each frame up to this stage and stop.
enum class ApplicationLevel : std::uint8_t {
  Source,
  Threshold,
  Edges,
  Connectivity,
  Ellipse,
  Reconstruction,
};

struct ThresholdOptions {
  ThresholdMethod method = ThresholdMethod::AtMod;
  int manual_value = 128;  // "Val", 0..255: pixels > value are white (eq. 2.1)
};

// How the searched region is binarized before edge detection (beyond the thesis, whose
// one threshold per frame fails where light is uneven: local_threshold.h).
enum class Binarization : std::uint8_t {
  Global,           // the thesis: one threshold (pipeline.threshold) for the whole region
  Local,            // each pixel against the mean of its window
  GlobalThenLocal,  // the thesis's threshold; when it yields no target holding its spots, local
};

struct BinarizationOptions {
  Binarization mode = Binarization::GlobalThenLocal;
  int window_px = 0;       // side of the local window; 0: a sixteenth of the image width
  double offset = 0.15;    // black: darker than the window mean m by more than offset * m ...
  int min_contrast = 12;   // ... and by more than this many grey levels
  bool coarse_search = true;  // a full-frame search looks at the frame reduced first (stage_chain.h)
};

struct EllipseOptions {
  EllipseMethod method = EllipseMethod::DirectFit;
  FitAcceptRule accept_rule = FitAcceptRule::RelativeError;
  double max_relative_error = 0.02;     // thesis threshold for E_rel
  double max_sampson_distance_px = 0.5;
  int min_path_pixels = 20;             // shorter paths are not considered
  // A fitted ellipse must be traced by its path: arcs with a path pixel within
  // trace_inlier_px, at least min_traced_fraction of the part inside the image and
  // min_arc_fraction of the whole perimeter (a border-cut ellipse).
  double trace_inlier_px = 1.0;
  double min_traced_fraction = 0.95;
  double min_arc_fraction = 0.3;
  // Consensus fit for a target whose contour is partly replaced by an occluder's:
  // refit on the inliers of the best six-point fit (at most robust_iterations, fewer
  // once 99 % sure of one clean sample), accepted when they trace
  // robust_min_traced_fraction of the ellipse.
  bool robust_fit = true;
  int robust_iterations = 1000;
  double robust_min_traced_fraction = 0.75;
  // Bennett decision rules (thesis 2.6.1) with thresholds measured on the synthetic
  // library for this implementation (docs/ellipse-detection.md; the thesis's own were
  // score 550-840, quality 255-375). 1e9: no upper limit.
  double bennett_min_score = 340.0;
  double bennett_max_score = 1e9;
  double bennett_min_quality = 0.0;
  double bennett_max_quality = 1e9;
  double bennett_min_peak_fraction = 0.0625;  // peak score / point pairs of the path
  // Beyond the thesis: the direct fit of an accepted path, which gives its ellipse, must
  // fit it with E_rel at most this. A point-symmetric shape that is no ellipse (a bar,
  // 67 x 8 px in data/samples/sample06_no_target.png, E_rel 0.043) passes rules 1-3;
  // library ellipses stay below 0.005 (docs/ellipse-detection.md). 1e9: rules 1-3 alone.
  double bennett_max_relative_error = 0.02;
  int bennett_max_points = 256;               // longer paths are subsampled (0: never)
  // Target selection: spot positions may deviate by this fraction of the disk radius.
  double target_spot_tolerance = 0.2;
  // A plain ellipse chosen as the target must be a view of a circle tilted at most this
  // far, its centre inside the image (plausibleTargetView).
  double target_max_tilt_deg = 80.0;
  // NoTarget unless an ellipse holds the target's two spots (otherwise the best ellipse).
  bool require_target_spots = false;
  // Report every target found instead of failing with AmbiguousTarget.
  bool report_all_targets = false;
  // With robust_fit, a rim without a path of its own is looked for from a pair of spots
  // (detect.h). Not a setting: the stage chain leaves it to the full-size passes.
  bool targets_from_spots = true;
};

struct ReconstructionOptions {
  bool distortion_correction = true;
  bool exact_undistortion = false;  // Newton inverse instead of the Taylor inverse (eqs. 4.18-4.19)
  ContourMode contour_mode = ContourMode::SubPixel;  // most accurate by far: docs/accuracy.md
  // Weigh the centre spot's polar line into the plane's normal: near head-on the rim alone
  // fixes the normal poorly (docs/reconstruction.md, docs/accuracy.md).
  bool centre_spot_normal = true;
  bool refine_pose = false;  // Levenberg-Marquardt steps against the rim's points and the spots (refine.h)
  // Spot centres under a Gaussian window that follows the spot, instead of the plain
  // darkness-weighted centroid of the spot's box (features.h; docs/reconstruction.md).
  bool weighted_spot_centres = true;
  // Sub-pixel mode: re-place the rim's points with its dark and bright levels fitted over
  // the whole rim and the blur's shrink of a curved edge undone (rim_edge.h); off, each
  // point keeps the level between its own plateaus (docs/reconstruction.md, Rim edge model).
  bool rim_edge_model = true;
  // Sub-pixel contour mode: leave the contour points off the rim (an occluder's edge, a
  // crossing under glare) out of the rim's fit, the self-check and the refinement
  // (rim_fit.h); off, and in the thesis's pixel modes, every point is fitted.
  bool robust_rim_fit = true;
  int crop_margin_px = 4;
  // Sub-pixel contour mode only (the pixel modes keep the thesis's rule, unchecked).
  // Self-check (docs/reconstruction.md): a pose that puts a spot's image further than this
  // from where it was found, or the rim's further (RMS) from its contour points, or both
  // further than kJointErrorShare of these (reconstruct.h), is PoseInconsistent.
  double max_spot_error_px = 1.0;
  double max_rim_error_px = 1.0;
  // The rim's two circles: the one reprojecting the spots better is kept when its error is
  // ambiguity_ratio times smaller and sqrt(error^2 + margin^2) below the other's; else a
  // tracked stream takes the one nearer the last pose, and a still the pose halfway between
  // them when that lies within ambiguity_tolerance_deg of both (normals up to twice that apart),
  // or is AmbiguousPose. The margin is ambiguity_margin_px on a sharp rim and grows with
  // the rim edge model's blur beyond 1 px of spread.
  double ambiguity_ratio = 1.3;
  double ambiguity_margin_px = 0.07;
  double ambiguity_tolerance_deg = 5.0;
};

struct TrackingOptions {
  TrackingMode mode = TrackingMode::Corners2D;
  int data_points = 5;             // last n points
  int degree = 2;                  // 0..3
  double min_r = 0.9;              // critical correlation coefficient
  double reduction_percent = 10.0; // "red [%]": damps shrinking of the region
  double enlarge_px = 20.0;        // fixed pixels added to width and height
  double enlarge_scale = 0.1;      // fixed scale factor
  double enlarge_speed_scale = 0.02; // scale per pixel/frame of the target centre's speed
};

struct DisplayOptions {
  enum class Background : std::uint8_t { Empty, Source, Binary } background = Background::Source;
  enum class Edges : std::uint8_t { None, EdgePixels, ConnectedPaths } edges = Edges::None;
  enum class Target : std::uint8_t { None, Path, Source, Binary } target = Target::Path;
  bool feature_edge = true;
  bool feature_spots = true;
  // The live calibration check (thesis A.1.1): the calibration pattern's ideal spot
  // positions and the spots found, drawn over every shown frame (core/calibration/calibration_check.h).
  bool calibration_check = false;
};

// Internal Camera Calibration panel (thesis 4.6): the lens distortion iteration.
struct CalibrationOptions {
  double relative_change = 0.01;  // converged when every parameter changes relatively less (thesis: 0.01)
  int max_iterations = 10;        // not converged by then: Diverged
  int min_matches = 20;           // fewer matched spots in an image: TooFewMatches, the image is skipped
  double max_ambiguous_fraction = 0.05;  // more ambiguous spots than this in an image: MatchAmbiguity
  bool refine_pose = true;  // correct each image's pattern pose from its spots with the distortion (off: the thesis)
};

struct PipelineOptions {
  ThresholdOptions threshold;
  BinarizationOptions binarization;
  EdgeMethod edge_method = EdgeMethod::Laplace;
  ConnectivityMethod connectivity = ConnectivityMethod::CN1;
  EllipseOptions ellipse;
  ThresholdOptions rethreshold{ThresholdMethod::AtMod, 128};
  ReconstructionOptions reconstruction;
  TrackingOptions tracking;
  ApplicationLevel level = ApplicationLevel::Reconstruction;
  DisplayOptions display;
  CalibrationOptions calibration;
};

}  // namespace imagepro

namespace imagepro {

// The input sources of thesis 2.2 (the Input Source panel of appendix A). Each has its
// own camera model in the settings (thesis A.3: the image plane, the principal point,
// the pixel size and the distortion "corresponding to the input sources").
enum class SourceKind : std::uint8_t { File, Camera, Virtual };
inline constexpr std::array<SourceKind, 3> kSourceKinds{SourceKind::File, SourceKind::Camera, SourceKind::Virtual};

// The Virtual perspective projection source (thesis 2.2): how the target is drawn
// and how it moves. "Settings" menu of appendix A: virtual velocities.
enum class RenderMode : std::uint8_t {
  Binary,  // thesis: 1-bit image, white target on black
  Grey,    // anti-aliased 8-bit grey with optional blur, noise, gradient, clutter
};

enum class MotionKind : std::uint8_t { Static, Sinusoid, SawTooth, Pendulum, ConstantVelocity };
enum class PoseAxis : std::uint8_t { Tx, Ty, Tz, Rx, Ry, Rz };

struct MotionOptions {
  MotionKind kind = MotionKind::Static;
  PoseAxis axis = PoseAxis::Tx;
  double amplitude = 100.0;  // mm for translations, degrees for rotations
  double period_s = 4.0;
  // Constant velocity (thesis A.2, the Settings menu's velocities): per parameter, deg/s
  // for the rotations and mm/s for the translations, inside a wrap-around box of the
  // given full width (deg, mm) centred on the initial pose; a width of 0 never wraps.
  Pose velocity{0.0, 20.0, 0.0, 100.0, 0.0, 0.0};
  Pose wrap_box{0.0, 120.0, 360.0, 400.0, 300.0, 600.0};
};

// A target hanging from a pivot below it (+Y is down), facing the camera, swinging in
// a vertical plane whose heading about Y is swing_axis_deg (0: swings along camera X).
struct PendulumOptions {
  double length_mm = 444.0;  // pivot to target centre (thesis 5.3.2: 444 mm)
  double amplitude_deg = 15.0;
  double gravity_m_s2 = 9.80665;
  std::array<double, 3> pivot_mm{0.0, -300.0, 1200.0};  // camera frame
  double swing_axis_deg = 0.0;
};

// What the Virtual source's camera sees around the target's card, in grey mode (binary
// frames, the thesis's, have a black background).
enum class Backdrop : std::uint8_t {
  Plain,  // the thesis's synthetic frames: one flat grey, background_level
  Room,   // a lit room: a wall with a window and a picture, a desk with books, a monitor,
          // a keyboard, a mug and a cable, darker towards the corners
};

struct VirtualSceneOptions {
  RenderMode mode = RenderMode::Grey;
  // Plain for a scene made here, as the studies, benchmarks and tests render it; the
  // settings' Virtual source starts in the room (Settings::virtual_scene).
  Backdrop backdrop = Backdrop::Plain;
  // Per axis, grey mode edge anti-aliasing: n x n samples per edge pixel. At 4 a pixel's
  // coverage came in steps of 1/16 (1/4 along a row or column), an error in the rim that the
  // accuracy study measured as the method's own; 8 costs three times the sampling and leaves
  // the study's figures to the method (docs/reconstruction.md, Accuracy study).
  int supersampling = 8;
  double blur_sigma_px = 0.0;
  double noise_sigma = 0.0;         // grey levels
  double illumination_gradient = 0.0;  // fractional brightness change across the width
  int clutter = 0;                  // number of white bars and rectangles
  unsigned seed = 1;                // noise and clutter
  int white_level = 230;
  int black_level = 20;
  int background_level = 110;       // the scene around the target's card
  double card_size_mm = 130.0;      // black square card carrying the target
  double frame_rate_hz = 25.0;
  Pose initial_pose{0.0, 0.0, 0.0, 0.0, 0.0, 800.0};
  MotionOptions motion;
  PendulumOptions pendulum;
  double key_step_mm = 5.0;         // per key press (appendix A keys)
  double key_step_deg = 1.0;
};

// The analogue TV standard a capture card (a composite or S-Video frame grabber like the
// thesis's PXC200) digitizes its input by; each group stands for all its variants
// (PAL-B, PAL-D ...), of which the driver picks.
enum class TvStandard : std::uint8_t { Keep, Pal, Ntsc, Secam };

// The Camera source (thesis 2.2: the frame grabber, here a V4L2 device): which device,
// at which size and rate, which of a capture card's inputs in which TV standard, and
// the device controls set after opening it.
struct CameraSourceOptions {
  std::string device = "/dev/video0";
  int width = 0;   // 0 (width or height): the Camera source's camera model's size
  int height = 0;
  double frame_rate_hz = 25.0;  // thesis 5.2.1; 0: the driver's own rate
  int input = -1;               // the card's input (imagepro-cli devices numbers them); -1: the device's
  TvStandard standard = TvStandard::Keep;
  std::map<std::string, std::int64_t> controls;  // control key (imagepro-cli devices) -> value
};

// The live pose stream (docs/streaming.md): every frame's result as one UDP datagram to
// host:port, for programs that want the pose as it is made.
enum class StreamFormat : std::uint8_t {
  Json,       // one JSON object a datagram: frame, timestamp, status, the six parameters
  OpenTrack,  // OpenTrack's "UDP over network" input: six little-endian doubles
};

struct StreamOptions {
  bool enabled = false;
  std::string host = "127.0.0.1";  // a name, an IPv4 or an IPv6 address
  int port = 5005;
  StreamFormat format = StreamFormat::Json;
  bool operator==(const StreamOptions&) const = default;
};

// Poses in frames the user chooses, and the live readout between two targets
// (settings "frames", docs/conventions.md *Frames of reference*). Ids are the set's
// (target_set.h), or kLoneTargetId 0 for the one target without a set; -1 is none.
struct PoseFramesOptions {
  int reference_target = -1;  // every other target's pose is also given in this one's frame
  int shown_target = -1;      // the target whose results the application shows; -1: the first found
  std::array<int, 2> measured_targets{-1, -1};  // whose distance and angle are shown live
  bool origin_set = false;    // "Set origin" stored `origin`: poses are also given in that world frame
  Pose origin;                // the world frame's pose in the camera frame (as a target's pose)
  bool operator==(const PoseFramesOptions&) const = default;
};

}  // namespace imagepro
