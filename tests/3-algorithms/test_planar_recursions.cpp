// The planar paths of the recursions (3-algorithms/planar_recursions.hpp, the mass matrix of
// mass_matrix.cpp):
//   - which models take them (Model::planar): every shipped scene, whose joints all turn about z or
//     slide in the xy plane (read from the files), and no model with one element that leaves the plane;
//   - the premise they rest on: on a planar model the spatial recursion's out-of-plane rates are exact
//     zeros, at any state;
//   - that the rate stage computes the spatial recursion's in-plane rates, in double and in the
//     derivative lanes of AD, at random states: the two add the same non-zero products in a
//     different order, so they differ by round-off only. Each component is a sum along the frame's
//     path of at most eight products per element, each bounded by the scale below (the largest rate
//     or rate product of the state); with at most 40 elements on a path that is 320 roundings of at
//     most ε·scale each, and the bound taken is 1024 ε·scale;
//   - independently of either path's formulas, that a planar mechanism and the same mechanism turned
//     about an oblique axis (which takes the spatial paths) have the same frames turned, the same
//     residual and derivatives and mass matrix, and the same motion (each test below gives its bound).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/track.hpp"
#include "mbsopt/model/workspace.hpp"
#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/algorithms/mass_matrix.hpp"
#include "mbsopt/algorithms/planar_recursions.hpp"
#include "mbsopt/algorithms/residual.hpp"
#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/sensitivity/forward_ad.hpp"
#include "mbsopt/io/scene_file.hpp"

