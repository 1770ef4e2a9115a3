// Independent work items on a few threads of this machine (`--jobs N`: the runs of `mbsopt
// compare`, the simulations of finite differences): each item runs on one thread with its own state, items are taken in order, and what an item throws is rethrown after
// all have finished (the one of the lowest index), so a parallel run fails as a serial one would.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

#include "mbsopt/sensitivity/thread_budget.hpp"

namespace mbsopt {

/// The machine's hardware threads (at least 1): the default of `--jobs`.
inline int machineThreads() { return static_cast<int>(std::max(1U, std::thread::hardware_concurrency())); }

/// Calls task(i) for i = 0 … count − 1 on min(jobs, count) threads (jobs ≤ 1: in order, on this one).
/// With `idle_threads`, every thread of the jobs that has no item (left) to take is given to it, so
/// the items still running can borrow it (thread_budget.hpp).
template <class Task>
void runInParallel(std::size_t count, int jobs, Task&& task, ThreadBudget* idle_threads = nullptr) {
  std::vector<std::exception_ptr> failures(count);
  std::atomic<std::size_t> next{0};
  const auto work = [&] {
    for (std::size_t i = next++; i < count; i = next++) {
      try {
        task(i);
      } catch (...) {
        failures[i] = std::current_exception();
      }
    }
    if (idle_threads) idle_threads->giveBack(1);
  };
  const std::size_t threads = std::min<std::size_t>(static_cast<std::size_t>(std::max(jobs, 1)), count);
  if (idle_threads) idle_threads->giveBack(std::max(jobs, 1) - static_cast<int>(std::max<std::size_t>(threads, 1)));
  if (threads <= 1) {
    work();
  } else {
    std::vector<std::jthread> pool;
    for (std::size_t t = 0; t < threads; ++t) pool.emplace_back(work);
  }  // the jthreads join here
  for (const std::exception_ptr& failure : failures)
    if (failure) std::rethrow_exception(failure);
}

}  // namespace mbsopt
