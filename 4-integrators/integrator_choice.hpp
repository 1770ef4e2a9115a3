// Which integrator a scene runs with (its `settings.integrator`, `settings.extrapolation_runs`,
// `settings.local_tolerance`): the registry of 4-integrators/integration.hpp names them.
#pragma once

#include <string>

namespace mbsopt {

struct IntegratorChoice {
  std::string name = "newmark";  ///< newmark | extrapolation | adaptive
  /// Extrapolation at the scene's step as its macro step: Newmark runs at h/1 … h/runs.
  int extrapolation_runs = 3;
  /// The adaptive integrator: what each step's local error in a coordinate may be (its unit). A design
  /// problem runs on the steps such a run takes at its initial design, frozen (NewmarkSettings::time_grid).
  double local_tolerance = 1e-6;

  /// The registry's properties of `name` (IntegratorInfo, integration.cpp).
  bool extrapolated() const;
  bool adaptive() const;
};

}  // namespace mbsopt
