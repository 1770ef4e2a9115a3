// The integrator allocates nothing once it runs: after the first steps have sized every buffer, a
// Newmark step (Newton iterations, B and its partition, the mass matrix, the projections, a refresh
// of the AD tangent matrices) takes no memory from the heap, on an open chain and on closed loops
// small and large. Nor does a gradient's time point once the stream's slots have their sizes (its
// AD passes, the projections' multipliers, the copies into the slot), and a whole gradient's
// allocations do not grow with its time points. Every allocation of the process is counted: malloc
// and its relatives are interposed (or, under AddressSanitizer, which owns malloc, counted by its
// allocation hook), so Eigen's dynamic matrices and operator new are seen alike.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <limits>

#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/sensitivity/design_problem.hpp"
#include "mbsopt/sensitivity/direct_sensitivity.hpp"
#include "mbsopt/sensitivity/discrete_adjoint.hpp"
#include "mbsopt/sensitivity/newmark_derivatives.hpp"
#include "mbsopt/design/chain_scenes.hpp"
#include "mbsopt/design/tramway.hpp"

namespace {
std::atomic<long> allocations{0};
}  // namespace

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MBSOPT_ALLOCATOR_HOOK 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define MBSOPT_ALLOCATOR_HOOK 1
#endif

#ifdef MBSOPT_ALLOCATOR_HOOK
#include <sanitizer/allocator_interface.h>
namespace {
void countAllocation(const volatile void*, std::size_t) { ++allocations; }
void ignoreRelease(const volatile void*) {}
[[maybe_unused]] const int hooks_installed = __sanitizer_install_malloc_and_free_hooks(countAllocation, ignoreRelease);
}  // namespace
#else
// glibc's allocator under its internal names: every allocation of the process, operator new's
// included, passes through these definitions, which count and forward.
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t count, std::size_t size);
void* __libc_realloc(void* pointer, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);

void* malloc(std::size_t size) noexcept {
  ++allocations;
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) noexcept {
  ++allocations;
  return __libc_calloc(count, size);
}
void* realloc(void* pointer, std::size_t size) noexcept {
  ++allocations;
  return __libc_realloc(pointer, size);
}
void* memalign(std::size_t alignment, std::size_t size) noexcept {
  ++allocations;
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
  ++allocations;
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) noexcept {
  ++allocations;
  *out = __libc_memalign(alignment, size);
  return *out ? 0 : ENOMEM;
}
}
#endif

