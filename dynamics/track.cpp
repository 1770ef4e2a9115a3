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

double endCurvature(const std::vector<Track::Segment>& segments) {
  return segments.empty() ? 0.0 : segments.back().curvature_end;
}

}  // namespace

Track::Track(Eigen::Vector3d origin, double heading)
    : origin_(std::move(origin)), heading_(heading), cos_heading_(std::cos(heading)), sin_heading_(std::sin(heading)) {}

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
  SegmentStart start{0.0, origin_, heading_, cos_heading_, sin_heading_};
  if (!segments_.empty()) {
    const TrackPoint end = advance(segments_.back(), starts_.back(), segments_.back().length);
    start = {starts_.back().arc_length + segments_.back().length, end.position, end.heading, std::cos(end.heading),
             std::sin(end.heading)};
  }
  segments_.push_back(segment);
  starts_.push_back(start);
}

TrackPoint Track::advance(const Segment& segment, const SegmentStart& start, double sigma) {
  TrackPoint point;
  const double k0 = segment.curvature_start;
  const double dk = (segment.curvature_end - segment.curvature_start) / segment.length;
  const double heading = start.heading;
  const Eigen::Vector3d& position = start.position;
  point.curvature = k0 + dk * sigma;
  point.curvature_derivative = dk;
  point.heading = heading + k0 * sigma + 0.5 * dk * sigma * sigma;
  if (segment.type != SegmentType::Clothoid) {
    const Eigen::Vector3d tangent(start.cos_heading, start.sin_heading, 0.0);
    if (k0 == 0.0) {  // a straight line: the start's tangent throughout
      point.cos_heading = start.cos_heading;
      point.sin_heading = start.sin_heading;
      point.position = position + sigma * tangent;
      return point;
    }
    // A circular arc turning by θ = κσ: the start's tangent turned by θ, and the chord
    // (sin θ t₀ + (1 − cos θ) n₀)/κ, one sine and cosine for both. 1 − cos θ is sin²θ/(1 + cos θ)
    // while cos θ > 0, with no cancellation for small θ.
    const Eigen::Vector3d normal(-start.sin_heading, start.cos_heading, 0.0);
    const double turn = k0 * sigma;
    const double sin_turn = std::sin(turn), cos_turn = std::cos(turn);
    const double versine = cos_turn > 0.0 ? sin_turn * sin_turn / (1.0 + cos_turn) : 1.0 - cos_turn;
    point.cos_heading = start.cos_heading * cos_turn - start.sin_heading * sin_turn;
    point.sin_heading = start.sin_heading * cos_turn + start.cos_heading * sin_turn;
    point.position = position + (sin_turn / k0) * tangent + (versine / k0) * normal;
    return point;
  }
  point.cos_heading = std::cos(point.heading);
  point.sin_heading = std::sin(point.heading);
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
    point.cos_heading = cos_heading_;
    point.sin_heading = sin_heading_;
    point.position = origin_ + s * point.tangent();
    return point;
  }
  // Last segment whose start is ≤ s (segments are right-continuous: at a junction the next one holds).
  auto it = std::upper_bound(starts_.begin(), starts_.end(), s,
                             [](double value, const SegmentStart& start) { return value < start.arc_length; });
  const std::size_t index = static_cast<std::size_t>(std::distance(starts_.begin(), it)) - 1;
  const Segment& segment = segments_[index];
  const double sigma = s - starts_[index].arc_length;
  if (sigma <= segment.length) return advance(segment, starts_[index], sigma);
  TrackPoint end = advance(segment, starts_[index], segment.length);
  end.position += (sigma - segment.length) * end.tangent();  // straight extension beyond the end
  end.curvature = 0.0;
  end.curvature_derivative = 0.0;
  return end;
}

}  // namespace mbsopt
