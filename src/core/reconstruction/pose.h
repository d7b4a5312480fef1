#pragma once
// Analytic, non-iterative pose of the target from its undistorted image (thesis 1.4):
// the ellipse of the disk's rim and the images of the two spots give Rx, Ry, Rz, Tx, Ty, Tz.
//
// The image conic C and the camera centre define an oblique cone Q = K^T C K (K the
// pinhole matrix). Ordering its eigenvalues l1 >= l2 > 0 > l3 (eigenvectors e1, e2, e3),
// Q - l2*I is a pair of planes, so every plane with normal
//     n = (+-sqrt(l1 - l2) e1 + sqrt(l2 - l3) e3) / sqrt(l1 - l3)
// cuts the cone in a circle; for radius R the plane lies at distance
//     d = R l2 / sqrt(-l1 l3)
// from the camera and the circle's centre is
//     c = d / (l2 sqrt(l1 - l3)) * (+-sqrt(l1 - l2) l3 e1 + sqrt(l2 - l3) l1 e3).
// Of the two candidates, the one whose centre projects onto the centre spot's image is
// the target; the offset spot's ray, cut with that plane, gives the target's +X axis and
// so Rz. The target's +Z is the plane normal pointing away from the camera.
//
// The centroid of a spot's image is not the image of the spot's centre (perspective moves
// it by a fraction of a pixel); once the plane is known this offset is computed in closed
// form from the spot's own image conic and removed before Rz is taken.
#include <Eigen/Core>
#include <array>

#include "core/common/geometry.h"
#include "core/common/status.h"
#include "core/ellipse/ellipse.h"

namespace imagepro {

struct CircleCandidate {
  Eigen::Vector3d normal;  // unit, camera frame, pointing away from the camera (n . centre > 0)
  Eigen::Vector3d centre;  // mm, camera frame
};

// The two circles of the given radius whose image (ideal, undistorted pixels) is `conic`.
// SingularConic when the cone is degenerate or has no real points, NotAnEllipse when the
// image conic is not an ellipse.
Status circleCandidates(const CameraModel& cam, const Conic& undistortedConic, double radius_mm,
                        std::array<CircleCandidate, 2>& out);

// The target's pose from its undistorted rim ellipse and the undistorted centroids of the
// centre and offset spots' images. The plane's normal is the cone's eigen-structure's; with
// `weighCentreSpot` it is averaged with the centre spot's polar line (normalFromPolarLine,
// the spot's perspective offset removed), each weighed by the inverse square of how far its
// expected pixel error (in the rim's axes, in the spot's image) turns it. Head-on, where the
// rim's ellipse is nearly a circle, the polar line then takes over.
// Errors: SingularConic / NotAnEllipse (conic), CentreSpotOutsideEllipse, NormalFacingAway
// (the target plane would be seen edge-on or from behind, or the offset spot's ray meets it
// behind the camera), SpotsNotFound (the offset spot is not where the target's geometry
// puts it relative to the centre).
// `candidates`, when given, receives both circles' poses (the chosen one first) and how
// well each reprojects the spots.
struct PoseCandidates {
  std::array<Pose, 2> pose{};
  std::array<Status, 2> status{Status::Stopped, Status::Stopped};
  std::array<std::array<double, 2>, 2> spot_errors_px{};  // spotReprojectionErrors of each (when Ok)
  double normals_apart_deg = 0.0;                 // the angle between the two circles' normals
};
Status poseFromEllipse(const CameraModel& cam, const TargetGeometry& target,
                       const Conic& undistortedConic, const Eigen::Vector2d& centreSpotPx,
                       const Eigen::Vector2d& offsetSpotPx, Pose& out,
                       bool weighCentreSpot = true, PoseCandidates* candidates = nullptr);

// The centre and the offset spot's distances (ideal pixels) between the observed centroid
// and where `pose` puts the spot's image centroid (its centre's image plus the perspective
// offset of spotCentroidOffset).
std::array<double, 2> spotReprojectionErrors(const CameraModel& cam, const TargetGeometry& target, const Pose& pose,
                             const Eigen::Vector2d& centreSpotPx, const Eigen::Vector2d& offsetSpotPx);

// The plane normal from the polar line of the centre spot's image with respect to the conic
// (the plane's vanishing line). Exact in theory for the image of the disk's centre; alone it
// depends on one point and, beyond about 10 deg of tilt, is far more sensitive to noise than
// the eigen-structure (docs/accuracy.md). Unit, pointing away from the camera.
Status normalFromPolarLine(const CameraModel& cam, const Conic& undistortedConic,
                           const Eigen::Vector2d& centreSpotPx, Eigen::Vector3d& normal);

// The image conic (ideal pixels) of a circle in the target plane: centre (x, y) and radius
// in target coordinates (mm), seen at `pose`. Used for the spot correction and by tests.
Eigen::Matrix3d imageConicOfTargetCircle(const CameraModel& cam, const Pose& pose, double x_mm,
                                         double y_mm, double radius_mm);
// How far perspective moves the centroid of a spot's image (the centre of its image conic)
// from the image of the spot's centre: the spot of radius_mm at (x_mm, y_mm) on the target
// plane placed by R, T. False when the image conic has no centre.
bool spotCentroidOffset(const CameraModel& cam, const Eigen::Matrix3d& R, const Eigen::Vector3d& T,
                        double x_mm, double y_mm, double radius_mm, Eigen::Vector2d& offset);
// Centre of a (central) conic given as a 3x3 symmetric matrix; false when it has none.
bool conicMatrixCentre(const Eigen::Matrix3d& M, Eigen::Vector2d& centre);

}  // namespace imagepro
