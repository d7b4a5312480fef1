#include "core/settings/enum_names.h"

namespace imagepro {

namespace {
using B = DisplayOptions::Background;
using ED = DisplayOptions::Edges;
using TD = DisplayOptions::Target;

constexpr EnumEntry<ThresholdMethod> kThreshold[] = {
    {ThresholdMethod::None, "none", "None",
     "no re-thresholding; the target's crop is cut at the frame's own threshold (thesis A.1.1, Re-Thresholding "
     "panel: the by-pass)"},
    {ThresholdMethod::Manual, "manual", "Manual", "the constant threshold Val, pixels above it are white (thesis 2.3, eq. 2.1)"},
    {ThresholdMethod::AtOrig, "at-orig", "AT-Orig",
     "Kittler-Illingworth minimum error threshold, the sums recomputed for every t (thesis 2.3.1, eqs. 2.4-2.10)"},
    {ThresholdMethod::AtMod, "at-mod", "AT-Mod",
     "the same minimum error criterion, computed incrementally with moment vectors (thesis 2.3.2, eqs. 2.11-2.17)"}};
constexpr EnumEntry<Binarization> kBinarization[] = {
    {Binarization::Global, "global", "Global", "one threshold for the whole searched region, the method above (thesis 2.3)"},
    {Binarization::Local, "local", "Local",
     "each pixel against the mean of its window; black where clearly darker than its surroundings (uneven light)"},
    {Binarization::GlobalThenLocal, "global-then-local", "Global, then local",
     "the thesis's threshold, and when that misses the target a second pass on the local binary image"}};
constexpr EnumEntry<EdgeMethod> kEdge[] = {
    {EdgeMethod::SobelThinning, "sobel-thinning", "Sobel + thinning",
     "every pixel with a non-zero Sobel gradient, then the three-pixel thinning; the earlier method, kept for "
     "comparison (thesis 2.4.1-2.4.2, eq. 2.21)"},
    {EdgeMethod::Laplace, "laplace", "Laplace",
     "a white pixel with a black 4-neighbour, one pixel thick; Sobel gradients at the edge pixels only (thesis "
     "2.4.3, eq. 2.25)"}};
constexpr EnumEntry<ConnectivityMethod> kConnectivity[] = {
    {ConnectivityMethod::CN0, "cn0", "CN0",
     "the earlier study's grouping, its bugs and path limit removed; scans every unassigned pixel, O(n^2) (thesis 2.5)"},
    {ConnectivityMethod::CN1, "cn1", "CN1",
     "one-pass grouping of 8-connected edge pixels through an index image, O(n) (thesis 2.5.1)"}};
constexpr EnumEntry<EllipseMethod> kEllipse[] = {
    {EllipseMethod::Bennett, "bennett", "Bennett",
     "one accumulator per connected path, accepted by its symmetry, quality, score and peak-share rules; the ellipse "
     "itself from the direct fit of the path, which must fit it (E_rel at most bennett_max_relative_error, so a "
     "point-symmetric bar is no ellipse) (thesis 2.6.1, eqs. 2.26-2.28)"},
    {EllipseMethod::DirectFit, "direct-fit", "Direct fit",
     "Fitzgibbon's least-squares ellipse fit of each path, accepted by the accept rule (E_rel of eq. 2.42 or the "
     "Sampson distance) when the path also traces the ellipse (thesis 2.6.2)"}};
constexpr EnumEntry<FitAcceptRule> kAccept[] = {
    {FitAcceptRule::RelativeError, "relative-error", "E_rel",
     "accept a fit whose relative error E_rel (in the fit's normalised coordinates) is below Max E_rel and whose path "
     "traces it (thesis 2.6.2, eq. 2.42)"},
    {FitAcceptRule::SampsonDistance, "sampson-distance", "Sampson distance",
     "accept a fit whose mean Sampson distance in pixels is below Max Sampson and whose path traces it (beyond the "
     "thesis 2.6.2)"}};
constexpr EnumEntry<ContourMode> kContour[] = {
    {ContourMode::EightPointsOrg, "8-points-org", "8 points ORG",
     "from the detected centre, walk pixel by pixel along the 8 directions E, SE, S, ... across the centre spot, then "
     "across white; the last white pixel before black, at its pixel centre. The earlier study's method (thesis A.1.1, "
     "Reconstruction panel)"},
    {ContourMode::EightPointsMod, "8-points-mod", "8 points MOD",
     "the same 8 rays, walked in 1/16 px steps from outside the detected rim inwards within +-w px of it (w = 2.5 px "
     "+ 4 % of the semi-major axis); the point between the last black and the first white sample, that white followed "
     "by a second white pixel. The improved version (thesis A.1.1, Reconstruction panel)"},
    {ContourMode::FullPathOrg, "full-path-org", "Full path ORG",
     "the disk's outer boundary in the binary crop: the first and the last white pixel of every row and every column, "
     "each pixel once, at its pixel centre. The earlier study's method (thesis A.1.1, Reconstruction panel)"},
    {ContourMode::FullPathMod, "full-path-mod", "Full path MOD",
     "one point per row or column crossing of the rim (rows where it runs closer to vertical, columns elsewhere), "
     "searched from outside inwards within +-w px of the detected rim: the first white pixel after black and before a "
     "second white one, the point on the pixel boundary. The improved version (thesis A.1.1, Reconstruction panel)"},
    {ContourMode::SubPixel, "subpixel", "Sub-pixel",
     "full path MOD's crossings (about 160 on a large rim) placed in the grey levels, by the area under the grey "
     "profile across the edge, or where the profile crosses the mean of its two plateaus; independent of the "
     "threshold (beyond the thesis: its recommendation 6.3). By default the rim edge model then places them "
     "again with levels and blur fitted over the whole rim; without it a near-round rim takes up to 320"}};
constexpr EnumEntry<TrackingMode> kTracking[] = {
    {TrackingMode::Off, "off", "Off", "no tracking: every frame is searched whole"},
    {TrackingMode::Corners2D, "2d-corners", "2D Corners",
     "polynomials over the last points of the target box's upper-left and lower-right corners give the next box "
     "(thesis 3.2.2.1)"},
    {TrackingMode::Parameters3D, "3d-parameters", "3D Parameters",
     "polynomials over the last six parameters give the next pose, the target projected through the camera gives "
     "the box (thesis 3.2.2.2)"}};
constexpr EnumEntry<ApplicationLevel> kLevel[] = {
    {ApplicationLevel::Source, "source", "Source", "grab the frame only (thesis 2.2)"},
    {ApplicationLevel::Threshold, "threshold", "Threshold", "up to thresholding (thesis 2.3)"},
    {ApplicationLevel::Edges, "edges", "Edges", "up to edge detection (thesis 2.4)"},
    {ApplicationLevel::Connectivity, "connectivity", "Connectivity", "up to connectivity analysis (thesis 2.5)"},
    {ApplicationLevel::Ellipse, "ellipse", "Ellipse", "up to ellipse detection (thesis 2.6)"},
    {ApplicationLevel::Reconstruction, "reconstruction", "Reconstruction",
     "the whole pipeline: 3D reconstruction and tracking (thesis figure 5.1)"}};
constexpr EnumEntry<B> kBackground[] = {{B::Empty, "empty", "Empty", "a black background"},
                                        {B::Source, "source", "Source", "the input frame"},
                                        {B::Binary, "binary", "Binary", "the thresholded search region"}};
constexpr EnumEntry<ED> kEdgeDisplay[] = {
    {ED::None, "none", "None", "no edges drawn"},
    {ED::EdgePixels, "edges", "Edge Detection", "the edge pixels of the selected edge detection method (thesis 2.4)"},
    {ED::ConnectedPaths, "connected-paths", "Connectivity", "each connected path in its own colour (thesis 2.5)"}};
constexpr EnumEntry<TD> kTargetDisplay[] = {{TD::None, "none", "None", "the target is not drawn"},
                                            {TD::Path, "path", "Path", "the detected ellipse"},
                                            {TD::Source, "source", "Source", "the grey image of the target region"},
                                            {TD::Binary, "binary", "Binary", "the binary image of the target region"}};
constexpr EnumEntry<RenderMode> kRender[] = {
    {RenderMode::Binary, "binary", "Binary", "binary frames as in the thesis (2.2)"},
    {RenderMode::Grey, "grey", "Grey", "anti-aliased grey frames with optional blur, noise, gradient and clutter"}};
constexpr EnumEntry<Backdrop> kBackdrop[] = {
    {Backdrop::Plain, "plain", "Plain", "one flat grey around the card, as the thesis's synthetic frames"},
    {Backdrop::Room, "room", "Room", "a lit room: a window, a desk with books, a monitor, a mug"}};
constexpr EnumEntry<MotionKind> kMotion[] = {
    {MotionKind::Static, "static", "Static", "the target stays put (the keys still move it)"},
    {MotionKind::Sinusoid, "sinusoid", "Sinusoid", "a sinusoid along or about the chosen axis"},
    {MotionKind::SawTooth, "saw-tooth", "Saw-tooth", "a saw-tooth along or about the chosen axis"},
    {MotionKind::Pendulum, "pendulum", "Pendulum", "a pendulum swinging from a pivot (thesis 5.3.2)"},
    {MotionKind::ConstantVelocity, "constant-velocity", "Constant velocity",
     "every parameter at its own constant rate, wrapping around inside a box about the start pose (thesis A.2)"}};
constexpr EnumEntry<PoseAxis> kAxis[] = {
    {PoseAxis::Tx, "tx", "Tx", "translation along x, mm"}, {PoseAxis::Ty, "ty", "Ty", "translation along y, mm"},
    {PoseAxis::Tz, "tz", "Tz", "translation along z, mm"}, {PoseAxis::Rx, "rx", "Rx", "rotation about x, degrees"},
    {PoseAxis::Ry, "ry", "Ry", "rotation about y, degrees"}, {PoseAxis::Rz, "rz", "Rz", "rotation about z, degrees"}};
constexpr EnumEntry<StreamFormat> kStreamFormat[] = {
    {StreamFormat::Json, "json", "JSON",
     "one JSON object a datagram: frame, timestamp, status and the six parameters in mm and degrees, with every "
     "target's when there are several"},
    {StreamFormat::OpenTrack, "opentrack", "OpenTrack",
     "OpenTrack's \"UDP over network\" input: x, y, z in cm and yaw, pitch, roll in degrees as six little-endian "
     "doubles, frames with a pose only"}};
constexpr EnumEntry<SourceKind> kSource[] = {
    {SourceKind::File, "file", "File", "still images or a video file (thesis 2.2)"},
    {SourceKind::Camera, "camera", "Camera", "a V4L2 camera or capture card, frame by frame (thesis 2.2)"},
    {SourceKind::Virtual, "virtual", "Virtual", "the virtual perspective projection of the target (thesis 2.2)"}};
constexpr EnumEntry<TvStandard> kTvStandard[] = {
    {TvStandard::Keep, "keep", "Keep", "the standard the device has, not set"},
    {TvStandard::Pal, "pal", "PAL", "PAL, 625 lines at 25 frames/s"},
    {TvStandard::Ntsc, "ntsc", "NTSC", "NTSC, 525 lines at 29.97 frames/s"},
    {TvStandard::Secam, "secam", "SECAM", "SECAM, 625 lines at 25 frames/s"}};
}  // namespace

std::span<const EnumEntry<ThresholdMethod>> enumEntries(ThresholdMethod) { return kThreshold; }
std::span<const EnumEntry<Binarization>> enumEntries(Binarization) { return kBinarization; }
std::span<const EnumEntry<EdgeMethod>> enumEntries(EdgeMethod) { return kEdge; }
std::span<const EnumEntry<ConnectivityMethod>> enumEntries(ConnectivityMethod) { return kConnectivity; }
std::span<const EnumEntry<EllipseMethod>> enumEntries(EllipseMethod) { return kEllipse; }
std::span<const EnumEntry<FitAcceptRule>> enumEntries(FitAcceptRule) { return kAccept; }
std::span<const EnumEntry<ContourMode>> enumEntries(ContourMode) { return kContour; }
std::span<const EnumEntry<TrackingMode>> enumEntries(TrackingMode) { return kTracking; }
std::span<const EnumEntry<ApplicationLevel>> enumEntries(ApplicationLevel) { return kLevel; }
std::span<const EnumEntry<DisplayOptions::Background>> enumEntries(DisplayOptions::Background) { return kBackground; }
std::span<const EnumEntry<DisplayOptions::Edges>> enumEntries(DisplayOptions::Edges) { return kEdgeDisplay; }
std::span<const EnumEntry<DisplayOptions::Target>> enumEntries(DisplayOptions::Target) { return kTargetDisplay; }
std::span<const EnumEntry<RenderMode>> enumEntries(RenderMode) { return kRender; }
std::span<const EnumEntry<Backdrop>> enumEntries(Backdrop) { return kBackdrop; }
std::span<const EnumEntry<MotionKind>> enumEntries(MotionKind) { return kMotion; }
std::span<const EnumEntry<PoseAxis>> enumEntries(PoseAxis) { return kAxis; }
std::span<const EnumEntry<StreamFormat>> enumEntries(StreamFormat) { return kStreamFormat; }
std::span<const EnumEntry<SourceKind>> enumEntries(SourceKind) { return kSource; }
std::span<const EnumEntry<TvStandard>> enumEntries(TvStandard) { return kTvStandard; }

}  // namespace imagepro
