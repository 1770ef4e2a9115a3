// NLopt's gradient-based local optimizers (Debian's 2.7.1): SLSQP, MMA, CCSAQ, behind the common
// interface, with that version's traps handled (docs/design.md §5): every stopping
// criterion set (none is by default), ROUNDOFF_LIMITED and FORCED_STOP caught (the C++ API throws
// them with x still holding the point), "success" re-checked for feasibility (SLSQP can claim it at
// an infeasible point, NLopt's bug 368, fixed only in 2.8), and evaluations cached (MMA and CCSAQ ask for gradients on inner iterations).
#pragma once

#include <nlopt.hpp>
#include <optional>

#include "mbsopt/optimizers/optimizer.hpp"

namespace mbsopt {

/// An NLopt algorithm and, for one that wraps another (AUGLAG), the local algorithm inside it.
struct NloptAlgorithm {
  nlopt::algorithm algorithm;
  std::optional<nlopt::algorithm> local;
};

/// One NLopt run. An "iteration" is one objective evaluation the algorithm asks for (NLopt has no
/// iteration callback), so `max_iterations` is NLopt's evaluation budget. A local algorithm stops on
/// the same relative change of x as the outer one.
OptimizerResult minimizeWithNlopt(const NloptAlgorithm& algorithm, NlpProblem& problem, const OptimizerOptions& options);

}  // namespace mbsopt
