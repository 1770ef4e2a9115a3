// Ipopt (Debian's 3.11.9) behind the common interface: a TNLP over the NlpProblem with dense
// constraint Jacobians and a limited-memory (L-BFGS) Hessian, the history from its
// intermediate_callback (docs/design.md §5). An "iteration" is one of Ipopt's own.
#pragma once

#include "mbsopt/optimizers/optimizer.hpp"

namespace mbsopt {

OptimizerResult minimizeWithIpopt(NlpProblem& problem, const OptimizerOptions& options);

}  // namespace mbsopt
