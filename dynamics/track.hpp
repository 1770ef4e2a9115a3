// A planar track curve parameterised by arc length: straight, clothoid and circular-arc segments.
// Position, heading, curvature and its derivative are exact (closed form, or Gauss-Legendre
// quadrature to round-off for the clothoid's Fresnel integrals).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "dynamics/scalar.hpp"

namespace mbsopt {

/// Geometry of the track at one arc length, in the track's base frame (curve in its x-y plane).
struct TrackPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double heading = 0.0;              ///< ψ(s): angle of the tangent from the base x axis, about z
  double cos_heading = 1.0;          ///< cos ψ(s)
  double sin_heading = 0.0;          ///< sin ψ(s)
  double curvature = 0.0;            ///< κ(s) = dψ/ds, positive when turning left
  double curvature_derivative = 0.0; ///< dκ/ds

  Eigen::Vector3d tangent() const { return {cos_heading, sin_heading, 0.0}; }
  Eigen::Vector3d normal() const { return {-sin_heading, cos_heading, 0.0}; }  ///< points to the left
};

/// Track geometry at arc length s for a scalar type that may carry derivatives: the exact values at
/// the value of s, carried to first order in s (dψ/ds = κ, dκ/ds = κ', piecewise κ'' = 0), which is
/// all a first-order derivative type needs. For double it is just the exact geometry.
template <class Scalar>
struct TrackState {
  TrackPoint point;    ///< exact geometry at the value of s
  Scalar offset;       ///< s − value(s): zero, with the derivatives of s
  Scalar heading;      ///< ψ(s)
  Scalar cos_heading;  ///< cos ψ(s)
  Scalar sin_heading;  ///< sin ψ(s)
  Scalar curvature;    ///< κ(s)
};

class Track {
 public:
  enum class SegmentType { Straight, Clothoid, Arc };
  struct Segment {
    SegmentType type;
    double length;
    double curvature_start;
    double curvature_end;
  };

  /// Starts at `origin` with heading `heading` (radians, about z).
  explicit Track(Eigen::Vector3d origin = Eigen::Vector3d::Zero(), double heading = 0.0);

  Track& straight(double length);
  /// Circular arc of radius `radius`; positive `angle` turns left, negative turns right.
  Track& arc(double radius, double angle);
  /// Curvature varying linearly from the current end curvature to `curvature_end`.
  Track& clothoid(double length, double curvature_end);

  double length() const { return starts_.empty() ? 0.0 : starts_.back().arc_length + segments_.back().length; }
  const std::vector<Segment>& segments() const { return segments_; }

  /// Exact geometry at arc length s. Beyond the ends the track continues straight along its end
  /// tangent, so Newton iterates that overshoot slightly stay well defined.
  TrackPoint at(double s) const;

 private:
  struct SegmentStart {
    double arc_length;
    Eigen::Vector3d position;
    double heading, cos_heading, sin_heading;
  };
  void append(const Segment& segment);
  static TrackPoint advance(const Segment& segment, const SegmentStart& start, double sigma);

  Eigen::Vector3d origin_;
  double heading_, cos_heading_, sin_heading_;
  std::vector<Segment> segments_;
  std::vector<SegmentStart> starts_;
};

template <class Scalar>
TrackState<Scalar> trackStateAt(const Track& track, const Scalar& s) {
  TrackState<Scalar> state{track.at(valueOf(s)), s - Scalar(valueOf(s)), Scalar(0), Scalar(0), Scalar(0), Scalar(0)};
  const TrackPoint& p = state.point;
  const Scalar turn = Scalar(p.curvature) * state.offset;  // ψ(s) − ψ(value(s)): zero, with dψ = κ ds
  state.heading = Scalar(p.heading) + turn;
  state.cos_heading = Scalar(p.cos_heading) - Scalar(p.sin_heading) * turn;
  state.sin_heading = Scalar(p.sin_heading) + Scalar(p.cos_heading) * turn;
  state.curvature = Scalar(p.curvature) + Scalar(p.curvature_derivative) * state.offset;
  return state;
}

}  // namespace mbsopt