namespace mbsopt {
namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

const std::vector<std::string> kShippedScenes = {
    "pendulum", "double_pendulum", "four_bar", "slider_crank", "tramway", "tramway_track_chart",
    "hard/pendulum_a01", "hard/n_four_bar_a02", "hard/andrews_squeezer"};

SceneSource shippedSource(const std::string& name) {
  return readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/" + name + ".yaml");
}

TEST(PlanarModel, EveryShippedSceneIsPlanar) {
  for (const std::string& name : kShippedScenes) EXPECT_TRUE(loadScene(shippedSource(name)).scene.model.planar()) << name;
}

TEST(PlanarModel, OneElementOutOfThePlaneMakesAModelSpatial) {
  const auto chain = [](auto&& last) {
    Model model;
    FrameIndex frame = model.addRevolute("hinge", Model::ground, Eigen::Vector3d::UnitZ());
    frame = model.addOffset("arm", frame, Eigen::Vector3d(1.0, 0.0, 0.3));  // lifted: still planar motion
    EXPECT_TRUE(model.planar());
    last(model, frame);
    return model.planar();
  };
  const Eigen::Matrix3d about_z = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d about_x = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_TRUE(chain([](Model& m, FrameIndex f) { m.addRevolute("z", f, -Eigen::Vector3d::UnitZ()); }));
  EXPECT_TRUE(chain([&](Model& m, FrameIndex f) { m.addOffset("turn", f, Eigen::Vector3d::Zero(), about_z); }));
  EXPECT_TRUE(chain([](Model& m, FrameIndex f) { m.addPrismatic("slide", f, Eigen::Vector3d(1.0, 2.0, 0.0)); }));
  EXPECT_FALSE(chain([](Model& m, FrameIndex f) { m.addRevolute("tilt", f, Eigen::Vector3d(0.0, 0.1, 1.0)); }));
  EXPECT_FALSE(chain([&](Model& m, FrameIndex f) { m.addOffset("roll", f, Eigen::Vector3d::Zero(), about_x); }));
  EXPECT_FALSE(chain([](Model& m, FrameIndex f) { m.addPrismatic("lift", f, Eigen::Vector3d(1.0, 0.0, 0.1)); }));
}

/// The largest velocity-like magnitude of the rates in ws (velocities, ω times the model's reach),
/// and the same for accelerations (α and ω² times the reach): the scale of every product summed.
struct RateScales {
  double velocity = 0.0, acceleration = 0.0;
};

template <class Scalar>
RateScales rateScales(const Workspace<Scalar>& ws) {
  double reach = 0.0, w = 0.0, v = 0.0, alpha = 0.0, a = 0.0;
  for (std::size_t k = 0; k < ws.position.size(); ++k) {
    for (int i = 0; i < 3; ++i) {
      reach = std::max(reach, std::abs(valueOf(ws.position[k][i])));
      w = std::max(w, std::abs(valueOf(ws.angular_velocity[k][i])));
      v = std::max(v, std::abs(valueOf(ws.velocity[k][i])));
      alpha = std::max(alpha, std::abs(valueOf(ws.angular_acceleration[k][i])));
      a = std::max(a, std::abs(valueOf(ws.acceleration[k][i])));
    }
  }
  return {1.0 + v + w * (1.0 + reach), 1.0 + a + (alpha + w * w) * (1.0 + reach)};
}

/// The largest |derivative lane| of the same quantities, as a scale for the lanes' round-off.
double laneScale(const Workspace<AdScalar>& ws) {
  double out = 1.0;
  for (std::size_t k = 0; k < ws.position.size(); ++k)
    for (int i = 0; i < 3; ++i)
      for (const auto* x : {&ws.position[k][i], &ws.angular_velocity[k][i], &ws.velocity[k][i],
                            &ws.angular_acceleration[k][i], &ws.acceleration[k][i]})
        out = std::max(out, x->derivatives().cwiseAbs().maxCoeff());
  return out;
}

/// Component i of frame k's rate in both workspaces, and the spatial one's premise: exactly zero out of
/// the plane (angular rates' x and y, linear rates' z).
template <class Scalar>
void expectSameRates(const std::vector<Vector3<Scalar>>& spatial, const std::vector<Vector3<Scalar>>& planar,
                     bool angular, double value_tolerance, double lane_tolerance, const std::string& what) {
  for (std::size_t k = 0; k < spatial.size(); ++k) {
    for (int i = 0; i < 3; ++i) {
      const bool in_plane = angular ? i == 2 : i < 2;
      const std::string where = what + ", frame " + std::to_string(k) + ", component " + std::to_string(i);
      if (!in_plane) {
        EXPECT_EQ(valueOf(spatial[k][i]), 0.0) << where;
        EXPECT_EQ(valueOf(planar[k][i]), 0.0) << where;
      }
      EXPECT_NEAR(valueOf(planar[k][i]), valueOf(spatial[k][i]), value_tolerance) << where;
      if constexpr (!std::is_same_v<Scalar, double>) {
        for (int j = 0; j < kMaxAdDirections; ++j) {
          if (!in_plane) {
            EXPECT_EQ(spatial[k][i].derivatives()[j], 0.0) << where << ", lane " << j;
          }
          EXPECT_NEAR(planar[k][i].derivatives()[j], spatial[k][i].derivatives()[j], lane_tolerance)
              << where << ", lane " << j;
        }
      }
    }
  }
}

/// A random state of the model near q0: q0 + U(−1, 1), q̇ and q̈ in U(−3, 3); in AD, the lanes seeded
/// with random directions in q, q̇ and q̈ at once.
template <class Scalar>
struct RandomState {
  VectorX<Scalar> q, v, a;
};

template <class Scalar>
RandomState<Scalar> randomState(const Eigen::VectorXd& q0, std::mt19937& generator) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto n = q0.size();
  RandomState<Scalar> out{VectorX<Scalar>(n), VectorX<Scalar>(n), VectorX<Scalar>(n)};
  for (Eigen::Index i = 0; i < n; ++i) {
    out.q[i] = Scalar(q0[i] + unit(generator));
    out.v[i] = Scalar(3.0 * unit(generator));
    out.a[i] = Scalar(3.0 * unit(generator));
    if constexpr (!std::is_same_v<Scalar, double>) {
      for (VectorX<Scalar>* x : {&out.q, &out.v, &out.a})
        for (int j = 0; j < kMaxAdDirections; ++j) (*x)[i].derivatives()[j] = unit(generator);
    }
  }
  return out;
}

