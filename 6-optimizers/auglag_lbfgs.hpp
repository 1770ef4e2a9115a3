// NLopt's augmented Lagrangian (AUGLAG, Conn, Gould & Toint; Birgin & Martínez) around its
// limited-memory BFGS (LD_LBFGS, Nocedal 1980): a quasi-Newton method on the same gradients, which
// takes equalities as well as inequalities by penalising both in the Lagrangian it minimises.
#pragma once

#include "mbsopt/optimizers/optimizer.hpp"

namespace mbsopt {

inline constexpr const char* kAuglagLbfgsDescription =
    "NLopt's augmented Lagrangian around its limited-memory BFGS: quasi-Newton, equalities and inequalities "
    "through the penalty";

OptimizerResult minimizeWithAuglagLbfgs(NlpProblem& problem, const OptimizerOptions& options);

}  // namespace mbsopt
