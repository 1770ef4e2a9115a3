#include "mbsopt/model/track.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace mbsopt {

namespace {

// 6-point Gauss-Legendre rule on [-1, 1] (nodes and weights, positive half). On a panel of width w
// whose tangent turns by θ ≤ 0.25 rad, the n-point rule integrates (cos ψ, sin ψ) with a relative
// error of about θ^{2n} (n!)⁴ / ((2n + 1) ((2n)!)³) (the Gauss remainder with |d^{2n}/dx^{2n}| ≈
// (θ/w)^{2n}): 1e-23 for n = 6, far below round-off; n = 4 would leave 1e-14.
constexpr std::array<double, 3> kGaussNodes = {0.2386191860831969, 0.6612093864662645, 0.9324695142031521};
constexpr std::array<double, 3> kGaussWeights = {0.4679139345726910, 0.3607615730481386, 0.1713244923791704};

/// A segment's length and its curvature at both ends.
template <class Scalar>
struct SegmentShape {
  TrackSegmentType type;
  Scalar length, curvature_start, curvature_end;
};

/// Where a segment starts: position and heading.
template <class Scalar>
struct SegmentStartTpl {
  Vector3<Scalar> position;
  Scalar heading, cos_heading, sin_heading;
};

/// Segment k's shape from its written numbers, as the builders derive it: an arc of radius R turning
/// by θ is |θ| R long with curvature sign(θ)/R; a clothoid runs from the previous segment's end
/// curvature (`previous_end`) to its own.
template <class Scalar>
SegmentShape<Scalar> shapeOf(TrackSegmentType type, const std::array<Scalar, 2>& numbers, const Scalar& previous_end) {
  using std::abs;
  switch (type) {
    case TrackSegmentType::Straight: return {type, numbers[0], Scalar(0), Scalar(0)};
    case TrackSegmentType::Arc: {
      const Scalar curvature = (valueOf(numbers[1]) < 0.0 ? Scalar(-1) : Scalar(1)) / numbers[0];
      return {type, abs(numbers[1]) * numbers[0], curvature, curvature};
    }
    case TrackSegmentType::Clothoid: return {type, numbers[0], previous_end, numbers[1]};
  }
  throw std::logic_error("unknown track segment type");
}

/// Geometry at σ along a segment that starts at `start`.
template <class Scalar>
TrackPointTpl<Scalar> alongSegment(const SegmentShape<Scalar>& segment, const SegmentStartTpl<Scalar>& start,
                                   const Scalar& sigma) {
  using std::abs;
  using std::cos;
  using std::sin;
  TrackPointTpl<Scalar> point;
  const Scalar& k0 = segment.curvature_start;
  const Scalar dk = (segment.curvature_end - segment.curvature_start) / segment.length;
  const Scalar& heading = start.heading;
  const Vector3<Scalar>& position = start.position;
  point.curvature = k0 + dk * sigma;
  point.curvature_derivative = dk;
  point.heading = heading + k0 * sigma + Scalar(0.5) * dk * sigma * sigma;
  const Vector3<Scalar> tangent(start.cos_heading, start.sin_heading, Scalar(0));
  if (segment.type == TrackSegmentType::Straight) {  // the start's tangent throughout
    point.cos_heading = start.cos_heading;
    point.sin_heading = start.sin_heading;
    point.position = position + tangent * sigma;
    return point;
  }
  if (segment.type == TrackSegmentType::Arc) {
    // A circular arc turning by θ = κσ: the start's tangent turned by θ, and the chord
    // (sin θ t₀ + (1 − cos θ) n₀)/κ, one sine and cosine for both. 1 − cos θ is sin²θ/(1 + cos θ)
    // while cos θ > 0, with no cancellation for small θ.
    const Vector3<Scalar> normal(-start.sin_heading, start.cos_heading, Scalar(0));
    const Scalar turn = k0 * sigma;
    const Scalar sin_turn = sin(turn), cos_turn = cos(turn);
    const Scalar versine =
        valueOf(cos_turn) > 0.0 ? Scalar(sin_turn * sin_turn / (Scalar(1) + cos_turn)) : Scalar(Scalar(1) - cos_turn);
    point.cos_heading = start.cos_heading * cos_turn - start.sin_heading * sin_turn;
    point.sin_heading = start.sin_heading * cos_turn + start.cos_heading * sin_turn;
    point.position = position + tangent * Scalar(sin_turn / k0) + normal * Scalar(versine / k0);
    return point;
  }
  point.cos_heading = cos(point.heading);
  point.sin_heading = sin(point.heading);
  // Fresnel integrals ∫(cos ψ, sin ψ) dσ by composite Gauss-Legendre, panels turning ≤ 0.25 rad.
  const double sigma_value = valueOf(sigma);
  const double turn = std::abs(valueOf(k0)) * std::abs(sigma_value) + 0.5 * std::abs(valueOf(dk)) * sigma_value * sigma_value;
  const int panels = std::max(1, static_cast<int>(std::ceil(turn / 0.25)));
  const Scalar width = sigma / Scalar(panels);
  Scalar sum_x(0), sum_y(0);
  for (int p = 0; p < panels; ++p) {
    const Scalar centre = Scalar(p + 0.5) * width;
    for (std::size_t g = 0; g < kGaussNodes.size(); ++g) {
      for (double side : {-1.0, 1.0}) {
        const Scalar x = centre + Scalar(side * 0.5) * width * kGaussNodes[g];
        const Scalar psi = heading + k0 * x + Scalar(0.5) * dk * x * x;
        sum_x += kGaussWeights[g] * cos(psi);
        sum_y += kGaussWeights[g] * sin(psi);
      }
    }
  }
  const Scalar half_width = Scalar(0.5) * width;
  point.position = position + Vector3<Scalar>(half_width * sum_x, half_width * sum_y, Scalar(0));
  return point;
}

/// The next segment's start at a segment's end (its cosine and sine taken afresh from the heading).
template <class Scalar>
SegmentStartTpl<Scalar> startOf(const TrackPointTpl<Scalar>& end) {
  using std::cos;
  using std::sin;
  return {end.position, end.heading, cos(end.heading), sin(end.heading)};
}

/// Before the start, the track continues straight along its start tangent.
template <class Scalar>
TrackPointTpl<Scalar> beforeStart(const SegmentStartTpl<Scalar>& start, const Scalar& s) {
  TrackPointTpl<Scalar> point;
  point.heading = start.heading;
  point.cos_heading = start.cos_heading;
  point.sin_heading = start.sin_heading;
  point.position = start.position + point.tangent() * s;
  return point;
}

/// Beyond the end (`excess` past it), straight along the end tangent, without curvature.
template <class Scalar>
TrackPointTpl<Scalar> beyondEnd(TrackPointTpl<Scalar> end, const Scalar& excess) {
  end.position += end.tangent() * excess;
  end.curvature = Scalar(0);
  end.curvature_derivative = Scalar(0);
  return end;
}

template <class Scalar>
SegmentStartTpl<Scalar> originOf(const Vector3<Scalar>& origin, const Scalar& heading) {
  using std::cos;
  using std::sin;
  return {origin, heading, cos(heading), sin(heading)};
}

}  // namespace

