// A track's numbers as model parameters: trackPointAt differentiates the geometry in every number
// (origin, heading, lengths, radii, angles, end curvatures), checked against central differences of
// Track::at on rebuilt tracks; the model names, rebuilds and refuses them as the scene file writes them.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/track.hpp"

namespace mbsopt {
namespace {

/// Straight, clothoid into a left arc, arc, clothoid out, straight: every segment type and both
/// kinds of junction, from an origin off the axes with a heading.
TrackNumbers transitionNumbers() {
  Track track(Eigen::Vector3d(1.5, -2.0, 0.25), 0.3);
  track.straight(6.0).clothoid(10.0, 1.0 / 25.0).arc(25.0, 0.8).clothoid(10.0, 0.0).straight(7.0);
  return track.numbers();
}

/// The numbers as one vector: origin x, y, z, heading, then each segment's numbers.
std::vector<double*> entries(TrackNumbers& numbers) {
  std::vector<double*> out{&numbers.origin.x(), &numbers.origin.y(), &numbers.origin.z(), &numbers.heading};
  for (std::size_t k = 0; k < numbers.types.size(); ++k)
    for (int n = 0; n < numberCount(numbers.types[k]); ++n) out.push_back(&numbers.numbers[k][static_cast<std::size_t>(n)]);
  return out;
}

/// Position, heading, curvature and its derivative as one vector.
Eigen::Matrix<double, 6, 1> flat(const TrackPoint& p) {
  Eigen::Matrix<double, 6, 1> out;
  out << p.position, p.heading, p.curvature, p.curvature_derivative;
  return out;
}

// Central differences with h = 1e-5 max(|x|, 1) leave a truncation error h²/6 |f'''| and a
// round-off of ε |f| / h ≈ 1e-16 · 53 / 1e-5 ≈ 5e-10. For the origin, the heading, lengths, radii and
// angles |f'''| ≲ 10 (the track is 53 m long, radius 25 m, curvatures ≤ 0.04 /m): 2e-10, and a
// tolerance of 1e-8. An end curvature turns the track downstream by ∂ψ/∂κ ≤ L/2 = 5 m per 1/m (L the
// clothoid's length), so |∂³r/∂κ³| ≲ (L/2)³ · 53 m ≈ 7e3 and the truncation reaches 1.1e-7: a
// tolerance of 2e-7 there. Both are far below any missing term (derivatives of 1e-2 and up).
TEST(TrackNumbers, EveryNumbersDerivativeMatchesCentralDifferences) {
  TrackNumbers numbers = transitionNumbers();
  const Track track(numbers);
  const std::vector<double*> x = entries(numbers);
  std::vector<std::size_t> segmentOf;  // of each segment number (entries after the first four)
  std::vector<int> numberIndexOf;
  for (std::size_t k = 0; k < numbers.types.size(); ++k)
    for (int n = 0; n < numberCount(numbers.types[k]); ++n) {
      segmentOf.push_back(k);
      numberIndexOf.push_back(n);
    }
  // Inside each segment (arc lengths 0-6, 6-16, 16-36, 36-46, 46-53) and beyond both ends.
  for (const double s : {-1.0, 3.0, 11.0, 27.0, 40.0, 50.0, 55.0}) {
    for (std::size_t first = 0; first < x.size(); first += kMaxAdDirections) {
      // One AD pass seeds up to kMaxAdDirections numbers at once.
      TrackNumbersTpl<AdScalar> seeded;
      seeded.types = numbers.types;
      std::vector<AdScalar*> y{&seeded.origin.x(), &seeded.origin.y(), &seeded.origin.z(), &seeded.heading};
      const AdScalar zero(0.0, AdDerivatives::Zero());
      seeded.numbers.assign(numbers.numbers.size(), {zero, zero});
      for (std::size_t k = 0; k < numbers.types.size(); ++k)
        for (int n = 0; n < numberCount(numbers.types[k]); ++n) y.push_back(&seeded.numbers[k][static_cast<std::size_t>(n)]);
      for (std::size_t i = 0; i < x.size(); ++i) {
        *y[i] = AdScalar(*x[i], AdDerivatives::Zero());
        if (i >= first && i < first + kMaxAdDirections) y[i]->derivatives()[static_cast<Eigen::Index>(i - first)] = 1.0;
      }
      const TrackPointTpl<AdScalar> p = trackPointAt(seeded, AdScalar(s, AdDerivatives::Zero()));
      // Its values are Track::at's.
      EXPECT_LT((flat(track.at(s)) - Eigen::Matrix<double, 6, 1>(p.position.x().value(), p.position.y().value(),
                                                                  p.position.z().value(), p.heading.value(),
                                                                  p.curvature.value(), p.curvature_derivative.value()))
                    .cwiseAbs()
                    .maxCoeff(),
                1e-12)
          << "s = " << s;
      for (std::size_t i = first; i < std::min(x.size(), first + kMaxAdDirections); ++i) {
        const double value = *x[i];
        const double h = 1e-5 * std::max(std::abs(value), 1.0);
        *x[i] = value + h;
        const auto up = flat(Track(numbers).at(s));
        *x[i] = value - h;
        const auto down = flat(Track(numbers).at(s));
        *x[i] = value;
        const Eigen::Matrix<double, 6, 1> difference = (up - down) / (2.0 * h);
        const auto lane = static_cast<Eigen::Index>(i - first);
        Eigen::Matrix<double, 6, 1> ad;
        ad << p.position.x().derivatives()[lane], p.position.y().derivatives()[lane], p.position.z().derivatives()[lane],
            p.heading.derivatives()[lane], p.curvature.derivatives()[lane], p.curvature_derivative.derivatives()[lane];
        const bool end_curvature =
            i >= 4 && numbers.types[segmentOf[i - 4]] == TrackSegmentType::Clothoid && numberIndexOf[i - 4] == 1;
        EXPECT_LT((ad - difference).cwiseAbs().maxCoeff(), end_curvature ? 2e-7 : 1e-8)
            << "s = " << s << ", number " << i;
      }
    }
  }
}

// Seeded in s alone, the fresh evaluation carries dr/ds = t, dψ/ds = κ, dκ/ds = κ' as the cached
// geometry's first-order extension does (trackStateAt): the two paths of the kinematics agree.
TEST(TrackNumbers, ArcLengthDerivativesAgreeWithTheCachedGeometry) {
  const TrackNumbers numbers = transitionNumbers();
  const Track track(numbers);
  TrackNumbersTpl<AdScalar> constant;
  constant.origin = numbers.origin.cast<AdScalar>();
  constant.heading = AdScalar(numbers.heading, AdDerivatives::Zero());
  constant.types = numbers.types;
  for (const auto& [a, b] : numbers.numbers)
    constant.numbers.push_back({AdScalar(a, AdDerivatives::Zero()), AdScalar(b, AdDerivatives::Zero())});
  for (const double s : {3.0, 11.0, 27.0, 40.0, 50.0}) {
    const AdScalar seeded(s, AdDerivatives::Unit(0));
    const TrackPointTpl<AdScalar> fresh = trackPointAt(constant, seeded);
    const TrackPointTpl<AdScalar> cached = trackStateAt(track, seeded);
    // Round-off of the quadrature's derivative in σ against the closed-form tangent: 1e-13.
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(fresh.position[c].derivatives()[0], cached.position[c].derivatives()[0], 1e-13) << "s = " << s;
    EXPECT_NEAR(fresh.heading.derivatives()[0], cached.heading.derivatives()[0], 1e-15) << "s = " << s;
    EXPECT_NEAR(fresh.curvature.derivatives()[0], cached.curvature.derivatives()[0], 1e-15) << "s = " << s;
  }
}

TEST(TrackNumbers, AreModelParametersUnderTheSceneFilesNames) {
  Model model;
  Track track(Eigen::Vector3d(1.0, 2.0, 0.0), 0.5);
  track.straight(6.0).clothoid(10.0, 0.04).arc(25.0, -0.8);
  const TrackIndex rail = model.addTrack("rail", track);
  EXPECT_EQ(model.parameter("rail.origin.y"), 2.0);
  EXPECT_EQ(model.parameter("rail.heading"), 0.5);
  EXPECT_EQ(model.parameter("rail.segments.0.length"), 6.0);
  EXPECT_EQ(model.parameter("rail.segments.1.end_curvature"), 0.04);
  EXPECT_EQ(model.parameter("rail.segments.2.radius"), 25.0);
  EXPECT_EQ(model.parameter("rail.segments.2.angle"), -0.8);
  EXPECT_THROW(model.parameterIndex("rail.segments.0.end_curvature"), std::invalid_argument);
  // Setting a number rebuilds the geometry: the arc that follows 2 m more straight starts 2 m later.
  const double before = model.track(rail).at(20.0).heading;
  model.setParameter("rail.segments.0.length", 8.0);
  EXPECT_DOUBLE_EQ(model.track(rail).at(22.0).heading, before);
  EXPECT_EQ(model.track(rail).length(), 8.0 + 10.0 + 25.0 * 0.8);
  // A number the builders refuse leaves the model unchanged, and says why.
  try {
    model.setParameter("rail.segments.2.radius", -1.0);
    ADD_FAILURE() << "a negative radius was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rail.segments.2.radius"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("radius must be positive"), std::string::npos) << e.what();
  }
  EXPECT_EQ(model.parameter("rail.segments.2.radius"), 25.0);
  EXPECT_EQ(model.track(rail).length(), 8.0 + 10.0 + 25.0 * 0.8);
  EXPECT_TRUE(isGeometricParameter(model, model.parameterIndex("rail.segments.2.angle")));
  EXPECT_EQ(trackOf(model, model.parameterIndex("rail.heading")), 0);
  // A straight has one number: no other parameter (gravity.x, index 0) is taken for its second.
  EXPECT_EQ(trackOf(model, model.parameterIndex("gravity.x")), -1);
  EXPECT_FALSE(isGeometricParameter(model, model.parameterIndex("gravity.x")));
}

}  // namespace
}  // namespace mbsopt
