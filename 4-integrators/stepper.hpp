// The contract of a one-step integrator that step controllers drive (Drake's DoStep, SUNDIALS'
// step return flags): from an initialized state at time(), attemptStep(t_next) solves one step
// without taking it; after a converged attempt exactly one of acceptStep() (the projections and
// checks, after which time() is t_next) or rejectStep() (back to the state before the attempt)
// follows; any other outcome of an attempt leaves the state as it was. Every outcome is typed
// (StepOutcome), and only smallerStepMayHelp(status) is retried with a smaller step.
// NewmarkIntegrator is the model; the conformance tests (tests/4-integrators/
// test_every_integrator.cpp) hold every registered integrator to this contract.
#pragma once

#include <Eigen/Core>
#include <concepts>

#include "mbsopt/integrators/step_outcome.hpp"

namespace mbsopt {

template <class Integrator>
concept Stepper = requires(Integrator integrator, const Integrator& done, const Eigen::VectorXd& state, double t) {
  integrator.initialize(state, state, t);
  { integrator.attemptStep(t) } -> std::same_as<StepOutcome>;
  { integrator.acceptStep() } -> std::same_as<StepOutcome>;
  integrator.rejectStep();
  { done.time() } -> std::convertible_to<double>;
  { done.q() } -> std::convertible_to<const Eigen::VectorXd&>;
  { done.v() } -> std::convertible_to<const Eigen::VectorXd&>;
  { done.a() } -> std::convertible_to<const Eigen::VectorXd&>;
  { done.lambda() } -> std::convertible_to<const Eigen::VectorXd&>;
};

}  // namespace mbsopt
