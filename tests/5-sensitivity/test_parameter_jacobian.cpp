// ∂f/∂b by forward AD of the residual, against central differences in every model parameter. The
// residual is a polynomial of degree at most two in each parameter (the centre of mass enters the
// moment of the inertial force twice, everything else once), so central differences are exact but
// for round-off, ~1e-16 |f| / δ: with δ = 1e-3 max(|b|, 1) a tolerance of 1e-9 of the row's scale
// is far above that and far below any missing term. A track's numbers (its radii, lengths, angles)
// enter through sines, cosines and Fresnel integrals instead: for them δ = 1e-5 max(|b|, 1). Their
// third derivatives are of order |f|/ℓ³ for the track's lengths ℓ ≥ 1 m (|∂³(m v²/R)/∂R³| = 6|f|/R³),
// so the truncation δ²/6 |f'''| ≲ δ²|f| stays below 1e-9 |f|/δ while δ ≤ 1e-3: with 1e-5, by 1e6.
#include <gtest/gtest.h>

#include "mbsopt/algorithms/residual.hpp"
#include "mbsopt/sensitivity/newmark_derivatives.hpp"
#include "mbsopt/sensitivity/parameter_jacobian.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "mbsopt/design/tramway.hpp"
#include "tests/sensitivity_scenes.hpp"

