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
  std::optional<nlopt::algorithm> local = std::nullopt;
};

/// One NLopt run. An "iteration" is one objective evaluation the algorithm asks for (NLopt has no
/// iteration callback), so `max_iterations` is NLopt's evaluation budget. A local algorithm stops on
/// the options' relative change of x and of its own f: the augmented Lagrangian it minimises holds the
/// constraints' penalty, so its f moves while feasibility is restored (unlike b_{k+1}, whose test is
/// off). Without the f test, L-BFGS ran on into round-off and ended Hock-Schittkowski 71 as an NLopt
/// failure at a violation of 3e-8 in the sanitizer build's arithmetic.
OptimizerResult minimizeWithNlopt(const NloptAlgorithm& algorithm, NlpProblem& problem, const OptimizerOptions& options);

}  // namespace mbsopt
