// One run of a work-precision study (`mbsopt precision`): what was run, how far its result
// is from the reference and how long it took; shared by the integrator and the gradient studies.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mbsopt {

struct PrecisionRun {
  std::string variant;  ///< an integrator variant ("newmark", "damped", ...) or a gradient method ("adjoint", ...)
  double step = 0.0;    ///< h [s]
  bool failed = false;
  std::string message;  ///< why it failed (empty when it did not)
  double error = std::numeric_limits<double>::quiet_NaN();  ///< the largest of `errors`; NaN when failed
  std::vector<std::pair<std::string, double>> errors;       ///< per compared quantity or functional
  double seconds = std::numeric_limits<double>::quiet_NaN();  ///< median wall time (to the failure if failed)
  std::optional<long> steps, newton_iterations;                ///< for integrator runs
  std::optional<double> estimated_error;  ///< the run's own estimate of `error` (extrapolation)
};

/// "a, b, c" (names in messages and headings).
inline std::string listed(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

/// `run` marked as failed, with the exception's message.
inline PrecisionRun failedRun(PrecisionRun run, const std::exception& e) {
  run.failed = true;
  run.message = e.what();
  return run;
}

/// Sets `seconds` to the median wall time of `repeat` calls of run() (at least one). An exception from
/// run() ends the series and propagates; `seconds` then holds the time of the failing call.
template <class Run>
void timeMedian(int repeat, Run&& run, double& seconds) {
  std::vector<double> times;
  for (int r = 0; r < std::max(repeat, 1); ++r) {
    const auto start = std::chrono::steady_clock::now();
    try {
      run();
    } catch (...) {
      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      throw;
    }
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(times.begin(), times.end());
  const std::size_t middle = times.size() / 2;
  seconds = times.size() % 2 ? times[middle] : 0.5 * (times[middle - 1] + times[middle]);
}

/// Progress of a study on stderr: silent for a study that ends within a second, then at most a line
/// per second, so that long studies say where they are.
class StudyProgress {
 public:
  explicit StudyProgress(std::size_t runs) : runs_(runs) {}
  /// After each run: "  [done/runs] what".
  void ran(const std::string& what) {
    ++done_;
    say("[" + std::to_string(done_) + "/" + std::to_string(runs_) + "] " + what);
  }
  /// Any other news (a long reference run).
  void say(const std::string& what) {
    const auto now = std::chrono::steady_clock::now();
    if (now - start_ < std::chrono::seconds(1) || now - last_ < std::chrono::seconds(1)) return;
    last_ = now;
    std::fprintf(stderr, "  %s (%.1f s elapsed)\n", what.c_str(), std::chrono::duration<double>(now - start_).count());
  }

 private:
  std::size_t runs_, done_ = 0;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_{};
};

}  // namespace mbsopt
