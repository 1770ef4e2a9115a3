// Failures are reported, never hidden (docs/design.md §3): the integrator stops with an error naming the
// time, the step, the residual norm and the element involved.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/io/scene_file.hpp"

using namespace mbsopt;

namespace {

const Eigen::Vector3d kX = Eigen::Vector3d::UnitX(), kZ = Eigen::Vector3d::UnitZ();
const Eigen::Matrix3d kInertia = 1e-2 * Eigen::Matrix3d::Identity();

NewmarkSettings settings(double step, double end_time) {
  NewmarkSettings s;
  s.step = step;
  s.end_time = end_time;
  return s;
}

}  // namespace

// The two points of a spring coincide: its direction u = d/|d| is 0/0. The spring says so by name.
TEST(IntegratorErrors, DegenerateElementIsNamedWithTheTimeAndStep) {
  Model model;
  const FrameIndex slider = model.addPrismatic("slider", Model::ground, kX);
  model.addBody("block", slider, 1.0, Eigen::Vector3d::Zero(), kInertia);
  model.addPointSpringDamper("spring", Model::ground, Eigen::Vector3d::Zero(), slider, Eigen::Vector3d::Zero(), 10.0,
                             0.0, 1.0);
  NewmarkIntegrator integrator(model, settings(0.125, 2.0));
  try {
    integrator.simulate(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1));  // block on the anchor
    FAIL() << "expected a SimulationError";
  } catch (const SimulationError& error) {
    EXPECT_EQ(error.step, 0);
    EXPECT_EQ(error.time, 0.0);
    EXPECT_NE(std::string(error.what()).find("'spring'"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("coincide"), std::string::npos) << error.what();
  }
}

// A joint that carries no mass makes the iteration matrix singular on its direction.
TEST(IntegratorErrors, SingularIterationMatrixIsReported) {
  Model model;
  const FrameIndex hinge = model.addRevolute("hinge", Model::ground, kZ);
  model.addOffset("arm", hinge, kX);  // no body anywhere beyond the joint
  NewmarkIntegrator integrator(model, settings(1e-3, 0.01));
  EXPECT_THROW(
      {
        try {
          integrator.simulate(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1));
        } catch (const SimulationError& error) {
          EXPECT_EQ(error.status, StepStatus::StepTooLarge);
          EXPECT_NE(std::string(error.what()).find("singular"), std::string::npos) << error.what();
          throw;
        }
      },
      SimulationError);
}

// A stiff pendulum swinging fast through large angles cannot converge in one Newton iteration.
TEST(IntegratorErrors, NewtonNonConvergenceSaysHowFarItGot) {
  Model model;
  const FrameIndex hinge = model.addRevolute("hinge", Model::ground, kZ);
  model.addBody("bob", hinge, 1.0, kX, kInertia);
  model.setGravity(Eigen::Vector3d(0.0, -9.81, 0.0));
  NewmarkSettings s = settings(0.05, 1.0);
  s.max_newton_iterations = 1;
  NewmarkIntegrator integrator(model, s);
  Eigen::VectorXd v0(1);
  v0 << 20.0;
  try {
    integrator.simulate(Eigen::VectorXd::Zero(1), v0);
    FAIL() << "expected a SimulationError";
  } catch (const SimulationError& error) {
    const std::string message = error.what();
    EXPECT_EQ(error.status, StepStatus::NewtonDiverged);
    EXPECT_NE(message.find("did not converge"), std::string::npos) << message;
    EXPECT_NE(message.find("t = "), std::string::npos) << message;
    EXPECT_NE(message.find("'hinge'"), std::string::npos) << message;
    EXPECT_GT(error.residual_norm, 0.0);
  }
}

// A loop that no configuration closes is said to be one, at its cut joint, not a Newton failure. The
// slider-crank of problems/scenes/slider_crank.yaml with a rod of L = 0.12 m, its rail at e = 0.05 m:
// the rod reaches the rail while r sin θ ≥ e − L, r = 0.1 m, θ = 10 t (the crank's drive), so until
// θ = π + asin(0.7), t* = 0.391665 s; the run stops at the first step after it.
TEST(IntegratorErrors, ALoopThatCannotCloseIsNamedAtItsCutWithTheTime) {
  const LoadedScene loaded =
      loadScene(readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/slider_crank.yaml"),
                {{"conrod_end.translation.x", 0.12}, {"rail.translation.y", 0.05}});
  const Scene& scene = loaded.scene;
  NewmarkIntegrator integrator(scene.model, scene.settings);
  try {
    integrator.simulate(scene.q0, scene.v0);
    FAIL() << "expected a SimulationError";
  } catch (const SimulationError& error) {
    const double t_star = (std::numbers::pi + std::asin(0.7)) / 10.0, h = scene.settings.step;
    EXPECT_EQ(error.status, StepStatus::LoopCannotClose);
    EXPECT_EQ(error.element, "wrist_pin");
    EXPECT_GT(error.time, t_star);
    EXPECT_LE(error.time, t_star + h * (1 + 1e-9));
    const std::string message = error.what();
    EXPECT_NE(message.find("the loop closed by wrist_pin cannot be closed"), std::string::npos) << message;
    EXPECT_NE(message.find("closure error of"), std::string::npos) << message;
    EXPECT_EQ(message.find("Newton did not converge"), std::string::npos) << message;
  }
}

