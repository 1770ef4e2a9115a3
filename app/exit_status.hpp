// The exit statuses of mbsopt besides 0 (success) and 1 (an error: bad input, a run that failed its
// own checks).
#pragma once

#include <stdexcept>

namespace mbsopt {

/// `mbsopt optimize` ran, but its optimizer did not converge (it failed, its budget ran out, or it
/// cannot take the problem): the outputs are written, the summary says why, and the status is 2.
inline constexpr int kExitNotConverged = 2;
struct NotConverged : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace mbsopt
