// A planar track curve parameterised by arc length: straight, clothoid and circular-arc segments.
// Position, heading, curvature and its derivative are exact (closed form, or Gauss-Legendre
// quadrature to round-off for the clothoid's Fresnel integrals). The same templated arithmetic
// serves the double geometry and the AD passes that differentiate the track's numbers.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "mbsopt/model/scalar.hpp"

namespace mbsopt {

/// Geometry of the track at one arc length, in the track's base frame (curve in its x-y plane).
template <class Scalar>
struct TrackPointTpl {
  Vector3<Scalar> position = Vector3<Scalar>::Zero();
  Scalar heading = Scalar(0);               ///< ψ(s): angle of the tangent from the base x axis, about z
  Scalar cos_heading = Scalar(1);           ///< cos ψ(s)
  Scalar sin_heading = Scalar(0);           ///< sin ψ(s)
  Scalar curvature = Scalar(0);             ///< κ(s) = dψ/ds, positive when turning left
  Scalar curvature_derivative = Scalar(0);  ///< dκ/ds

  Vector3<Scalar> tangent() const { return {cos_heading, sin_heading, Scalar(0)}; }
  Vector3<Scalar> normal() const { return {-sin_heading, cos_heading, Scalar(0)}; }  ///< points to the left
};
using TrackPoint = TrackPointTpl<double>;

enum class TrackSegmentType { Straight, Clothoid, Arc };

/// The numbers a track is written with, as the scene file writes them: its start (origin, heading)
/// and per segment a straight's {length}, an arc's {radius, angle} (angle > 0 turns left), a
/// clothoid's {length, end_curvature} (its curvature runs linearly from the previous segment's end).
template <class Scalar>
struct TrackNumbersTpl {
  Vector3<Scalar> origin = Vector3<Scalar>::Zero();
  Scalar heading = Scalar(0);
  std::vector<TrackSegmentType> types;
  std::vector<std::array<Scalar, 2>> numbers;  ///< a straight's second number is unused (zero)
};
using TrackNumbers = TrackNumbersTpl<double>;

/// How many numbers a segment of this type is written with (1 or 2), and the name of number i
/// ("length", "radius", "angle", "end_curvature").
int numberCount(TrackSegmentType type);
const char* numberName(TrackSegmentType type, int i);

/// The geometry at arc length s of the track `numbers` describe, every segment's start computed
/// afresh from the numbers: exact (as Track::at) for a scalar that carries derivatives in s and in
/// the numbers, which is how an AD pass differentiates a track's numbers as design variables.
/// O(number of segments) per call; Track::at caches the starts for the double geometry.
template <class Scalar>
TrackPointTpl<Scalar> trackPointAt(const TrackNumbersTpl<Scalar>& numbers, const Scalar& s);

class Track {
 public:
  using SegmentType = TrackSegmentType;
  struct Segment {
    SegmentType type;
    double length;
    double curvature_start;
    double curvature_end;
  };

  /// Starts at `origin` with heading `heading` (radians, about z).
  explicit Track(Eigen::Vector3d origin = Eigen::Vector3d::Zero(), double heading = 0.0);
  /// The track the numbers describe, with the checks of the builders (std::invalid_argument).
  explicit Track(const TrackNumbers& numbers);

  Track& straight(double length);
  /// Circular arc of radius `radius`; positive `angle` turns left, negative turns right.
  Track& arc(double radius, double angle);
  /// Curvature varying linearly from the current end curvature to `curvature_end`.
  Track& clothoid(double length, double curvature_end);

  double length() const { return starts_.empty() ? 0.0 : starts_.back().arc_length + segments_.back().length; }
  const std::vector<Segment>& segments() const { return segments_; }
  /// The numbers it was built with (Track(numbers) rebuilds it).
  const TrackNumbers& numbers() const { return numbers_; }

  /// Exact geometry at arc length s. Beyond the ends the track continues straight along its end
  /// tangent, so Newton iterates that overshoot slightly stay well defined.
  TrackPoint at(double s) const;

 private:
  struct SegmentStart {
    double arc_length;
    Eigen::Vector3d position;
    double heading, cos_heading, sin_heading;
  };
  void append(TrackSegmentType type, double first, double second);

  TrackNumbers numbers_;
  std::vector<Segment> segments_;
  std::vector<SegmentStart> starts_;
};

/// Track geometry at arc length s for a scalar type that may carry derivatives in s: the exact
/// values at the value of s, carried to first order in s (dr/ds = t, dψ/ds = κ, dκ/ds = κ',
/// piecewise κ'' = 0), which is all a first-order derivative type needs. For double it is just the
/// exact geometry.
template <class Scalar>
TrackPointTpl<Scalar> trackStateAt(const Track& track, const Scalar& s) {
  const TrackPoint p = track.at(valueOf(s));
  if constexpr (std::is_same_v<Scalar, double>) {
    return p;
  } else {
    const Scalar ds = s - Scalar(valueOf(s));       // zero, with the derivatives of s
    const Scalar turn = Scalar(p.curvature) * ds;  // ψ(s) − ψ(value(s)), dψ = κ ds
    TrackPointTpl<Scalar> out;
    out.position = p.position.cast<Scalar>() + p.tangent().cast<Scalar>() * ds;
    out.heading = Scalar(p.heading) + turn;
    out.cos_heading = Scalar(p.cos_heading) - Scalar(p.sin_heading) * turn;
    out.sin_heading = Scalar(p.sin_heading) + Scalar(p.cos_heading) * turn;
    out.curvature = Scalar(p.curvature) + Scalar(p.curvature_derivative) * ds;
    out.curvature_derivative = Scalar(p.curvature_derivative);
    return out;
  }
}

extern template TrackPointTpl<double> trackPointAt<double>(const TrackNumbersTpl<double>&, const double&);
extern template TrackPointTpl<AdScalar> trackPointAt<AdScalar>(const TrackNumbersTpl<AdScalar>&, const AdScalar&);

}  // namespace mbsopt