/// The turn of the whole mechanism in the invariance tests below: about an oblique axis.
const Eigen::Matrix3d kTilt = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();

/// A planar model whose every kind of element sits on a moving frame (the shipped scenes slide only
/// on fixed frames, where 2 ω_e × v_rel and the slider's κ ṡ² terms meet no rotation): a hinge, an
/// offset turned about z and lifted out of the plane, a prismatic joint on it, a hinge about −z, a curve
/// slider that follows its track (a clothoid into an arc) and one that only translates on another, a
/// hinge on that one, and on the root a second slider that follows its track; bodies with products of
/// inertia, gravity in the plane, a joint spring, a point spring and a track guidance. `turned`: the same mechanism and gravity hung from a frame turned by kTilt (the
/// first element), which moves out of the plane.
Model everyPlanarElement(bool turned = false) {
  Model model;
  FrameIndex root = Model::ground;
  if (turned) root = model.addOffset("tilted", Model::ground, Eigen::Vector3d::Zero(), kTilt);
  const Eigen::Vector3d gravity(0.0, -9.81, 0.0);
  model.setGravity(turned ? Eigen::Vector3d(kTilt * gravity) : gravity);
  Eigen::Matrix3d inertia;
  inertia << 0.3, 0.01, 0.02, 0.01, 0.2, 0.03, 0.02, 0.03, 0.4;
  FrameIndex frame = model.addRevolute("hinge", root, Eigen::Vector3d::UnitZ());
  model.addBody("crank", frame, 2.0, Eigen::Vector3d(0.4, 0.1, 0.05), inertia);
  frame = model.addOffset("arm", frame, Eigen::Vector3d(1.0, 0.2, 0.3),
                          Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix());
  frame = model.addPrismatic("slide", frame, Eigen::Vector3d(1.0, 2.0, 0.0));
  model.addBody("block", frame, 1.5, Eigen::Vector3d(-0.1, 0.2, 0.0), 0.5 * inertia);
  frame = model.addRevolute("swivel", frame, -Eigen::Vector3d::UnitZ());
  model.addBody("head", frame, 0.7, Eigen::Vector3d(0.2, -0.3, 0.1), 0.2 * inertia);
  Track curve(Eigen::Vector3d(0.1, -0.2, 0.0), 0.3);
  curve.straight(0.5).clothoid(1.0, 2.0).arc(0.5, 1.0);
  const TrackIndex track = model.addTrack("rail", curve);
  const FrameIndex rider = model.addCurveSlider("rider", frame, track, SliderOrientation::FollowTrack);
  model.addBody("bogie", rider, 1.1, Eigen::Vector3d(0.3, 0.1, 0.0), 0.3 * inertia);
  frame = model.addOffset("tail", rider, Eigen::Vector3d(-0.3, 0.5, 0.0));
  const FrameIndex shuttle = model.addCurveSlider("shuttle", frame, track, SliderOrientation::Translate);
  model.addBody("car", shuttle, 0.9, Eigen::Vector3d(0.05, 0.1, -0.2), 0.4 * inertia);
  const FrameIndex yaw = model.addRevolute("yaw", shuttle, Eigen::Vector3d::UnitZ());
  model.addBody("pivot", yaw, 0.6, Eigen::Vector3d(0.2, 0.1, 0.0), 0.3 * inertia);
  // A second branch, on the root (the ground of the planar model, whose rates the recursions skip):
  // a slider that follows its track, so that both its rotation rate and its curvature bias enter.
  const FrameIndex runner = model.addCurveSlider("runner", root, track, SliderOrientation::FollowTrack);
  model.addBody("trolley", runner, 0.8, Eigen::Vector3d(0.1, -0.2, 0.0), 0.2 * inertia);
  model.addJointSpringDamper("hinge_spring", "hinge", 30.0, 0.5, 0.1);
  model.addPointSpringDamper("tether", root, Eigen::Vector3d(0.5, -1.0, 0.0), shuttle, Eigen::Vector3d(0.1, 0.0, 0.0),
                             40.0, 0.8, 0.5);
  // On a hinge that turns against the track, on a slider whose base turns: its deviation, the
  // base's rotation rate and the track's curvature all enter (on the slider that follows its track
  // the deviation is constant and the guidance's torque and its reaction cancel in the residual).
  model.addTrackGuidance("guidance", yaw, "shuttle", 200.0, 3.0);
  return model;
}