int numberCount(TrackSegmentType type) { return type == TrackSegmentType::Straight ? 1 : 2; }

const char* numberName(TrackSegmentType type, int i) {
  switch (type) {
    case TrackSegmentType::Straight: return "length";
    case TrackSegmentType::Arc: return i == 0 ? "radius" : "angle";
    case TrackSegmentType::Clothoid: return i == 0 ? "length" : "end_curvature";
  }
  throw std::logic_error("unknown track segment type");
}

template <class Scalar>
TrackPointTpl<Scalar> trackPointAt(const TrackNumbersTpl<Scalar>& numbers, const Scalar& s) {
  if (numbers.types.empty()) throw std::logic_error("trackPointAt: the track has no segment");
  SegmentStartTpl<Scalar> start = originOf(numbers.origin, numbers.heading);
  if (valueOf(s) < 0.0) return beforeStart(start, s);
  Scalar arc_length(0), end_curvature(0);
  for (std::size_t k = 0;; ++k) {
    const SegmentShape<Scalar> segment = shapeOf(numbers.types[k], numbers.numbers[k], end_curvature);
    const Scalar next = arc_length + segment.length;
    const bool last = k + 1 == numbers.types.size();
    // The last segment whose start is ≤ s (right-continuous at a junction), as Track::at.
    if (valueOf(s) < valueOf(next) || last) {
      const Scalar sigma = s - arc_length;
      if (valueOf(sigma) <= valueOf(segment.length)) return alongSegment(segment, start, sigma);
      return beyondEnd(alongSegment(segment, start, segment.length), Scalar(sigma - segment.length));
    }
    start = startOf(alongSegment(segment, start, segment.length));
    arc_length = next;
    end_curvature = segment.curvature_end;
  }
}