namespace mbsopt {
namespace {

/// What `steps` Newmark steps did after `warm_up` steps from the scene's start.
struct CountedSteps {
  long allocations = 0;
  long tangent_refreshes = 0;  ///< AD evaluations of the tangent matrices among them
  long mass_refreshes = 0;
};

CountedSteps countSteps(const Scene& scene, long warm_up, long steps) {
  NewmarkIntegrator integrator(scene.model, scene.settings);
  integrator.initialize(scene.q0, scene.v0);
  for (long k = 0; k < warm_up; ++k) integrator.step();
  const IntegratorStatistics before = integrator.statistics();
  const long allocations_before = allocations.load();
  for (long k = 0; k < steps; ++k) integrator.step();
  const long counted = allocations.load() - allocations_before;
  const IntegratorStatistics& after = integrator.statistics();
  return {counted, after.jacobian_updates - before.jacobian_updates, after.mass_updates - before.mass_updates};
}

TEST(Allocations, TheCounterSeesEigenAndOperatorNew) {
  // The counter itself must work, or every zero below would mean nothing.
  const long before = allocations.load();
  Eigen::VectorXd* vector = new Eigen::VectorXd(Eigen::VectorXd::Zero(100));
  const long after = allocations.load();
  delete vector;
  EXPECT_GE(after - before, 2);  // the object and its coefficients
}

TEST(Allocations, TramwayStepsAllocateNothing) {
  // 2 s in: bogie 1 is in the curve; the next second crosses the curvature jumps of bogie 2's entry.
  const CountedSteps counted = countSteps(tramwayScene(), 2000, 1000);
  EXPECT_EQ(counted.allocations, 0);
  EXPECT_GT(counted.mass_refreshes, 0);  // the closed loop's projections ran
}

TEST(Allocations, OpenChainStepsAllocateNothingEvenWhenTheTangentsAreRefreshed) {
  // At h = 5 ms the chain's modified Newton slows down on tens of these steps and refreshes the
  // tangents (at 1 ms, started from its extrapolated solutions, it hardly ever does).
  Scene scene = planarChainScene(8);
  scene.settings.step = 5e-3;
  const CountedSteps counted = countSteps(scene, 10, 200);
  EXPECT_EQ(counted.allocations, 0);
  EXPECT_GT(counted.tangent_refreshes, 0);  // the AD passes were among the counted steps
}

TEST(Allocations, ClosedChainStepsAllocateNothing) {
  // The tangents are not refreshed here (the open chain covers that path, the same code). 8 links:
  // the explicit products of the partition; 24: M by the articulated-body recursion and the
  // range-space solves (from NewmarkSettings::articulated_mass_from on), and, with those off, the
  // partition's reflectors (beyond 16 coordinates).
  for (const int links : {8, 24})
    for (const bool recursive : {true, false}) {
      Scene scene = closedPlanarChainScene(links);
      if (!recursive) scene.settings.articulated_mass_from = std::numeric_limits<int>::max();
      const CountedSteps counted = countSteps(scene, 10, 200);
      EXPECT_EQ(counted.allocations, 0) << links << " links";
      EXPECT_GT(counted.mass_refreshes, 0) << links << " links";  // B, M and the projections ran
    }
}

TEST(Allocations, GradientTimePointsAllocateNothingOnceTheStreamIsSized) {
  // The tram's design problem with the artificial variable at 2 m/s² (below max |a_lat|, so the
  // cost's seeds are non-zero where |a_lat| exceeds it): the points from the end back, as the
  // adjoint takes them, on one job. The stream holds at most kAhead slots (kRun on one job); after
  // twice kAhead points every slot has held a point, with and without sensors to differentiate.
  DesignProblem problem = tramwayDesignProblem();
  problem.design.artificial.initial = 2.0;
  const std::vector<ConstraintFunctional> functionals = transcribe(problem);
  TrajectoryDerivatives derivatives(problem, functionals, initialPoint(problem));
  const Eigen::Index last = derivatives.timePoints() - 1;
  TrajectoryDerivatives::PointStream points(derivatives, last, 1, 1);
  constexpr long kWarmUp = 2 * TrajectoryDerivatives::PointStream::kAhead, kCounted = 4000;
  ASSERT_GT(last, kWarmUp + kCounted);
  for (long n = 0; n < kWarmUp; ++n) points.next();
  const long before = allocations.load();
  long sensed = 0;
  for (long n = 0; n < kCounted; ++n) sensed += points.next().seeds.position.cwiseAbs().maxCoeff() > 0.0;
  EXPECT_EQ(allocations.load() - before, 0);
  EXPECT_GT(sensed, 0);         // points that differentiate sensors were among them
  EXPECT_LT(sensed, kCounted);  // and points that do not
}

TEST(Allocations, GradientAllocationsDoNotGrowWithTheTimePoints) {
  // The tram's problem over 6 s and over 12 s, one job: 6000 more time points. An allocation per
  // point or per backward step would add at least 6000; what may grow is the adjoint's sweep
  // buffers, resized where the set of active constraints changes, and the seeds it scans.
  for (const bool adjoint : {true, false}) {
    long counted[2] = {0, 0};
    for (const int half : {0, 1}) {
      DesignProblem problem = tramwayDesignProblem();
      problem.design.artificial.initial = 2.0;  // below max |a_lat|: the cost's seeds are non-zero
      problem.scene.settings.end_time = 6.0 * (half + 1);
      const std::vector<ConstraintFunctional> functionals = transcribe(problem);
      const Eigen::VectorXd x = initialPoint(problem);
      const long before = allocations.load();
      if (adjoint) adjointGradient(problem, functionals, x, nullptr, 1);
      else directGradient(problem, functionals, x, nullptr, 1);
      counted[half] = allocations.load() - before;
    }
    EXPECT_LT(counted[1] - counted[0], 600) << (adjoint ? "adjoint" : "direct") << ": " << counted[0] << " over 6 s, "
                                           << counted[1] << " over 12 s";
  }
}

}  // namespace
}  // namespace mbsopt
