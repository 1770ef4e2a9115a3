#include "mbsopt/optimizers/auglag_lbfgs.hpp"

#include "mbsopt/optimizers/nlopt_optimizer.hpp"

namespace mbsopt {

OptimizerResult minimizeWithAuglagLbfgs(NlpProblem& problem, const OptimizerOptions& options) {
  return minimizeWithNlopt({nlopt::AUGLAG, nlopt::LD_LBFGS}, problem, options);
}

}  // namespace mbsopt