template <class Scalar>
void comparePaths(const Model& model, const Eigen::VectorXd& q0, const std::string& name) {
  std::mt19937 generator(20261125);
  for (int trial = 0; trial < 20; ++trial) {
    const RandomState<Scalar> x = randomState<Scalar>(q0, generator);
    Workspace<Scalar> spatial(model), planar(model);
    // Rotations, positions and the joints' axes (which the position level leaves out), then each path.
    forwardKinematics(model, spatial, x.q, x.v, x.a, KinematicsLevel::Velocity);
    forwardKinematics(model, planar, x.q, x.v, x.a, KinematicsLevel::Velocity);
    for (const KinematicsLevel level : {KinematicsLevel::Velocity, KinematicsLevel::Acceleration}) {
      spatialFrameRates(model, spatial, x.v, x.a, level);
      planarFrameRates(model, planar, x.v, x.a, level);
      const RateScales scales = rateScales(spatial);
      double lanes = 1.0;
      if constexpr (!std::is_same_v<Scalar, double>) lanes = laneScale(spatial);
      const std::string what = name + ", trial " + std::to_string(trial);
      expectSameRates(spatial.angular_velocity, planar.angular_velocity, true, 1024 * kEpsilon * scales.velocity,
                      1024 * kEpsilon * lanes, what + ", ω");
      expectSameRates(spatial.velocity, planar.velocity, false, 1024 * kEpsilon * scales.velocity,
                      1024 * kEpsilon * lanes, what + ", v");
      if (level != KinematicsLevel::Acceleration) continue;
      expectSameRates(spatial.angular_acceleration, planar.angular_acceleration, true,
                      1024 * kEpsilon * scales.acceleration, 1024 * kEpsilon * lanes, what + ", α");
      expectSameRates(spatial.acceleration, planar.acceleration, false, 1024 * kEpsilon * scales.acceleration,
                      1024 * kEpsilon * lanes, what + ", a");
    }
    spatialFrameAccelerationsAtRest(model, spatial, x.a);
    planarFrameAccelerationsAtRest(model, planar, x.a);
    const RateScales scales = rateScales(spatial);
    double lanes = 1.0;
    if constexpr (!std::is_same_v<Scalar, double>) lanes = laneScale(spatial);
    const std::string what = name + ", trial " + std::to_string(trial) + ", at rest";
    expectSameRates(spatial.angular_velocity, planar.angular_velocity, true, 0.0, 0.0, what + ", ω");
    expectSameRates(spatial.velocity, planar.velocity, false, 0.0, 0.0, what + ", v");
    expectSameRates(spatial.angular_acceleration, planar.angular_acceleration, true,
                    1024 * kEpsilon * scales.acceleration, 1024 * kEpsilon * lanes, what + ", α");
    expectSameRates(spatial.acceleration, planar.acceleration, false, 1024 * kEpsilon * scales.acceleration,
                    1024 * kEpsilon * lanes, what + ", a");
  }
}

template <class Scalar>
void compareOnEveryModel() {
  for (const std::string& name : kShippedScenes) {
    const LoadedScene loaded = loadScene(shippedSource(name));
    comparePaths<Scalar>(loaded.scene.model, loaded.scene.q0, name);
  }
  const Model model = everyPlanarElement();
  ASSERT_TRUE(model.planar());
  comparePaths<Scalar>(model, Eigen::VectorXd::Constant(model.coordinateCount(), 0.7), "every planar element");
}

