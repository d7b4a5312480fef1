#include "core/settings/enum_names.h"

namespace imagepro {

namespace {
constexpr EnumEntry<ThresholdMethod> kThreshold[] = {{ThresholdMethod::None, "none"},
                                                     {ThresholdMethod::Manual, "manual"},
                                                     {ThresholdMethod::AtOrig, "at-orig"},
                                                     {ThresholdMethod::AtMod, "at-mod"}};
constexpr EnumEntry<EdgeMethod> kEdge[] = {{EdgeMethod::SobelThinning, "sobel-thinning"},
                                           {EdgeMethod::Laplace, "laplace"}};
constexpr EnumEntry<ConnectivityMethod> kConnectivity[] = {{ConnectivityMethod::CN0, "cn0"},
                                                           {ConnectivityMethod::CN1, "cn1"}};
constexpr EnumEntry<EllipseMethod> kEllipse[] = {{EllipseMethod::Bennett, "bennett"},
                                                 {EllipseMethod::DirectFit, "direct-fit"}};
constexpr EnumEntry<FitAcceptRule> kAccept[] = {{FitAcceptRule::RelativeError, "relative-error"},
                                                {FitAcceptRule::SampsonDistance, "sampson-distance"}};
constexpr EnumEntry<ContourMode> kContour[] = {{ContourMode::EightPointsOrg, "8-points-org"},
                                               {ContourMode::EightPointsMod, "8-points-mod"},
                                               {ContourMode::FullPathOrg, "full-path-org"},
                                               {ContourMode::FullPathMod, "full-path-mod"},
                                               {ContourMode::SubPixel, "subpixel"}};
constexpr EnumEntry<TrackingMode> kTracking[] = {{TrackingMode::Off, "off"},
                                                 {TrackingMode::Corners2D, "2d-corners"},
                                                 {TrackingMode::Parameters3D, "3d-parameters"}};
constexpr EnumEntry<ApplicationLevel> kLevel[] = {{ApplicationLevel::Source, "source"},
                                                  {ApplicationLevel::Threshold, "threshold"},
                                                  {ApplicationLevel::Edges, "edges"},
                                                  {ApplicationLevel::Connectivity, "connectivity"},
                                                  {ApplicationLevel::Ellipse, "ellipse"},
                                                  {ApplicationLevel::Reconstruction, "reconstruction"}};
constexpr EnumEntry<DisplayOptions::Background> kBackground[] = {
    {DisplayOptions::Background::Empty, "empty"},
    {DisplayOptions::Background::Source, "source"},
    {DisplayOptions::Background::Binary, "binary"}};
constexpr EnumEntry<DisplayOptions::Edges> kEdgeDisplay[] = {
    {DisplayOptions::Edges::None, "none"},
    {DisplayOptions::Edges::EdgePixels, "edges"},
    {DisplayOptions::Edges::ConnectedPaths, "connected-paths"}};
constexpr EnumEntry<DisplayOptions::Target> kTargetDisplay[] = {
    {DisplayOptions::Target::None, "none"},
    {DisplayOptions::Target::Path, "path"},
    {DisplayOptions::Target::Source, "source"},
    {DisplayOptions::Target::Binary, "binary"}};
constexpr EnumEntry<Binarization> kBinarization[] = {{Binarization::Global, "global"},
                                                     {Binarization::Local, "local"},
                                                     {Binarization::GlobalThenLocal, "global-then-local"}};
constexpr EnumEntry<RenderMode> kRender[] = {{RenderMode::Binary, "binary"}, {RenderMode::Grey, "grey"}};
constexpr EnumEntry<MotionKind> kMotion[] = {{MotionKind::Static, "static"},
                                             {MotionKind::Sinusoid, "sinusoid"},
                                             {MotionKind::SawTooth, "saw-tooth"},
                                             {MotionKind::Pendulum, "pendulum"}};
constexpr EnumEntry<PoseAxis> kAxis[] = {{PoseAxis::Tx, "tx"}, {PoseAxis::Ty, "ty"}, {PoseAxis::Tz, "tz"},
                                         {PoseAxis::Rx, "rx"}, {PoseAxis::Ry, "ry"}, {PoseAxis::Rz, "rz"}};
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
std::span<const EnumEntry<MotionKind>> enumEntries(MotionKind) { return kMotion; }
std::span<const EnumEntry<PoseAxis>> enumEntries(PoseAxis) { return kAxis; }

}  // namespace imagepro