// A NaN the model produces without a degenerate element (here a force law that is NaN by input).
TEST(IntegratorErrors, NaNInTheResidualNamesTheJoint) {
  Model model;
  const FrameIndex slider = model.addPrismatic("slider", Model::ground, kX);
  model.addBody("block", slider, 1.0, Eigen::Vector3d::Zero(), kInertia);
  model.addJointActuation("push", "slider", TimeFunction::polynomial({std::numeric_limits<double>::quiet_NaN()}));
  NewmarkIntegrator integrator(model, settings(0.125, 2.0));
  try {
    integrator.simulate(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1));
    FAIL() << "expected a SimulationError";
  } catch (const SimulationError& error) {
    EXPECT_EQ(error.element, "slider");
    EXPECT_NE(std::string(error.what()).find("not finite"), std::string::npos) << error.what();
  }
}

// An unclosed initial state, or a weld cut assembled upside down, is refused before the first step.
TEST(IntegratorErrors, UnclosedOrFlippedInitialStatesAreRefused) {
  Model model;
  const FrameIndex hinge = model.addRevolute("hinge", Model::ground, kZ);
  model.addBody("bob", hinge, 1.0, kX, kInertia);
  const FrameIndex tip = model.addOffset("tip", hinge, kX);
  const FrameIndex anchor = model.addOffset("anchor", Model::ground, kX);
  model.addWeldCut("weld", tip, anchor);
  NewmarkIntegrator integrator(model, settings(1e-3, 0.1));
  Eigen::VectorXd q(1);
  q << 0.2;
  EXPECT_THROW(integrator.initialize(q, Eigen::VectorXd::Zero(1)), std::invalid_argument);
  q << 0.0;
  EXPECT_NO_THROW(integrator.initialize(q, Eigen::VectorXd::Zero(1)));
  // A tip frame turned by 180° about the hinge: the weld equations hold at q = 0 (x·y = 0, y·z = 0,
  // z·x = 0 for R = diag(−1, −1, 1)), but the frames do not coincide.
  Model flipped;
  const FrameIndex pivot = flipped.addRevolute("pivot", Model::ground, kZ);
  flipped.addBody("bar", pivot, 1.0, kX, kInertia);
  const FrameIndex end = flipped.addOffset("end", pivot, Eigen::Vector3d::Zero(), Eigen::Vector3d(-1, -1, 1).asDiagonal());
  flipped.addWeldCut("weld", end, Model::ground);
  NewmarkIntegrator flipped_integrator(flipped, settings(1e-3, 0.1));
  EXPECT_THROW(flipped_integrator.initialize(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1)), std::invalid_argument);
}

TEST(IntegratorErrors, InvalidSettingsAndStatesAreRejected) {
  Model model;
  const FrameIndex hinge = model.addRevolute("hinge", Model::ground, kZ);
  model.addBody("bob", hinge, 1.0, kX, kInertia);
  EXPECT_THROW(NewmarkIntegrator(model, settings(0.0, 1.0)), std::invalid_argument);
  EXPECT_THROW(NewmarkIntegrator(model, settings(1e-3, -1.0)), std::invalid_argument);
  EXPECT_THROW(NewmarkIntegrator(model, settings(std::numeric_limits<double>::quiet_NaN(), 1.0)),
               std::invalid_argument);
  NewmarkSettings no_iterations = settings(1e-3, 1.0);
  no_iterations.max_newton_iterations = 0;
  EXPECT_THROW(NewmarkIntegrator(model, no_iterations), std::invalid_argument);
  // 1 s is not a whole number of 0.3 s steps: four equal steps of 0.25 s, the last ending at 1 s.
  NewmarkIntegrator ragged(model, settings(0.3, 1.0));
  EXPECT_EQ(ragged.settings().step, 0.25);
  const Trajectory covering = ragged.simulate(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1));
  ASSERT_EQ(covering.time.size(), 5);
  EXPECT_EQ(covering.time[4], 1.0);
  EXPECT_EQ(covering.time[1], 0.25);
  EXPECT_THROW(NewmarkIntegrator(model, settings(1.5, 1.0)), std::invalid_argument);  // a step longer than the run
  NewmarkIntegrator integrator(model, settings(1e-3, 1.0));
  EXPECT_THROW(integrator.initialize(Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2)), std::invalid_argument);
  Eigen::VectorXd nan(1);
  nan << std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(integrator.initialize(nan, Eigen::VectorXd::Zero(1)), std::invalid_argument);
}

