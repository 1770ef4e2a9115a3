#include "dynamics/track.hpp"

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

// sin(x)/x, accurate near 0.
double sinc(double x) { return std::abs(x) < 1e-4 ? 1.0 - x * x / 6.0 : std::sin(x) / x; }

double endCurvature(const std::vector<Track::Segment>& segments) {
  return segments.empty() ? 0.0 : segments.back().curvature_end;
}

}  // namespace

Eigen::Vector3d TrackPoint::tangent() const { return {std::cos(heading), std::sin(heading), 0.0}; }
Eigen::Vector3d TrackPoint::normal() const { return {-std::sin(heading), std::cos(heading), 0.0}; }

Track::Track(Eigen::Vector3d origin, double heading) : origin_(std::move(origin)), heading_(heading) {}

Track& Track::straight(double length) {
  append({SegmentType::Straight, length, 0.0, 0.0});
  return *this;
}

Track& Track::arc(double radius, double angle) {
  if (!(radius > 0.0)) throw std::invalid_argument("Track::arc: radius must be positive");
  const double curvature = std::copysign(1.0 / radius, angle);
  append({SegmentType::Arc, std::abs(angle) * radius, curvature, curvature});
  return *this;
}

Track& Track::clothoid(double length, double curvature_end) {
  if (!std::isfinite(curvature_end)) throw std::invalid_argument("Track::clothoid: the end curvature must be finite");
  append({SegmentType::Clothoid, length, endCurvature(segments_), curvature_end});
  return *this;
}

void Track::append(const Segment& segment) {
  if (!(segment.length > 0.0) || !std::isfinite(segment.length))
    throw std::invalid_argument("Track: segment length must be positive and finite");
  SegmentStart start{0.0, origin_, heading_};
  if (!segments_.empty()) {
    const TrackPoint end = advance(segments_.back(), starts_.back().position, starts_.back().heading,
                                   segments_.back().length);
    start = {starts_.back().arc_length + segments_.back().length, end.position, end.heading};
  }
  segments_.push_back(segment);
  starts_.push_back(start);
}

TrackPoint Track::advance(const Segment& segment, const Eigen::Vector3d& position, double heading, double sigma) {
  TrackPoint point;
  const double k0 = segment.curvature_start;
  const double dk = (segment.curvature_end - segment.curvature_start) / segment.length;
  point.curvature = k0 + dk * sigma;
  point.curvature_derivative = dk;
  point.heading = heading + k0 * sigma + 0.5 * dk * sigma * sigma;
  if (segment.type != SegmentType::Clothoid) {
    // Chord of a circular arc (a straight line when κ = 0): length σ·sinc(κσ/2) at mid heading.
    const double half_turn = 0.5 * k0 * sigma;
    const double chord = sigma * sinc(half_turn);
    const double chord_heading = heading + half_turn;
    point.position = position + chord * Eigen::Vector3d(std::cos(chord_heading), std::sin(chord_heading), 0.0);
    return point;
  }
  // Fresnel integrals ∫(cos ψ, sin ψ) dσ by composite Gauss-Legendre, panels turning ≤ 0.25 rad.
  const double turn = std::abs(k0) * std::abs(sigma) + 0.5 * std::abs(dk) * sigma * sigma;
  const int panels = std::max(1, static_cast<int>(std::ceil(turn / 0.25)));
  const double width = sigma / panels;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int p = 0; p < panels; ++p) {
    const double centre = (p + 0.5) * width;
    for (std::size_t g = 0; g < kGaussNodes.size(); ++g) {
      for (double side : {-1.0, 1.0}) {
        const double x = centre + side * 0.5 * width * kGaussNodes[g];
        const double psi = heading + k0 * x + 0.5 * dk * x * x;
        sum += kGaussWeights[g] * Eigen::Vector3d(std::cos(psi), std::sin(psi), 0.0);
      }
    }
  }
  point.position = position + 0.5 * width * sum;
  return point;
}

TrackPoint Track::at(double s) const {
  if (segments_.empty()) throw std::logic_error("Track::at: the track has no segment");
  if (s < 0.0) {  // straight extension before the start
    TrackPoint point;
    point.heading = heading_;
    point.position = origin_ + s * point.tangent();
    return point;
  }
  // Last segment whose start is ≤ s (segments are right-continuous: at a junction the next one holds).
  auto it = std::upper_bound(starts_.begin(), starts_.end(), s,
                             [](double value, const SegmentStart& start) { return value < start.arc_length; });
  const std::size_t index = static_cast<std::size_t>(std::distance(starts_.begin(), it)) - 1;
  const Segment& segment = segments_[index];
  const double sigma = s - starts_[index].arc_length;
  if (sigma <= segment.length) return advance(segment, starts_[index].position, starts_[index].heading, sigma);
  TrackPoint end = advance(segment, starts_[index].position, starts_[index].heading, segment.length);
  end.position += (sigma - segment.length) * end.tangent();  // straight extension beyond the end
  end.curvature = 0.0;
  end.curvature_derivative = 0.0;
  return end;
}

}  // namespace mbsopt
