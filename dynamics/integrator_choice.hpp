// Which integrator a scene runs with (its `settings.integrator`, `settings.extrapolation_runs`): the
// registry of dynamics/integration.hpp names them.
#pragma once

#include <string>

namespace mbsopt {

struct IntegratorChoice {
  std::string name = "newmark";  ///< newmark | extrapolation
  /// Extrapolation at the scene's step as its macro step: Newmark runs at h/1 … h/runs.
  int extrapolation_runs = 3;

  bool extrapolated() const { return name == "extrapolation"; }
};

}  // namespace mbsopt
