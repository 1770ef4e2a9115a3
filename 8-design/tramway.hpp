// The paper's example (§6) as fixed by docs/tramway.md: a two-carbody tram on two bogies,
// yaw plane, through a 14 m curve at 3.7 m/s.
#pragma once

#include <memory>

#include "mbsopt/model/track.hpp"
#include "mbsopt/integrators/scene.hpp"
#include "mbsopt/sensitivity/design_problem.hpp"

namespace mbsopt {

/// The design variables b = (k_f, k_r, c_f, c_r) of the spec, SI units.
struct TramwayDesign {
  double front_stiffness = 246e3;  ///< k_f [N·m/rad]
  double rear_stiffness = 246e3;   ///< k_r [N·m/rad]
  double front_damping = 15e3;     ///< c_f [N·m·s/rad]
  double rear_damping = 15e3;      ///< c_r [N·m·s/rad]
};

/// Which joint coordinates carry the bogies' yaw. Both describe the same mechanism (same
/// configuration space, energy and dissipation); they differ as discrete systems.
enum class BogieYawChart {
  /// Absolute bogie yaw: translating curve sliders, guidance springs acting on yaw − ψ(s), the
  /// loop closed by holding bogie 2's centre on the track (2 equations in the plane). Every
  /// coordinate is C² in time even where the track curvature jumps. The default.
  Absolute,
  /// The spec's literal topology: bogie yaw relative to the track tangent (sliders that turn with
  /// the track, joint springs), loop closed by a weld to the track frame at s₂ (3 equations in the
  /// plane). Where κ jumps, the inertia term I(κ s̈ + κ' ṡ²) holds a Dirac in κ' that a piecewise
  /// track cannot carry: the integrated relative yaw rate stays continuous, so the bogie's absolute
  /// yaw rate jumps by Δκ·ṡ (a non-physical kick). Exact only on tracks with continuous curvature.
  RelativeToTrack
};

struct TramwayOptions {
  double transition_length = 0.0;  ///< L_t [m]: clothoids at both ends of the arc (0 = the spec's track)
  double arc_angle = 1.5707963267948966;  ///< total turn of the curve [rad] (the spec: 90°)
  double speed = 3.7;              ///< [m/s]: bogie 1's constant speed
  BogieYawChart chart = BogieYawChart::Absolute;
};

namespace tramway {
inline constexpr double kRadius = 14.0;         ///< R [m]
inline constexpr double kFirstStraight = 12.0;  ///< [m]
inline constexpr double kLastStraight = 30.0;   ///< [m]
inline constexpr double kStartArcLength = 10.0; ///< s₁(0) [m]
inline constexpr double kEndTime = 12.0;        ///< [s]
inline constexpr double kBogieSpacing = 9.0;    ///< pivot to articulation 4.5 m on each carbody [m]
}  // namespace tramway

/// Straight 12 m, optional clothoid, left arc R = 14 m (90° in all by default), optional clothoid,
/// straight 30 m. The scene adds it as the track "rail" (its numbers are parameters rail.…).
Track tramwayTrack(const TramwayOptions& options = {});

/// The scene: coordinates s₁ (driven), bogie-1 yaw, front pivot, articulation, rear pivot,
/// [bogie-2 yaw, RelativeToTrack chart only], s₂ (cut curve slider); sensors a_lat, yaw_front,
/// yaw_rear. Settings: h = 1 ms, 12 s.
Scene tramwayScene(const TramwayDesign& design = {}, const TramwayOptions& options = {});

/// The design problem of the spec (docs/tramway.md, "Design problem"): b = (k_f, k_r, c_f,
/// c_r) scaled to kN·m/rad and kN·m·s/rad, cost max |a_lat| through b5 (initially 3 m/s², bounds
/// [0, 10]), |yaw_front|, |yaw_rear| ≤ 10°, the paper's ∫⟨φ⟩dt ≤ 0. The same as the `design:`
/// section of problems/scenes/tramway.yaml.
DesignProblem tramwayDesignProblem(const TramwayDesign& design = {}, const TramwayOptions& options = {});

}  // namespace mbsopt