TEST(PlanarKinematics, RatesAreThoseOfTheSpatialRecursion) { compareOnEveryModel<double>(); }

TEST(PlanarKinematics, DerivativeLanesAreThoseOfTheSpatialRecursion) { compareOnEveryModel<AdScalar>(); }

// The residual is a list of generalised forces: it does not change when the whole mechanism and its
// gravity are turned. Hung from a frame turned by R0 about an oblique axis, a planar scene takes the
// spatial recursions, and at the same (q, q̇, q̈) with its multipliers turned the same way (a cut's
// coincidence rows p_a − p_b are in ground axes; its orthogonality rows u·w are invariant) its
// residual, the residual's derivatives and its mass matrix must be the planar model's. Both sum the
// same wrenches, once in other axes: each row is a sum of at most a few hundred products, each
// bounded by the scale of the evaluation (its largest row or derivative), so they differ by a few
// hundred roundings of ε·scale at most; the bound taken is 4096 ε·scale.

/// The scene's text with every reference to the ground moved to a frame "tilted", an offset turned by
/// kTilt under the ground, and its gravity turned by kTilt.
std::string tiltedScene(std::string text) {
  for (std::size_t at = text.find(": ground"); at != std::string::npos; at = text.find(": ground", at))
    text.replace(at, 8, ": tilted");
  const std::size_t elements = text.find("\nelements:\n");
  EXPECT_NE(elements, std::string::npos);
  text.insert(elements + 11,
              "  - {name: tilted, type: offset, parent: ground, rotation: {axis: [1, 2, 3], angle: 0.7}}\n");
  const std::size_t gravity = text.find("\ngravity: [");
  if (gravity != std::string::npos) {
    const std::size_t begin = gravity + 11, end = text.find(']', begin);
    Eigen::Vector3d g;
    EXPECT_EQ(std::sscanf(text.substr(begin, end - begin).c_str(), "%lf, %lf, %lf", &g.x(), &g.y(), &g.z()), 3);
    const Eigen::Vector3d turned = kTilt * g;
    char numbers[128];
    std::snprintf(numbers, sizeof numbers, "%.17g, %.17g, %.17g", turned.x(), turned.y(), turned.z());
    text.replace(begin, end - begin, numbers);
  }
  return text;
}

/// λ for the tilted model: each cut's coincidence rows turned by kTilt.
Eigen::VectorXd tiltedMultipliers(const Model& model, Eigen::VectorXd lambda) {
  Eigen::Index row = 0;
  for (const CutJoint& cut : model.cuts()) {
    lambda.segment<3>(row) = kTilt * lambda.segment<3>(row);
    row += equationCount(cut.kind);
  }
  return lambda;
}

double largest(const Eigen::MatrixXd& x) { return x.size() ? x.cwiseAbs().maxCoeff() : 0.0; }

/// A planar model and the same mechanism turned by kTilt (spatial), with a state to start from.
struct TurnedPair {
  std::string name;
  Model planar, turned;
  Eigen::VectorXd q0;
};

std::vector<TurnedPair> turnedPairs() {
  std::vector<TurnedPair> out;
  for (const std::string& name : kShippedScenes) {
    const SceneSource source = shippedSource(name);
    const LoadedScene planar = loadScene(source);
    out.push_back({name, planar.scene.model, loadScene({source.path, tiltedScene(source.text)}).scene.model,
                   planar.scene.q0});
  }
  const Model model = everyPlanarElement();
  out.push_back({"every planar element", model, everyPlanarElement(true),
                 Eigen::VectorXd::Constant(model.coordinateCount(), 0.7)});
  for (const TurnedPair& pair : out) {
    EXPECT_TRUE(pair.planar.planar()) << pair.name;
    EXPECT_FALSE(pair.turned.planar()) << pair.name;
    EXPECT_EQ(pair.planar.coordinateCount(), pair.turned.coordinateCount()) << pair.name;
    EXPECT_EQ(pair.planar.frameCount() + 1, pair.turned.frameCount()) << pair.name;
  }
  return out;
}

