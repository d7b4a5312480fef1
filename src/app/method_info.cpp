#include "app/method_info.h"

#include <QObject>

namespace imagepro::app {

namespace {
QString tr(const char* text) { return QObject::tr(text); }
}  // namespace

QString methodToolTip(ThresholdMethod m) {
  switch (m) {
    case ThresholdMethod::None: return tr("No re-thresholding: the first binary image is used for the target (thesis 2.3)");
    case ThresholdMethod::Manual: return tr("Manual: the constant threshold Val, pixels above it are white (thesis 2.3, eq. 2.1)");
    case ThresholdMethod::AtOrig: return tr("AT-Orig: Kittler-Illingworth minimum error threshold, sums recomputed for every t (thesis 2.3, eqs. 2.4-2.10)");
    case ThresholdMethod::AtMod: return tr("AT-Mod: the same minimum error criterion, computed incrementally with moment vectors (thesis 2.3, eqs. 2.11-2.17)");
  }
  return {};
}

QString methodToolTip(EdgeMethod m) {
  switch (m) {
    case EdgeMethod::SobelThinning: return tr("Sobel + thinning: gradient magnitude and three-pixel thinning, the earlier method (thesis 2.4, eq. 2.21)");
    case EdgeMethod::Laplace: return tr("Laplace: a white pixel with a black 4-neighbour, Sobel gradients at edge pixels only (thesis 2.4, eq. 2.25)");
  }
  return {};
}

QString methodToolTip(ConnectivityMethod m) {
  switch (m) {
    case ConnectivityMethod::CN0: return tr("CN0: the corrected grouping of the earlier study, O(n^2) (thesis 2.5)");
    case ConnectivityMethod::CN1: return tr("CN1: one-pass grouping of 8-connected edge pixels, O(n) (thesis 2.5)");
  }
  return {};
}

QString methodToolTip(EllipseMethod m) {
  switch (m) {
    case EllipseMethod::Bennett: return tr("Bennett: per-path accumulator with score, quality and symmetry rules (thesis 2.6.1)");
    case EllipseMethod::DirectFit: return tr("Direct fit: Fitzgibbon's least-squares ellipse fit, accepted by its relative error (thesis 2.6.2, eq. 2.42)");
  }
  return {};
}

QString methodToolTip(FitAcceptRule m) {
  switch (m) {
    case FitAcceptRule::RelativeError: return tr("Accept a fit whose relative error E_rel is below the limit (thesis 2.6.2, eq. 2.42)");
    case FitAcceptRule::SampsonDistance: return tr("Accept a fit whose mean Sampson distance in pixels is below the limit (scale invariant)");
  }
  return {};
}

QString methodToolTip(ContourMode m) {
  switch (m) {
    case ContourMode::EightPointsOrg: return tr("8 points ORG: eight contour points, the original method (thesis appendix A, Reconstruction)");
    case ContourMode::EightPointsMod: return tr("8 points MOD: eight contour points, the more reliable version (thesis appendix A, Reconstruction)");
    case ContourMode::FullPathOrg: return tr("Full path ORG: every contour pixel, the original method (thesis appendix A, Reconstruction)");
    case ContourMode::FullPathMod: return tr("Full path MOD: every contour pixel, the more reliable version (thesis appendix A, Reconstruction)");
    case ContourMode::SubPixel: return tr("Sub-pixel: the grey-level edge along the gradient (beyond the thesis, its recommendation 6.3)");
  }
  return {};
}

QString methodToolTip(TrackingMode m) {
  switch (m) {
    case TrackingMode::Off: return tr("No tracking: every frame is searched whole");
    case TrackingMode::Corners2D: return tr("2D corners: extrapolate the corners of the detected region (thesis 3.3)");
    case TrackingMode::Parameters3D: return tr("3D parameters: extrapolate the six parameters and project the target (thesis 3.3)");
  }
  return {};
}

QString methodToolTip(ApplicationLevel m) {
  switch (m) {
    case ApplicationLevel::Source: return tr("Grab the frame only (thesis 2.2)");
    case ApplicationLevel::Threshold: return tr("Up to thresholding (thesis 2.3)");
    case ApplicationLevel::Edges: return tr("Up to edge detection (thesis 2.4)");
    case ApplicationLevel::Connectivity: return tr("Up to connectivity analysis (thesis 2.5)");
    case ApplicationLevel::Ellipse: return tr("Up to ellipse detection (thesis 2.6)");
    case ApplicationLevel::Reconstruction: return tr("The whole pipeline: 3D reconstruction and tracking (thesis figure 5.1)");
  }
  return {};
}

QString methodToolTip(DisplayOptions::Background m) {
  switch (m) {
    case DisplayOptions::Background::Empty: return tr("A black background");
    case DisplayOptions::Background::Source: return tr("The input frame");
    case DisplayOptions::Background::Binary: return tr("The thresholded search region");
  }
  return {};
}

QString methodToolTip(DisplayOptions::Edges m) {
  switch (m) {
    case DisplayOptions::Edges::None: return tr("No edges drawn");
    case DisplayOptions::Edges::EdgePixels: return tr("The edge pixels of the selected edge detection method (thesis 2.4)");
    case DisplayOptions::Edges::ConnectedPaths: return tr("Each connected path in its own colour (thesis 2.5)");
  }
  return {};
}

QString methodToolTip(DisplayOptions::Target m) {
  switch (m) {
    case DisplayOptions::Target::None: return tr("The target is not drawn");
    case DisplayOptions::Target::Path: return tr("The detected ellipse");
    case DisplayOptions::Target::Source: return tr("The grey image of the target region");
    case DisplayOptions::Target::Binary: return tr("The binary image of the target region");
  }
  return {};
}

QString methodToolTip(RenderMode m) {
  switch (m) {
    case RenderMode::Binary: return tr("Binary frames as in the thesis (2.2)");
    case RenderMode::Grey: return tr("Anti-aliased grey frames with optional blur, noise, gradient and clutter");
  }
  return {};
}

QString methodToolTip(MotionKind m) {
  switch (m) {
    case MotionKind::Static: return tr("The target stays put (the keys still move it)");
    case MotionKind::Sinusoid: return tr("A sinusoid along or about the chosen axis");
    case MotionKind::SawTooth: return tr("A saw-tooth along or about the chosen axis");
    case MotionKind::Pendulum: return tr("A pendulum swinging from a pivot (thesis 5.3.2)");
  }
  return {};
}

QString methodToolTip(PoseAxis m) {
  switch (m) {
    case PoseAxis::Tx: case PoseAxis::Ty: case PoseAxis::Tz: return tr("Translation, mm");
    case PoseAxis::Rx: case PoseAxis::Ry: case PoseAxis::Rz: return tr("Rotation, degrees");
  }
  return {};
}

}  // namespace imagepro::app
