#pragma once
// Motions of the Virtual perspective projection source (thesis 2.2, 3.3, 5.3.2):
// the pose of the target at time t for the motion of the settings, and the per-key
// pose increments of the keyboard in appendix A.2.1.
//
//  * static:    initial_pose.
//  * sinusoid:  initial_pose with  amplitude * sin(2 pi t / period)  added on `axis`.
//  * saw-tooth: the thesis's zig-zag (its tracking errors of table 3.1 rule out a jump):
//               initial_pose with a triangle wave of `amplitude` added on `axis`: 0 at
//               t = 0, rising at constant speed 4 amplitude / period to +amplitude at a
//               quarter period, down to -amplitude at three quarters, and back.
//  * pendulum:  the target hangs at `length` below `pivot` (+Y is down) and swings in
//               the vertical plane of heading swing_axis_deg about Y (0: along camera X);
//               its centre moves on the circle and the target turns with the rope, so
//               it keeps facing the camera at rest (orientation = swing rotation *
//               initial_pose's rotation; initial_pose's translation is not used).
//               The swing angle is the exact large-amplitude solution of
//               theta'' = -(g / L) sin(theta):  sin(theta / 2) = k sn(omega0 t, k),
//               k = sin(amplitude / 2), omega0 = sqrt(g / L), with the Jacobi elliptic
//               function sn computed by the arithmetic-geometric mean. Period
//               4 K(k) / omega0, which tends to eq. 5.1 (2 pi sqrt(L / g)) for small
//               amplitudes. t = 0 is the lowest point, moving towards +swing direction.
//  * constant velocity: each parameter of initial_pose advances by velocity * t and wraps
//               around inside a box centred on initial_pose (wrap_box, its full width per
//               parameter): leaving it on one side, the target comes back in on the other,
//               as in the thesis's Settings menu velocities (appendix A.2). A width of 0
//               lets that parameter run on.
#include "core/common/geometry.h"
#include "core/settings/options.h"

namespace imagepro {

// The keys of appendix A: 4-6 Tx, 2-8 Ty, Insert-Delete Tz, Up-Down Rx, Left-Right Ry,
// Home-End Rz. Minus / Plus name the direction of the change.
enum class VirtualKey { TxMinus, TxPlus, TyMinus, TyPlus, TzMinus, TzPlus, RxMinus, RxPlus, RyMinus, RyPlus, RzMinus, RzPlus };

// Pose of the target at time t_s (seconds) for scene.motion / scene.pendulum.
Pose virtualPoseAt(const VirtualSceneOptions& scene, double t_s);

// The offset the keys build up starts at zero (a default Pose is 1000 mm deep, not zero).
inline constexpr Pose kZeroPoseOffset{0.0, 0.0, 0.0, 0.0, 0.0, 0.0};

// Adds one key press to `offset`: key_step_mm for translations, key_step_deg for rotations.
void applyKey(VirtualKey key, const VirtualSceneOptions& scene, Pose& offset);
// The pose with a key offset added, parameter by parameter.
Pose withOffset(const Pose& pose, const Pose& offset);

// Pendulum: exact period (s) and swing angle (deg) at time t_s.
double pendulumPeriodS(const PendulumOptions& pendulum);
double pendulumAngleDeg(const PendulumOptions& pendulum, double t_s);
// The pendulum's pose held at swing angle theta_deg (the target at rest there).
Pose pendulumPoseAtAngle(const VirtualSceneOptions& scene, double theta_deg);

}  // namespace imagepro