// Frame by frame: the turned mechanism's frame k + 1 (its frame 1 is the turned root) is the planar
// model's frame k turned by kTilt: R' = kTilt R, and kTilt times its position, its velocities and its
// accelerations, in value and in the derivative lanes. Both compute the same sums of products, once
// in other axes; the bound is 1024 ε times the largest magnitude of the kind (as above).
template <class Scalar>
void expectTurnedFrames(const TurnedPair& pair) {
  std::mt19937 generator(20261125);
  Workspace<Scalar> a(pair.planar), b(pair.turned);
  for (int trial = 0; trial < 10; ++trial) {
    const RandomState<Scalar> x = randomState<Scalar>(pair.q0, generator);
    forwardKinematics(pair.planar, a, x.q, x.v, x.a, KinematicsLevel::Acceleration);
    forwardKinematics(pair.turned, b, x.q, x.v, x.a, KinematicsLevel::Acceleration);
    const RateScales scales = rateScales(b);
    double reach = 1.0, lanes = 1.0;
    for (const auto& p : b.position) reach = std::max(reach, std::abs(valueOf(p.norm())));
    if constexpr (!std::is_same_v<Scalar, double>) lanes = laneScale(b);
    const auto expectTurned = [&](const auto& planar, const auto& turned, double scale, const std::string& what) {
      for (Eigen::Index i = 0; i < planar.size(); ++i) {
        Scalar expected(0);
        const Eigen::Index row = i % 3, col = i / 3;  // entries of a 3-vector, or of a 3 × 3 matrix by column
        for (int j = 0; j < 3; ++j) expected += kTilt(row, j) * planar(j + 3 * (col));
        EXPECT_NEAR(valueOf(turned(i)), valueOf(expected), 1024 * kEpsilon * scale) << what << ", entry " << i;
        if constexpr (!std::is_same_v<Scalar, double>) {
          for (int l = 0; l < kMaxAdDirections; ++l)
            EXPECT_NEAR(turned(i).derivatives()[l], expected.derivatives()[l], 1024 * kEpsilon * lanes)
                << what << ", entry " << i << ", lane " << l;
        }
      }
    };
    for (std::size_t k = 1; k < a.rotation.size(); ++k) {
      const std::string what = pair.name + ", trial " + std::to_string(trial) + ", frame " + std::to_string(k);
      expectTurned(a.rotation[k], b.rotation[k + 1], 1.0, what + ", R");
      expectTurned(a.position[k], b.position[k + 1], reach, what + ", p");
      expectTurned(a.angular_velocity[k], b.angular_velocity[k + 1], scales.velocity, what + ", ω");
      expectTurned(a.velocity[k], b.velocity[k + 1], scales.velocity, what + ", v");
      expectTurned(a.angular_acceleration[k], b.angular_acceleration[k + 1], scales.acceleration, what + ", α");
      expectTurned(a.acceleration[k], b.acceleration[k + 1], scales.acceleration, what + ", a");
    }
  }
}

TEST(PlanarKinematics, FramesAreThoseOfTheTurnedMechanism) {
  for (const TurnedPair& pair : turnedPairs()) {
    expectTurnedFrames<double>(pair);
    expectTurnedFrames<AdScalar>(pair);
  }
}

/// On a planar model no stage writes the wrench components the planar backward recursion does not
/// carry (F_z, M_x, M_y): they keep the workspace's zeros, in every derivative lane too, whatever the
/// multipliers of the rows that vanish in the plane (a revolute cut's orthogonality rows turn λ
/// into an in-plane moment), the points' heights of a point spring, or the bodies' centres.
template <class Scalar>
void expectUncarriedWrenchesZero(const Workspace<Scalar>& ws, const std::string& what) {
  for (std::size_t k = 0; k < ws.force.size(); ++k)
    for (const Scalar* x : {&ws.force[k].z(), &ws.moment[k].x(), &ws.moment[k].y()}) {
      EXPECT_EQ(valueOf(*x), 0.0) << what << ", frame " << k;
      if constexpr (!std::is_same_v<Scalar, double>) {
        EXPECT_TRUE(x->derivatives().isZero(0.0)) << what << ", frame " << k;
      }
    }
}

