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
  double curvature = 0.0;            ///< κ(s) = dψ/ds, positive when turning left
  double curvature_derivative = 0.0; ///< dκ/ds

  Eigen::Vector3d tangent() const;   ///< (cos ψ, sin ψ, 0)
  Eigen::Vector3d normal() const;    ///< (−sin ψ, cos ψ, 0), points to the left
};

/// Track geometry at arc length s for a scalar type that may carry derivatives: the exact values at
/// the value of s, carried to first order in s (dψ/ds = κ, dκ/ds = κ', piecewise κ'' = 0), which is
/// all a first-order derivative type needs. For double it is just the exact geometry.
template <class Scalar>
struct TrackState {
  TrackPoint point;   ///< exact geometry at the value of s
  Scalar offset;      ///< s − value(s): zero, with the derivatives of s
  Scalar heading;     ///< ψ(s)
  Scalar curvature;   ///< κ(s)
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
    double heading;
  };
  void append(const Segment& segment);
  static TrackPoint advance(const Segment& segment, const Eigen::Vector3d& position, double heading, double sigma);

  Eigen::Vector3d origin_;
  double heading_;
  std::vector<Segment> segments_;
  std::vector<SegmentStart> starts_;
};

template <class Scalar>
TrackState<Scalar> trackStateAt(const Track& track, const Scalar& s) {
  TrackState<Scalar> state{track.at(valueOf(s)), s - Scalar(valueOf(s)), Scalar(0), Scalar(0)};
  state.heading = Scalar(state.point.heading) + Scalar(state.point.curvature) * state.offset;
  state.curvature = Scalar(state.point.curvature) + Scalar(state.point.curvature_derivative) * state.offset;
  return state;
}

}  // namespace mbsopt
