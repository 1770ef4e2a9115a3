// A runnable scene: a model, its initial state and its integration settings.
#pragma once

#include <Eigen/Core>

#include "mbsopt/model/model.hpp"
#include "mbsopt/integrators/integrator_choice.hpp"
#include "mbsopt/integrators/newmark.hpp"

namespace mbsopt {

struct Scene {
  Model model;
  Eigen::VectorXd q0;  ///< initial coordinates (all, driven ones included)
  Eigen::VectorXd v0;  ///< initial rates
  NewmarkSettings settings;
  IntegratorChoice integrator;  ///< the scene's `settings.integrator` (fixed-step Newmark by default)
};

}  // namespace mbsopt