void expectSameResidual(const TurnedPair& pair) {
  const std::string& name = pair.name;
  const Model& a = pair.planar;
  const Model& b = pair.turned;
  std::mt19937 generator(20261125);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const std::vector<AdInput> inputs = adInputs({adInputs(AdInput::Kind::Position, allCoordinates(a)),
                                                adInputs(AdInput::Kind::Velocity, allCoordinates(a)),
                                                adInputs(AdInput::Kind::Acceleration, allCoordinates(a))});
  Workspace<double> wa(a), wb(b);
  Workspace<AdScalar> ada(a), adb(b);
  for (int trial = 0; trial < 10; ++trial) {
    const RandomState<double> x = randomState<double>(pair.q0, generator);
    Eigen::VectorXd lambda(a.constraintCount());
    for (Eigen::Index i = 0; i < lambda.size(); ++i) lambda[i] = 100.0 * unit(generator);
    const Eigen::VectorXd lambda_b = tiltedMultipliers(a, lambda);
    const double t = 0.5 + unit(generator);
    Eigen::VectorXd fa, fb;
    residual(a, wa, x.q, x.v, x.a, lambda, t, fa);
    residual(b, wb, x.q, x.v, x.a, lambda_b, t, fb);
    const std::string what = name + ", trial " + std::to_string(trial);
    const double scale = 1.0 + std::max(largest(fa), largest(fb));
    EXPECT_LE(largest(fa - fb), 4096 * kEpsilon * scale) << what << ": f " << fa.transpose() << " against " << fb.transpose();
    Eigen::MatrixXd ma, mb;  // M = ∂f/∂q̈ by the composite rigid bodies, at the geometry the residual left
    massMatrix(a, wa, ma);
    massMatrix(b, wb, mb);
    EXPECT_LE(largest(ma - mb), 4096 * kEpsilon * (1.0 + largest(ma))) << what << ": M";
    const Eigen::MatrixXd ja = residualJacobian(a, ada, x.q, x.v, x.a, lambda, t, inputs, {});
    const Eigen::MatrixXd jb = residualJacobian(b, adb, x.q, x.v, x.a, lambda_b, t, inputs, {});
    const double lanes = 1.0 + std::max(largest(ja), largest(jb));
    EXPECT_LE(largest(ja - jb), 4096 * kEpsilon * lanes) << what << ": ∂f/∂(q, q̇, q̈)";
    // M(q) q̈ + B(q)ᵀλ alone (the projections' terms), at rest, with its derivatives in q.
    const Eigen::Index seeded = std::min<Eigen::Index>(a.coordinateCount(), kMaxAdDirections);
    VectorX<AdScalar> q, zero, acceleration, multipliers_a, multipliers_b, ga, gb;
    seedVector(x.q, 0, 0, seeded, q);
    seedVector(Eigen::VectorXd::Zero(x.q.size()), 0, 0, 0, zero);
    seedVector(x.a, 0, 0, 0, acceleration);
    seedVector(lambda, 0, 0, 0, multipliers_a);
    seedVector(lambda_b, 0, 0, 0, multipliers_b);
    for (auto [model, ws, multipliers, g] : {std::tuple{&a, &ada, &multipliers_a, &ga}, std::tuple{&b, &adb, &multipliers_b, &gb}}) {
      forwardKinematics(*model, *ws, q, zero, acceleration, KinematicsLevel::Velocity);  // geometry and joint axes
      frameAccelerationsAtRest(*model, *ws, acceleration);
      inertialAndLoopForcesFromKinematics(*model, *ws, acceleration, *multipliers, *g);
    }
    Eigen::MatrixXd rest_a(ga.size(), 1 + kMaxAdDirections), rest_b(gb.size(), 1 + kMaxAdDirections);
    for (Eigen::Index i = 0; i < ga.size(); ++i) {
      rest_a(i, 0) = ga[i].value();
      rest_a.row(i).tail(kMaxAdDirections) = ga[i].derivatives().transpose();
      rest_b(i, 0) = gb[i].value();
      rest_b.row(i).tail(kMaxAdDirections) = gb[i].derivatives().transpose();
    }
    const double rest_scale = 1.0 + std::max(largest(rest_a), largest(rest_b));
    EXPECT_LE(largest(rest_a - rest_b), 4096 * kEpsilon * rest_scale) << what << ": M q̈ + Bᵀλ";
    expectUncarriedWrenchesZero(wa, what + ", after the residual");
    expectUncarriedWrenchesZero(ada, what + ", after the AD passes");
  }
}