TEST(IntegratorErrors, ModelBuilderRejectsBadInput) {
  Model model;
  EXPECT_THROW(model.addRevolute("zero_axis", Model::ground, Eigen::Vector3d::Zero()), std::invalid_argument);
  EXPECT_THROW(model.addRevolute("bad_parent", 7, kZ), std::invalid_argument);
  const FrameIndex hinge = model.addRevolute("hinge", Model::ground, kZ);
  EXPECT_THROW(model.addRevolute("hinge", Model::ground, kZ), std::invalid_argument);  // duplicate name
  EXPECT_THROW(model.addBody("massless", hinge, 0.0, Eigen::Vector3d::Zero(), kInertia), std::invalid_argument);
  // A zero moment is a slender rod or a point mass (allowed); a negative one is no body.
  EXPECT_THROW(model.addBody("negative", hinge, 1.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 1, -0.1).asDiagonal()),
               std::invalid_argument);
  Eigen::Matrix3d skew = kInertia;
  skew(0, 1) = 1.0;
  EXPECT_THROW(model.addBody("asymmetric", hinge, 1.0, Eigen::Vector3d::Zero(), skew), std::invalid_argument);
  EXPECT_THROW(model.addSphericalCut("self", hinge, hinge), std::invalid_argument);
  EXPECT_THROW(model.addJointSpringDamper("spring", "no_such_joint", 1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(model.parameter("no_such.parameter"), std::invalid_argument);
  model.addJointSpringDamper("spring", "hinge", 5.0, 1.0);
  model.setParameter("spring.k", 7.0);
  EXPECT_EQ(model.value(std::get<JointSpringDamper>(model.forces()[0]).stiffness), 7.0);
}

// Every numeric parameter has a stable dotted name that reads and writes the model.
TEST(ModelParameters, DottedNamesAddressEveryForceAndBodyParameter) {
  Model model;
  const FrameIndex hinge = model.addRevolute("hinge", Model::ground, kZ);
  model.addBody("bob", hinge, 2.0, kX, kInertia);
  model.addJointSpringDamper("spring", "hinge", 5.0, 1.0, 0.25);
  model.addPointSpringDamper("strut", Model::ground, kX, hinge, kX, 3.0, 0.5, 1.5);
  const std::vector<std::string> names = model.parameterNames();
  for (const char* name : {"gravity.z", "bob.mass", "bob.com.x", "bob.Izz", "spring.k", "spring.c", "spring.rest",
                           "strut.k", "strut.c", "strut.rest_length"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  EXPECT_EQ(model.parameter("spring.rest"), 0.25);
  EXPECT_EQ(model.parameter("strut.rest_length"), 1.5);
  model.setParameter("bob.mass", 3.0);
  EXPECT_EQ(model.value(model.bodies()[0].mass), 3.0);
  // The builder's checks still hold, and a refused value leaves the model unchanged.
  EXPECT_THROW(model.setParameter("bob.mass", -1.0), std::invalid_argument);
  EXPECT_THROW(model.setParameter("bob.Izz", -5.0), std::invalid_argument);
  EXPECT_THROW(model.setParameter("spring.k", std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_EQ(model.value(model.bodies()[0].mass), 3.0);
  EXPECT_EQ(model.parameter("spring.k"), 5.0);
}

// Elements hold indices into the model's parameter vector: the names list them in index order,
// a copy of the model reads its own values through the same indices, and a time input is a
// parameter only while it is constant.
TEST(ModelParameters, IndicesFollowTheNamesAndSurviveACopy) {
  Model model;
  const FrameIndex hinge = model.addRevolute("hinge", Model::ground, kZ);
  model.addBody("bob", hinge, 2.0, kX, kInertia);
  model.addJointSpringDamper("spring", "hinge", 5.0, 1.0, 0.25);
  model.addGuidanceSpring("guide", "hinge", 1.0, 0.0, TimeFunction::harmonic(0.1, 2.0));
  model.addJointActuation("push", "hinge", TimeFunction::constant(4.0));
  const std::vector<std::string>& names = model.parameterNames();
  ASSERT_EQ(static_cast<int>(names.size()), model.parameterCount());
  for (int i = 0; i < model.parameterCount(); ++i)
    EXPECT_EQ(model.parameterIndex(names[static_cast<std::size_t>(i)]), static_cast<ParameterIndex>(i));
  const auto& guide = std::get<JointSpringDamper>(model.forces()[1]);
  EXPECT_FALSE(guide.rest.isConstant());  // a moving target
  EXPECT_EQ(std::find(names.begin(), names.end(), "guide.rest"), names.end());
  EXPECT_DOUBLE_EQ(model.value(guide.rest, 0.5), 0.1 * std::sin(1.0));
  const auto& push = std::get<JointActuation>(model.forces()[2]);
  ASSERT_TRUE(push.force.isConstant());
  EXPECT_EQ(model.value(push.force, 0.5), 4.0);
  Model copy = model;
  copy.setParameter("push.value", 6.0);
  copy.setParameter("bob.com.x", 0.5);
  EXPECT_EQ(copy.value(push.force, 0.5), 6.0);  // the original's element, the copy's vector
  EXPECT_EQ(model.value(push.force, 0.5), 4.0);
  EXPECT_EQ(copy.centreOfMass(copy.bodies()[0]), Eigen::Vector3d(0.5, 0.0, 0.0));
  EXPECT_EQ(model.centreOfMass(model.bodies()[0]), kX);
  EXPECT_EQ(copy.inertia(copy.bodies()[0]), kInertia);
}
