#include "mbsopt/integrators/track_breaks.hpp"

#include <algorithm>
#include <cmath>

#include "mbsopt/integrators/extrapolation.hpp"

namespace mbsopt {

namespace {

/// The arc lengths at which the curvature of `track` jumps: where one segment's end curvature differs
/// from the next one's start, and at either end of the track where it is curved (beyond its ends a
/// track runs on straight, Track::at).
std::vector<double> curvatureJumps(const Track& track) {
  std::vector<double> jumps;
  const std::vector<Track::Segment>& segments = track.segments();
  if (segments.empty()) return jumps;
  if (segments.front().curvature_start != 0.0) jumps.push_back(0.0);
  double s = 0.0;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    s += segments[k].length;
    const double next = k + 1 < segments.size() ? segments[k + 1].curvature_start : 0.0;
    if (segments[k].curvature_end != next) jumps.push_back(s);
  }
  return jumps;
}

/// θ ∈ [0, 1] where the cubic Hermite interpolant of (s0, ṡ0 h) and (s1, ṡ1 h) equals `target`, given
/// that s0 − target and s1 − target differ in sign (bisection to round-off: 60 halvings of [0, 1]).
double hermiteCrossing(double s0, double ds0, double s1, double ds1, double target) {
  const auto at = [&](double x) {
    const double x2 = x * x, x3 = x2 * x;
    return (2 * x3 - 3 * x2 + 1) * s0 + (x3 - 2 * x2 + x) * ds0 + (-2 * x3 + 3 * x2) * s1 + (x3 - x2) * ds1 - target;
  };
  if (s0 == target) return 0.0;
  if (s1 == target) return 1.0;
  double lo = 0.0, hi = 1.0;
  const bool rising = s1 > s0;  // then the cubic is below the target at lo, above it at hi
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((at(mid) < 0.0) == rising ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// Calls f(coordinate, track) for every curve slider with a coordinate.
template <class F>
void forEachCurveSlider(const Model& model, F&& f) {
  for (const KinematicElement& element : model.elements()) {
    const auto* slider = std::get_if<CurveSliderJoint>(&element.kind);
    if (slider && element.coordinate >= 0) f(static_cast<Eigen::Index>(element.coordinate), model.track(slider->track));
  }
}

}  // namespace

bool hasCurvatureJumps(const Model& model) {
  bool any = false;
  forEachCurveSlider(model, [&any](Eigen::Index, const Track& track) { any = any || !curvatureJumps(track).empty(); });
  return any;
}

std::vector<double> curvatureJumpTimes(const Model& model, const Trajectory& trajectory) {
  std::vector<double> times;
  const Eigen::VectorXd& t = trajectory.time;
  forEachCurveSlider(model, [&](Eigen::Index row, const Track& track) {
    for (double jump : curvatureJumps(track)) {
      for (Eigen::Index i = 0; i + 1 < t.size(); ++i) {
        const double s0 = trajectory.q(row, i), s1 = trajectory.q(row, i + 1);
        if ((s0 - jump) * (s1 - jump) > 0.0 || s0 == s1) continue;
        if (s1 == jump && i + 2 < t.size()) continue;  // the next interval starts there and finds it
        const double h = t[i + 1] - t[i];
        const double theta = hermiteCrossing(s0, trajectory.v(row, i) * h, s1, trajectory.v(row, i + 1) * h, jump);
        times.push_back(t[i] + theta * h);
      }
    }
  });
  std::sort(times.begin(), times.end());
  return times;
}

double crossingStep(double step, double end_time) { return std::min(step * step / end_time, step / 16.0); }

std::shared_ptr<const std::vector<double>> gradedTimeGrid(double step, double end_time,
                                                         const std::vector<double>& breaks) {
  const long steps = stepsToCover(end_time, step);
  step = uniformStep(step, end_time);
  const double end = end_time;
  const double eta = crossingStep(step, end_time);
  // Around each break, points at distances η/2, η, 2η, ... below `step` on both sides; the uniform
  // points within half a step beyond the farthest are left out (the step joining the two is then
  // between h/2 and 3h/2).
  std::vector<double> graded;
  std::vector<std::pair<double, double>> windows;
  for (double t : breaks) {
    if (!(t > 0.0 && t < end)) continue;
    double distance = 0.5 * eta;
    double farthest = distance;
    for (; distance < step; distance *= 2.0) {
      farthest = distance;
      for (double side : {-1.0, 1.0})
        if (t + side * distance > 0.0 && t + side * distance < end) graded.push_back(t + side * distance);
    }
    windows.emplace_back(t - farthest - 0.5 * step, t + farthest + 0.5 * step);
  }
  std::vector<double> points = graded;
  for (long k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) * step;
    const bool inside = std::any_of(windows.begin(), windows.end(), [t](const auto& w) { return t > w.first && t < w.second; });
    if (!inside || k == 0 || k == steps) points.push_back(k == steps ? end : t);
  }
  std::sort(points.begin(), points.end());
  // Two breaks closer than their windows interleave their points: keep none closer than η/4 to the
  // last (a break's own points are η/2 apart or more).
  auto grid = std::make_shared<std::vector<double>>();
  for (double t : points)
    if (grid->empty() || t - grid->back() >= 0.25 * eta) grid->push_back(t);
  if (grid->back() != end) grid->back() = end;
  return grid;
}

}  // namespace mbsopt
