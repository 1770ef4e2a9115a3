// Idle threads, lent for as long as a piece of work needs them. `mbsopt compare` runs several
// optimizations at once, one thread each; when no run is left to start, a thread that finishes its
// run is idle, and the runs still going borrow it for their gradients. A lone run (`mbsopt
// optimize`) holds a budget of its own spare threads, for its gradients and its simulations ahead
// (DesignNlp). Borrowing never waits: it takes what is idle at that moment. The results never
// depend on what was borrowed (gradients and simulations are the same to the bit on any number of
// threads).
#pragma once

#include <algorithm>
#include <atomic>

namespace mbsopt {

class ThreadBudget {
 public:
  /// `idle`: the threads no one uses yet.
  explicit ThreadBudget(int idle = 0) : idle_(idle) {}
  ThreadBudget(const ThreadBudget&) = delete;
  ThreadBudget& operator=(const ThreadBudget&) = delete;

  /// Takes up to `wanted` idle threads; returns how many (0 when none is idle).
  int borrow(int wanted) {
    int idle = idle_.load();
    for (;;) {
      const int taken = std::min(idle, wanted);
      if (taken <= 0) return 0;
      if (idle_.compare_exchange_weak(idle, idle - taken)) return taken;
    }
  }
  /// Threads that became idle: borrowed ones given back, or a thread whose own work has ended.
  void giveBack(int count) { idle_ += count; }
  /// A thread that lent itself while it waited (giveBack(1)) takes itself back, whether or not
  /// another one borrowed it meanwhile: for that while, one thread more runs than the budget has.
  void reclaim() { --idle_; }
  /// The threads idle now (negative while a reclaimed thread is still lent out).
  int idle() const { return idle_.load(); }

 private:
  std::atomic<int> idle_;
};

/// Idle threads borrowed from a budget for as long as this object lives.
class BorrowedThreads {
 public:
  BorrowedThreads(ThreadBudget& budget, int wanted) : budget_(budget), count_(budget.borrow(wanted)) {}
  ~BorrowedThreads() { budget_.giveBack(count_); }
  BorrowedThreads(const BorrowedThreads&) = delete;
  BorrowedThreads& operator=(const BorrowedThreads&) = delete;
  int count() const { return count_; }

 private:
  ThreadBudget& budget_;
  int count_;
};

}  // namespace mbsopt