TEST(PlanarResidual, IsTheSpatialResidualOfTheTurnedMechanism) {
  for (const TurnedPair& pair : turnedPairs()) expectSameResidual(pair);
}

// The whole integrator on both paths: the tram and the four-bar, turned, follow the same motion. The
// two runs solve the same equations at every step, each to Newton's target, the larger of the
// tolerance and the increments' round-off floor (ε times the largest coordinate, or the closure
// rows' reach, over βh²): q̈ may differ by that per step, and q by βh² times it summed over the
// steps. The bounds take ten times those, as tests/3-algorithms/test_articulated_mass.cpp does (two runs, each
// off by up to its target, and what the earlier steps carry into the later ones).
TEST(PlanarModel, TheTurnedMechanismFollowsTheSameMotion) {
  for (const std::string& name : {std::string("tramway"), std::string("four_bar")}) {
    const SceneSource source = shippedSource(name);
    LoadedScene planar = loadScene(source), turned = loadScene({source.path, tiltedScene(source.text)});
    ASSERT_TRUE(planar.scene.model.planar());
    ASSERT_FALSE(turned.scene.model.planar());
    for (LoadedScene* scene : {&planar, &turned}) scene->scene.settings.end_time = 2.0;
    NewmarkIntegrator a(planar.scene.model, planar.scene.settings), b(turned.scene.model, turned.scene.settings);
    const Trajectory ta = a.simulate(planar.scene.q0, planar.scene.v0);
    const Trajectory tb = b.simulate(turned.scene.q0, turned.scene.v0);
    ASSERT_EQ(ta.q.cols(), tb.q.cols()) << name;
    const NewmarkSettings& s = planar.scene.settings;
    const double beta_h2 = s.beta * s.step * s.step;
    double reach = 1.0;
    Workspace<double> ws(planar.scene.model);
    for (Eigen::Index k = 0; k < ta.q.cols(); ++k) {
      const Eigen::VectorXd q = ta.q.col(k);
      forwardKinematics(planar.scene.model, ws, q, q, q, KinematicsLevel::Position);
      for (const auto& p : ws.position) reach = std::max(reach, p.lpNorm<1>() + ta.q.col(k).cwiseAbs().maxCoeff());
    }
    const double per_step = s.newton_tolerance * (1.0 + ta.a.cwiseAbs().maxCoeff()) + kEpsilon * reach / beta_h2;
    const double steps = static_cast<double>(ta.q.cols() - 1);
    EXPECT_LE((ta.a - tb.a).cwiseAbs().maxCoeff(), 10.0 * per_step) << name;
    EXPECT_LE((ta.q - tb.q).cwiseAbs().maxCoeff(), 10.0 * steps * beta_h2 * per_step) << name;
    EXPECT_LE((ta.v - tb.v).cwiseAbs().maxCoeff(), 10.0 * steps * s.gamma * s.step * per_step) << name;
  }
}

}  // namespace
}  // namespace mbsopt