namespace mbsopt {
namespace {

/// Every parameter of the model, in its order (the columns the tests compare).
std::vector<ParameterIndex> everyParameter(const Model& model) {
  std::vector<ParameterIndex> out;
  for (std::size_t j = 0; j < model.parameterNames().size(); ++j) out.push_back(static_cast<ParameterIndex>(j));
  return out;
}

void expectCentralDifferences(Model model, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                              const Eigen::VectorXd& a, const Eigen::VectorXd& lambda, double t) {
  const std::vector<std::string> names = model.parameterNames();
  Workspace<AdScalar> ws_ad(model);
  const Eigen::MatrixXd J = parameterJacobian(model, ws_ad, q, v, a, lambda, t, everyParameter(model));
  ASSERT_EQ(J.cols(), static_cast<Eigen::Index>(names.size()));
  Workspace<double> ws(model);
  Eigen::VectorXd f0, up, down;
  residual(model, ws, q, v, a, lambda, t, f0);
  for (std::size_t j = 0; j < names.size(); ++j) {
    const double value = model.parameter(names[j]);
    const bool polynomial = trackOf(model, model.parameterIndex(names[j])) < 0;
    const double delta = (polynomial ? 1e-3 : 1e-5) * std::max(std::abs(value), 1.0);
    model.setParameter(names[j], value + delta);
    residual(model, ws, q, v, a, lambda, t, up);
    model.setParameter(names[j], value - delta);
    residual(model, ws, q, v, a, lambda, t, down);
    model.setParameter(names[j], value);
    const Eigen::VectorXd difference = (up - down) / (2.0 * delta);
    const double scale = std::max(f0.cwiseAbs().maxCoeff(), 1.0) / delta;
    EXPECT_LE((J.col(static_cast<Eigen::Index>(j)) - difference).cwiseAbs().maxCoeff(), 1e-9 * scale) << names[j];
  }
  // Seeding leaves the values alone: the AD residual's value is the plain one.
  EXPECT_TRUE(ws_ad.parameter_seeds.empty());
}

// The columns of ∂f/∂b computed in double for the parameters f is linear in (a force element's
// stiffness or damping: linearForceParameterColumn, what the exact gradients use instead of an AD
// direction) against the forward-AD columns of the whole residual: the same derivative of a linear
// function, summed in another order, so equal to round-off (1e-12 of the column). Every other
// parameter is refused, and the state is chosen so that no column is zero.
void expectLinearForceColumnsMatchAd(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                     const Eigen::VectorXd& a, const Eigen::VectorXd& lambda, double t,
                                     int expected_linear) {
  const std::vector<std::string> names = model.parameterNames();
  Workspace<AdScalar> ws_ad(model);
  const Eigen::MatrixXd J = parameterJacobian(model, ws_ad, q, v, a, lambda, t, everyParameter(model));
  Workspace<double> ws(model);
  forwardKinematics(model, ws, q, v, a, KinematicsLevel::Velocity);
  int linear = 0;
  for (std::size_t j = 0; j < names.size(); ++j) {
    const ParameterIndex index = model.parameterIndex(names[j]);
    Eigen::VectorXd column;
    const bool computed = linearForceParameterColumn(model, ws, q, v, t, index, column);
    EXPECT_EQ(computed, isLinearForceParameter(model, index)) << names[j];
    if (!computed) continue;
    ++linear;
    const Eigen::VectorXd ad = J.col(static_cast<Eigen::Index>(j));
    ASSERT_GT(ad.cwiseAbs().maxCoeff(), 0.0) << names[j];
    EXPECT_LE((column - ad).cwiseAbs().maxCoeff(), 1e-12 * ad.cwiseAbs().maxCoeff()) << names[j];
  }
  EXPECT_EQ(linear, expected_linear);
}

// The tram mid-curve: masses, centres of mass, inertias, secondary springs and dampers, track
// guidance, the track's numbers, gravity (zero here, but its derivative is not).
TEST(ParameterJacobian, TramwayMatchesCentralDifferences) {
  Scene scene = tramwayScene(TramwayDesign{}, TramwayOptions{});
  scene.settings.end_time = 2.0;
  const Trajectory trajectory = NewmarkIntegrator(scene.model, scene.settings).simulate(scene.q0, scene.v0);
  const Eigen::Index k = trajectory.time.size() - 1;
  expectCentralDifferences(scene.model, trajectory.q.col(k), trajectory.v.col(k), trajectory.a.col(k),
                           trajectory.lambda.col(k), trajectory.time[k]);
  // The stiffness and damping of the two secondary suspensions and the two track guidances (the
  // recursion carries a guidance's torque to every coordinate behind it), in double against AD.
  expectLinearForceColumnsMatchAd(scene.model, trajectory.q.col(k), trajectory.v.col(k), trajectory.a.col(k),
                                  trajectory.lambda.col(k), trajectory.time[k], 8);
}

// A spatial double pendulum with offset centres of mass, a joint spring with a rest angle, a point
// spring-damper with a rest length, a constant actuation and gravity: every other parameter kind.
TEST(ParameterJacobian, ForceElementsAndGravityMatchCentralDifferences) {
  Model model;
  const FrameIndex shoulder = model.addRevolute("shoulder", Model::ground, Eigen::Vector3d(0.2, 1.0, 0.1));
  const FrameIndex elbow_point = model.addOffset("elbow_point", shoulder, Eigen::Vector3d(0.0, 0.0, -1.0));
  const FrameIndex elbow = model.addRevolute("elbow", elbow_point, Eigen::Vector3d(1.0, 0.3, 0.0));
  model.addBody("upper", shoulder, 2.0, Eigen::Vector3d(0.05, -0.02, -0.5), Eigen::Vector3d(0.2, 0.25, 0.1).asDiagonal());
  model.addBody("lower", elbow, 1.5, Eigen::Vector3d(0.03, 0.01, -0.4), Eigen::Vector3d(0.1, 0.12, 0.05).asDiagonal());
  model.setGravity(Eigen::Vector3d(0.1, -0.2, -9.81));
  model.addJointSpringDamper("elbow_spring", "elbow", 30.0, 0.7, 0.25);
  model.addPointSpringDamper("strut", Model::ground, Eigen::Vector3d(0.5, 0.0, 0.0), elbow,
                             Eigen::Vector3d(0.0, 0.1, -0.8), 120.0, 3.0, 0.9);
  model.addJointActuation("motor", "shoulder", TimeFunction::constant(1.5));
  const Eigen::VectorXd q = Eigen::Vector2d(0.4, -0.7), v = Eigen::Vector2d(1.1, -0.6), a = Eigen::Vector2d(-2.0, 3.0);
  expectCentralDifferences(model, q, v, a, Eigen::VectorXd(), 0.3);
  // The joint spring's and the strut's stiffness and damping, in double against AD.
  expectLinearForceColumnsMatchAd(model, q, v, a, Eigen::VectorXd(), 0.3, 4);
}

// Parameters are seeded by their index in the model, not by the address of their storage: a copy
// of the step derivatives, which holds a model of its own, gives the original's ∂f/∂b (seeded by
// address, the copy seeded the original's storage and read zero derivatives).
TEST(ParameterJacobian, ACopyOfTheStepDerivativesSeedsItsOwnModel) {
  SceneSource source = readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/four_bar.yaml");
  source.text += test::kFourBarDesign;
  const DesignProblem problem = loadDesignProblem(source, {{"settings.end_time", 0.05}});
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  TrajectoryDerivatives original(problem, functionals, initialPoint(problem));
  TrajectoryDerivatives copy(original);
  const Eigen::Index k = original.timePoints() - 1;
  const Eigen::MatrixXd expected = original.step(k).parameters;
  ASSERT_GT(expected.cwiseAbs().maxCoeff(), 0.0);  // the masses and the centre of mass act on the motion
  EXPECT_EQ(copy.step(k).parameters, expected);
}

}  // namespace
}  // namespace mbsopt
