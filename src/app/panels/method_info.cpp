#include "app/panels/method_info.h"

#include <QObject>

namespace imagepro::app {

namespace {
QString tr(const char* text) { return QObject::tr(text); }
}  // namespace

QString methodToolTip(ThresholdMethod m) {
  switch (m) {
    case ThresholdMethod::None: return tr("None: no re-thresholding; the target's crop is cut at the frame's own threshold (thesis A.1.1, Re-Thresholding panel: the by-pass)");
    case ThresholdMethod::Manual: return tr("Manual: the constant threshold Val, pixels above it are white (thesis 2.3, eq. 2.1)");
    case ThresholdMethod::AtOrig: return tr("AT-Orig: Kittler-Illingworth minimum error threshold, the sums recomputed for every t (thesis 2.3.1, eqs. 2.4-2.10)");
    case ThresholdMethod::AtMod: return tr("AT-Mod: the same minimum error criterion, computed incrementally with moment vectors (thesis 2.3.2, eqs. 2.11-2.17)");
  }
  return {};
}

QString methodToolTip(Binarization m) {
  switch (m) {
    case Binarization::Global: return tr("Global: one threshold for the whole searched region, the method above (thesis 2.3)");
    case Binarization::Local: return tr("Local: each pixel against the mean of its window; black where clearly darker than its surroundings (uneven light)");
    case Binarization::GlobalThenLocal: return tr("Global, then local: the thesis's threshold, and when that misses the target a second pass on the local binary image");
  }
  return {};
}

QString methodToolTip(EdgeMethod m) {
  switch (m) {
    case EdgeMethod::SobelThinning: return tr("Sobel + thinning: every pixel with a non-zero Sobel gradient, then the three-pixel thinning; the earlier method, kept for comparison (thesis 2.4.1-2.4.2, eq. 2.21)");
    case EdgeMethod::Laplace: return tr("Laplace: a white pixel with a black 4-neighbour, one pixel thick; Sobel gradients at the edge pixels only (thesis 2.4.3, eq. 2.25)");
  }
  return {};
}

QString methodToolTip(ConnectivityMethod m) {
  switch (m) {
    case ConnectivityMethod::CN0: return tr("CN0: the earlier study's grouping, its bugs and path limit removed; scans every unassigned pixel, O(n^2) (thesis 2.5)");
    case ConnectivityMethod::CN1: return tr("CN1: one-pass grouping of 8-connected edge pixels through an index image, O(n) (thesis 2.5.1)");
  }
  return {};
}

QString methodToolTip(EllipseMethod m) {
  switch (m) {
    case EllipseMethod::Bennett: return tr("Bennett: one accumulator per connected path, accepted by its symmetry, quality, score and peak-share rules; the ellipse itself from the direct fit of the path (thesis 2.6.1, eqs. 2.26-2.28)");
    case EllipseMethod::DirectFit: return tr("Direct fit: Fitzgibbon's least-squares ellipse fit of each path, accepted by the accept rule (E_rel of eq. 2.42 or the Sampson distance) when the path also traces the ellipse (thesis 2.6.2)");
  }
  return {};
}

QString methodToolTip(FitAcceptRule m) {
  switch (m) {
    case FitAcceptRule::RelativeError: return tr("Accept a fit whose relative error E_rel (in the fit's normalised coordinates) is below Max E_rel and whose path traces it (thesis 2.6.2, eq. 2.42)");
    case FitAcceptRule::SampsonDistance: return tr("Accept a fit whose mean Sampson distance in pixels is below Max Sampson and whose path traces it (beyond the thesis 2.6.2)");
  }
  return {};
}

QString methodToolTip(ContourMode m) {
  switch (m) {
    case ContourMode::EightPointsOrg:
      return tr("8 points ORG: from the detected centre, walk pixel by pixel along the 8 directions E, SE, S, ... "
                "across the centre spot, then across white; the last white pixel before black, at its pixel centre. "
                "The earlier study's method (thesis A.1.1, Reconstruction panel)");
    case ContourMode::EightPointsMod:
      return tr("8 points MOD: the same 8 rays, walked in 1/16 px steps from outside the detected rim inwards within "
                "+-w px of it (w = 2.5 px + 4 % of the semi-major axis); the point between the last black and the first "
                "white sample, that white followed by a second white pixel. The improved version (thesis A.1.1, "
                "Reconstruction panel)");
    case ContourMode::FullPathOrg:
      return tr("Full path ORG: the disk's outer boundary in the binary crop: the first and the last white pixel of "
                "every row and every column, each pixel once, at its pixel centre. The earlier study's method "
                "(thesis A.1.1, Reconstruction panel)");
    case ContourMode::FullPathMod:
      return tr("Full path MOD: one point per row or column crossing of the rim (rows where it runs closer to vertical, "
                "columns elsewhere), searched from outside inwards within +-w px of the detected rim: the first white "
                "pixel after black and before a second white one, the point on the pixel boundary. The improved "
                "version (thesis A.1.1, Reconstruction panel)");
    case ContourMode::SubPixel:
      return tr("Sub-pixel: full path MOD's crossings (about 160 on a large rim) placed in the grey levels, by the area "
                "under the grey profile across the edge, or where the profile crosses the mean of its two plateaus; "
                "independent of the threshold (beyond the thesis: its recommendation 6.3)");
  }
  return {};
}

QString methodToolTip(TrackingMode m) {
  switch (m) {
    case TrackingMode::Off: return tr("No tracking: every frame is searched whole");
    case TrackingMode::Corners2D: return tr("2D corners: polynomials over the last points of the target box's upper-left and lower-right corners give the next box (thesis 3.2.2.1)");
    case TrackingMode::Parameters3D: return tr("3D parameters: polynomials over the last six parameters give the next pose, the target projected through the camera gives the box (thesis 3.2.2.2)");
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