template TrackPointTpl<double> trackPointAt<double>(const TrackNumbersTpl<double>&, const double&);
template TrackPointTpl<AdScalar> trackPointAt<AdScalar>(const TrackNumbersTpl<AdScalar>&, const AdScalar&);

Track::Track(Eigen::Vector3d origin, double heading) {
  numbers_.origin = std::move(origin);
  numbers_.heading = heading;
}

Track::Track(const TrackNumbers& numbers) : Track(numbers.origin, numbers.heading) {
  for (std::size_t k = 0; k < numbers.types.size(); ++k) {
    const auto& [first, second] = numbers.numbers[k];
    switch (numbers.types[k]) {
      case TrackSegmentType::Straight: straight(first); break;
      case TrackSegmentType::Arc: arc(first, second); break;
      case TrackSegmentType::Clothoid: clothoid(first, second); break;
    }
  }
}

Track& Track::straight(double length) {
  append(SegmentType::Straight, length, 0.0);
  return *this;
}

Track& Track::arc(double radius, double angle) {
  if (!(radius > 0.0) || !std::isfinite(radius)) throw std::invalid_argument("Track::arc: radius must be positive");
  if (angle == 0.0 || !std::isfinite(angle)) throw std::invalid_argument("Track::arc: an arc must turn (angle ≠ 0)");
  append(SegmentType::Arc, radius, angle);
  return *this;
}

Track& Track::clothoid(double length, double curvature_end) {
  if (!std::isfinite(curvature_end)) throw std::invalid_argument("Track::clothoid: the end curvature must be finite");
  append(SegmentType::Clothoid, length, curvature_end);
  return *this;
}

void Track::append(TrackSegmentType type, double first, double second) {
  const double previous_end = segments_.empty() ? 0.0 : segments_.back().curvature_end;
  const SegmentShape<double> shape = shapeOf<double>(type, {first, second}, previous_end);
  if (!(shape.length > 0.0) || !std::isfinite(shape.length))
    throw std::invalid_argument("Track: segment length must be positive and finite");
  SegmentStartTpl<double> start = originOf(numbers_.origin, numbers_.heading);
  double arc_length = 0.0;
  if (!segments_.empty()) {
    const Segment& last = segments_.back();
    const SegmentStart& from = starts_.back();
    start = startOf(alongSegment<double>({last.type, last.length, last.curvature_start, last.curvature_end},
                                         {from.position, from.heading, from.cos_heading, from.sin_heading},
                                         last.length));
    arc_length = from.arc_length + last.length;
  }
  numbers_.types.push_back(type);
  numbers_.numbers.push_back({first, type == TrackSegmentType::Straight ? 0.0 : second});
  segments_.push_back({type, shape.length, shape.curvature_start, shape.curvature_end});
  starts_.push_back({arc_length, start.position, start.heading, start.cos_heading, start.sin_heading});
}

TrackPoint Track::at(double s) const {
  if (segments_.empty()) throw std::logic_error("Track::at: the track has no segment");
  if (s < 0.0) return beforeStart(originOf(numbers_.origin, numbers_.heading), s);
  // Last segment whose start is ≤ s (segments are right-continuous: at a junction the next one holds).
  auto it = std::upper_bound(starts_.begin(), starts_.end(), s,
                             [](double value, const SegmentStart& start) { return value < start.arc_length; });
  const std::size_t index = static_cast<std::size_t>(std::distance(starts_.begin(), it)) - 1;
  const Segment& segment = segments_[index];
  const SegmentShape<double> shape{segment.type, segment.length, segment.curvature_start, segment.curvature_end};
  const SegmentStart& from = starts_[index];
  const SegmentStartTpl<double> start{from.position, from.heading, from.cos_heading, from.sin_heading};
  const double sigma = s - from.arc_length;
  if (sigma <= segment.length) return alongSegment(shape, start, sigma);
  return beyondEnd(alongSegment(shape, start, segment.length), sigma - segment.length);
}

}  // namespace mbsopt
