// Independent evaluations on several threads (5-sensitivity/parallel_runs.hpp: `mbsopt compare --jobs`, finite differences):
// every item runs once, a failure surfaces as in a serial run, and design evaluations and
// optimisations on separate problem copies give bit-identical results whatever runs beside them
// (each has its own model and workspaces; Ipopt's solves are serialised inside the adapter).
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <memory>
#include <string>
#include <stdexcept>

#include "mbsopt/sensitivity/gradient_method.hpp"
#include "mbsopt/sensitivity/newmark_derivatives.hpp"
#include "mbsopt/sensitivity/parallel_runs.hpp"
#include "mbsopt/optimizers/optimizer.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "mbsopt/design/design_nlp.hpp"
#include "tests/sensitivity_scenes.hpp"

namespace mbsopt {
namespace {

TEST(ParallelRuns, EveryItemRunsOnceWhateverTheNumberOfThreads) {
  for (const int jobs : {1, 2, 3, 64}) {
    std::array<std::atomic<int>, 20> calls{};
    runInParallel(calls.size(), jobs, [&](std::size_t i) { ++calls[i]; });
    for (const auto& count : calls) EXPECT_EQ(count.load(), 1) << jobs << " jobs";
  }
}

// A budget lends what is idle and no more; runInParallel gives it the threads that have no item:
// those beyond the items at the start, and each one as it runs out of items.
TEST(ParallelRuns, IdleThreadsAreLentOnceAndGivenBack) {
  ThreadBudget budget(2);
  EXPECT_EQ(budget.borrow(3), 2);
  EXPECT_EQ(budget.borrow(1), 0);
  budget.giveBack(1);
  {
    const BorrowedThreads borrowed(budget, 4);
    EXPECT_EQ(borrowed.count(), 1);
    EXPECT_EQ(budget.idle(), 0);
  }
  EXPECT_EQ(budget.idle(), 1);
  budget.reclaim();  // a thread that lent itself takes itself back while lent out
  budget.reclaim();
  EXPECT_EQ(budget.idle(), -1);
  EXPECT_EQ(budget.borrow(1), 0);

  ThreadBudget idle;
  std::array<int, 2> idle_during{};
  runInParallel(idle_during.size(), 5, [&](std::size_t i) { idle_during[i] = idle.idle(); }, &idle);
  for (const int count : idle_during) EXPECT_GE(count, 3);  // five jobs, two items: three idle from the start
  EXPECT_EQ(idle.idle(), 5);
  ThreadBudget serial;
  runInParallel(3, 1, [](std::size_t) {}, &serial);
  EXPECT_EQ(serial.idle(), 1);
}

TEST(ParallelRuns, TheLowestFailingItemIsRethrownAfterAllHaveRun) {
  std::array<std::atomic<int>, 12> calls{};
  try {
    runInParallel(calls.size(), 3, [&](std::size_t i) {
      ++calls[i];
      if (i == 4 || i == 9) throw std::runtime_error("item " + std::to_string(i));
    });
    FAIL() << "nothing was rethrown";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "item 4");
  }
  for (const auto& count : calls) EXPECT_EQ(count.load(), 1);
}

/// The four-bar design problem over its first 0.25 s (the test is about threads, not about the
/// motion: short runs keep it quick under the sanitizers).
DesignProblem fourBar() {
  SceneSource source = readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/four_bar.yaml");
  source.text += test::kFourBarDesign;
  return loadDesignProblem(source, {{"settings.end_time", 0.25}});
}

/// The values and adjoint gradients at the start moved by `shift` in every variable.
NlpEvaluation evaluateShifted(const DesignProblem& problem, double shift) {
  DesignNlp nlp(problem, "adjoint");
  NlpEvaluation out;
  nlp.evaluate(nlp.start().array() * (1.0 + shift), true, out);
  return out;
}

// A closed loop (SVD partition, thread-local buffers of B and M) with adjoint gradients: four
// points on two threads equal the same points one after the other, to the bit.
TEST(ParallelRuns, ConcurrentDesignEvaluationsAreBitIdenticalToSerialOnes) {
  const DesignProblem problem = fourBar();
  const std::array<double, 4> shifts{0.0, 0.01, -0.02, 0.03};
  std::array<NlpEvaluation, 4> serial, parallel;
  runInParallel(shifts.size(), 1, [&](std::size_t i) { serial[i] = evaluateShifted(problem, shifts[i]); });
  runInParallel(shifts.size(), 2, [&](std::size_t i) { parallel[i] = evaluateShifted(problem, shifts[i]); });
  for (std::size_t i = 0; i < shifts.size(); ++i) {
    EXPECT_EQ(serial[i].cost, parallel[i].cost);
    EXPECT_EQ(serial[i].constraints, parallel[i].constraints);
    EXPECT_EQ(serial[i].cost_gradient, parallel[i].cost_gradient);
    EXPECT_EQ(serial[i].constraint_jacobian, parallel[i].constraint_jacobian);
  }
}

// Finite differences on several threads: every simulation the same as on one, so the same
// gradient to the bit, central and forward, with and without the simulation at x given.
TEST(ParallelRuns, FiniteDifferencesOnTwoThreadsEqualThoseOnOne) {
  DesignProblem problem = fourBar();
  problem.design.artificial.initial = 0.01;  // below max |joint_c_y|: the cost's constraints are active
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  const DesignResponse at_x = evaluateDesign(problem, functionals, x);
  for (const bool central : {true, false})
    for (const DesignResponse* simulated : {static_cast<const DesignResponse*>(nullptr), &at_x}) {
      const DesignGradient one = finiteDifferenceGradient(problem, functionals, x, 1e-5, central, simulated, 1);
      const DesignGradient two = finiteDifferenceGradient(problem, functionals, x, 1e-5, central, simulated, 2);
      EXPECT_EQ(one.constraints, two.constraints) << (central ? "central" : "forward");
      EXPECT_EQ(one.cost, two.cost);
      // Not a comparison of zeros: some constraint moves with the design variables.
      EXPECT_GT(one.constraints.leftCols(x.size() - 1).cwiseAbs().maxCoeff(), 0.0);
    }
}

/// The four-bar problem over 0.6 s: more time points than a PointStream holds, so its buffer wraps.
DesignProblem fourBarOverSixTenths() {
  SceneSource source = readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/four_bar.yaml");
  source.text += test::kFourBarDesign;
  DesignProblem problem = loadDesignProblem(source, {{"settings.end_time", 0.6}});
  problem.design.artificial.initial = 0.01;  // below max |joint_c_y|: the cost's constraints are active
  EXPECT_GT(problem.scene.settings.end_time / problem.scene.settings.step,
            static_cast<double>(TrajectoryDerivatives::PointStream::kAhead));
  return problem;
}

// The points of a sweep computed ahead by helper threads (TrajectoryDerivatives::PointStream), in
// both directions, past the buffer's wrap: the same points in the same order, to the bit, whatever
// the number of threads.
TEST(ParallelRuns, PointStreamsHandOutTheSamePointsWhateverTheNumberOfThreads) {
  const DesignProblem problem = fourBarOverSixTenths();
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  TrajectoryDerivatives serial(problem, functionals, x), parallel(problem, functionals, x);
  const Eigen::Index last = serial.timePoints() - 1;
  for (const int jobs : {2, 3})
    for (const bool forward : {true, false}) {
      TrajectoryDerivatives::PointStream one(serial, forward ? 1 : last, forward ? last : 1, 1);
      TrajectoryDerivatives::PointStream many(parallel, forward ? 1 : last, forward ? last : 1, jobs);
      for (Eigen::Index n = 0; n < last; ++n) {
        const TrajectoryDerivatives::PointDerivatives& a = one.next();
        const TrajectoryDerivatives::PointDerivatives& b = many.next();
        ASSERT_TRUE(a.step.mass == b.step.mass && a.step.stiffness == b.step.stiffness &&
                    a.step.damping == b.step.damping && a.step.parameters == b.step.parameters &&
                    a.closure.jacobian == b.closure.jacobian && a.seeds.position == b.seeds.position &&
                    a.seeds.acceleration == b.seeds.acceleration)
            << "point " << n << " of the " << (forward ? "forward" : "backward") << " stream, " << jobs << " jobs";
      }
    }
}

// With jobs ≥ 2 the simulation runs on a thread of its own while the others evaluate the points
// already stored (TrajectoryDerivatives::earlyPoints()); the streams hand those out. Every matrix of
// every point, and the simulation's values, the same to the bit as when all is done after the
// simulation on one thread, in both directions (a forward stream starts with the early points, a
// backward one ends with them).
TEST(ParallelRuns, PointsEvaluatedDuringTheSimulationEqualThoseEvaluatedAfterIt) {
  const DesignProblem problem = fourBarOverSixTenths();
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  TrajectoryDerivatives serial(problem, functionals, x);
  const Eigen::Index last = serial.timePoints() - 1;
  const Eigen::MatrixXd none = Eigen::MatrixXd::Zero(serial.functionalCount(), serial.variableCount());
  for (const int jobs : {2, 3})
    for (const bool forward : {true, false}) {
      // How far the evaluations get before the simulation ends depends on the scheduler: on a busy
      // machine a try may see none, so a few tries (a run with none falls back to the serial path).
      std::unique_ptr<TrajectoryDerivatives> early;
      for (int attempt = 0; attempt < 20 && (!early || early->earlyPoints() == 0); ++attempt)
        early = std::make_unique<TrajectoryDerivatives>(problem, functionals, x, nullptr, jobs);
      ASSERT_GT(early->earlyPoints(), 0) << jobs << " jobs";
      const DesignGradient a = serial.gradient(none), b = early->gradient(none);
      ASSERT_EQ(a.values->cost, b.values->cost);
      ASSERT_EQ(a.values->constraints, b.values->constraints);
      TrajectoryDerivatives::PointStream one(serial, forward ? 1 : last, forward ? last : 1, 1);
      TrajectoryDerivatives::PointStream many(*early, forward ? 1 : last, forward ? last : 1, jobs);
      for (Eigen::Index n = 0; n < last; ++n) {
        const TrajectoryDerivatives::PointDerivatives& p = one.next();
        const TrajectoryDerivatives::PointDerivatives& q = many.next();
        const StepDerivatives &s = p.step, &t = q.step;
        const ClosureDerivatives &c = p.closure, &d = q.closure;
        ASSERT_TRUE(s.mass == t.mass && s.damping == t.damping && s.stiffness == t.stiffness &&
                    s.parameters == t.parameters && c.jacobian == d.jacobian && c.velocity_q == d.velocity_q &&
                    c.acceleration_q == d.acceleration_q &&
                    c.velocity_projection == d.velocity_projection &&
                    c.acceleration_projection == d.acceleration_projection &&
                    c.velocity_projection_parameters == d.velocity_projection_parameters &&
                    c.acceleration_projection_parameters == d.acceleration_projection_parameters &&
                    p.seeds.position == q.seeds.position && p.seeds.velocity == q.seeds.velocity &&
                    p.seeds.acceleration == q.seeds.acceleration)
            << "point " << n << " of the " << (forward ? "forward" : "backward") << " stream, " << jobs << " jobs, "
            << early->earlyPoints() << " early points";
      }
    }
}

// A simulation that fails part-way while points are being evaluated beside it: the exact methods
// raise its error, as on one thread (no hang, no crash, no partial gradient).
TEST(ParallelRuns, ASimulationThatFailsBesideTheEvaluationsRaisesItsError) {
  DesignProblem problem = fourBarOverSixTenths();
  problem.scene.settings.energy_tolerance = 1e-9;  // the energy drifts past this at t = 0.094 s
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  for (const std::string method : {"adjoint", "direct"}) {
    std::string serial_error;
    try {
      designGradient(method, problem, functionals, x, 1e-6, nullptr, 1);
    } catch (const SimulationError& error) {
      serial_error = error.what();
    }
    ASSERT_NE(serial_error.find("energy"), std::string::npos) << method << ": " << serial_error;
    for (const int jobs : {2, 3}) {
      try {
        designGradient(method, problem, functionals, x, 1e-6, nullptr, jobs);
        ADD_FAILURE() << method << ", " << jobs << " jobs: no error";
      } catch (const SimulationError& error) {
        EXPECT_EQ(std::string(error.what()), serial_error) << method << ", " << jobs << " jobs";
      }
    }
  }
}

// The step derivatives of adjoint and direct on two and three threads, on a closed loop: the same
// gradients to the bit as on one thread.
TEST(ParallelRuns, ExactGradientsOnTwoThreadsEqualThoseOnOne) {
  const DesignProblem problem = fourBarOverSixTenths();
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  const Eigen::VectorXd x = initialPoint(problem);
  for (const std::string method : {"adjoint", "direct"}) {
    const DesignGradient one = designGradient(method, problem, functionals, x, 1e-6, nullptr, 1);
    EXPECT_GT(one.constraints.leftCols(x.size() - 1).cwiseAbs().maxCoeff(), 0.0) << method;  // not zeros
    for (const int jobs : {2, 3}) {
      const DesignGradient many = designGradient(method, problem, functionals, x, 1e-6, nullptr, jobs);
      EXPECT_EQ(one.constraints, many.constraints) << method << ", " << jobs << " jobs";
    }
  }
}

// Whole optimisations, two of them Ipopt's (one solve at a time inside the adapter), beside SDCC
// and SLSQP, as `mbsopt compare --jobs 2` runs them: two at a time, and the gradients and the
// simulations ahead of the runs still going on the thread of a run that has ended. The same points,
// costs and evaluation counts as when each runs alone on one thread; every thread lent is given back.
TEST(ParallelRuns, ConcurrentOptimisationsEqualSerialOnes) {
  const DesignProblem problem = loadDesignProblem({"chain.yaml", test::kOpenChainProblem}, {{"settings.end_time", 0.3}});
  const std::array<std::string, 4> optimizers{"ipopt", "sdcc", "ipopt", "slsqp"};
  OptimizerOptions options;
  options.max_iterations = 15;
  std::array<OptimizerResult, 4> serial, parallel;
  const auto idle_threads = std::make_shared<ThreadBudget>();
  const auto run = [&](std::array<OptimizerResult, 4>& out, std::size_t i, int jobs) {
    DesignNlp nlp(problem, "adjoint", 1e-6, jobs, jobs > 1 ? idle_threads : nullptr);
    out[i] = minimize(optimizers[i], nlp, options);
  };
  runInParallel(optimizers.size(), 1, [&](std::size_t i) { run(serial, i, 1); });
  runInParallel(optimizers.size(), 2, [&](std::size_t i) { run(parallel, i, 2); }, idle_threads.get());
  EXPECT_EQ(idle_threads->idle(), 2);  // both threads idle again, none lent twice or kept
  for (std::size_t i = 0; i < optimizers.size(); ++i) {
    EXPECT_EQ(serial[i].x, parallel[i].x) << optimizers[i];
    EXPECT_EQ(serial[i].cost, parallel[i].cost) << optimizers[i];
    EXPECT_EQ(serial[i].value_evaluations, parallel[i].value_evaluations) << optimizers[i];
    EXPECT_EQ(serial[i].status, parallel[i].status) << optimizers[i];
    EXPECT_GT(serial[i].value_evaluations, 3) << optimizers[i];  // runs that went somewhere
  }
  EXPECT_EQ(serial[0].x, serial[2].x);  // and the two Ipopt runs agree with each other
}

// SDCC with two jobs: after a rejected trial the next one is simulated on a second thread while
// the current one is (DesignNlp::anticipate). The run visits the same points, to the bit, with the
// same counts as with one job; some of those simulations did run ahead (on the four-bar with
// ξ₀ = 4 the trials overshoot often, so runs of rejections happen). With a thread shared with other
// runs (`mbsopt compare`), idle throughout, nothing runs ahead: only the gradients borrow it.
TEST(ParallelRuns, SdccWithSimulationsAheadEqualsSdccWithout) {
  SceneSource source = readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/four_bar.yaml");
  source.text += test::kFourBarDesign;
  const DesignProblem problem = loadDesignProblem(source, {{"settings.end_time", 0.6}});
  OptimizerOptions options;
  options.max_iterations = 40;
  options.settings = {{"initial_step_bound", "4"}};
  DesignNlp one_job(problem, "adjoint", 1e-6, 1), two_jobs(problem, "adjoint", 1e-6, 2);
  const OptimizerResult serial = minimize("sdcc", one_job, options);
  const OptimizerResult ahead = minimize("sdcc", two_jobs, options);
  EXPECT_EQ(serial.x, ahead.x);
  EXPECT_EQ(serial.cost, ahead.cost);
  EXPECT_EQ(serial.value_evaluations, ahead.value_evaluations);
  EXPECT_EQ(serial.gradient_evaluations, ahead.gradient_evaluations);
  ASSERT_EQ(serial.history.size(), ahead.history.size());
  for (std::size_t k = 0; k < serial.history.size(); ++k) EXPECT_EQ(serial.history[k].x, ahead.history[k].x) << k;
  EXPECT_EQ(one_job.simulationsAhead(), 0);
  EXPECT_GT(two_jobs.simulationsAheadUsed(), 0);
  const auto idle_thread = std::make_shared<ThreadBudget>(1);
  DesignNlp shared_thread(problem, "adjoint", 1e-6, 2, idle_thread);
  const OptimizerResult shared = minimize("sdcc", shared_thread, options);
  EXPECT_EQ(serial.x, shared.x);
  EXPECT_EQ(serial.value_evaluations, shared.value_evaluations);
  EXPECT_EQ(shared_thread.simulationsAhead(), 0);
  EXPECT_EQ(idle_thread->idle(), 1);
}

}  // namespace
}  // namespace mbsopt
