// The time points' derivatives on several threads: evaluated while the simulation runs
// (TrajectoryDerivatives::simulateWhileEvaluating, packed in one buffer until a stream hands them
// out) and ahead of a sweep (TrajectoryDerivatives::PointStream). Every point is computed by the
// same code as on one thread (newmark_derivatives.cpp), on a workspace of its thread's own.
#include <algorithm>
#include <memory>

#include "mbsopt/sensitivity/newmark_derivatives.hpp"

namespace mbsopt {

namespace {

/// Calls f on each matrix of a point (its seeds excepted), in one fixed order.
template <class Point, class F>
void forEachMatrix(Point& point, F&& f) {
  auto& s = point.step;
  auto& c = point.closure;
  for (auto* matrix : {&s.mass, &s.damping, &s.stiffness, &s.parameters, &c.jacobian, &c.velocity_q, &c.acceleration_q,
                       &c.velocity_projection, &c.acceleration_projection, &c.velocity_projection_parameters,
                       &c.acceleration_projection_parameters, &c.position_parameters, &c.velocity_parameters,
                       &c.acceleration_parameters})
    f(*matrix);
}

/// Writes the shape and the coefficients of `m` at `out` and moves past them; false when they do not
/// fit before `end`.
template <class Matrix>
bool packMatrix(const Matrix& m, double*& out, const double* end) {
  if (end - out < 2 + m.size()) return false;
  *out++ = static_cast<double>(m.rows());
  *out++ = static_cast<double>(m.cols());
  out = std::copy(m.data(), m.data() + m.size(), out);
  return true;
}

template <class Matrix>
void unpackMatrix(const double*& in, Matrix& m) {
  m.resize(static_cast<Eigen::Index>(in[0]), static_cast<Eigen::Index>(in[1]));
  in += 2;
  std::copy(in, in + m.size(), m.data());
  in += m.size();
}

}  // namespace

bool TrajectoryDerivatives::packPoint(const PointDerivatives& point, const std::vector<ResponseJacobian>& sensors,
                                      double* out, const double* end) {
  bool fits = true;
  forEachMatrix(point, [&](const Eigen::MatrixXd& m) { fits = fits && packMatrix(m, out, end); });
  for (const ResponseJacobian& J : sensors) {
    if (!fits || out == end) return false;
    *out++ = J.value;
    fits = packMatrix(J.position, out, end) && packMatrix(J.velocity, out, end) &&
           packMatrix(J.acceleration, out, end) && packMatrix(J.parameters, out, end) &&
           packMatrix(J.multipliers, out, end);
  }
  // B's partition, with M factored when B has rows: the sweep copies it instead of computing it.
  const Eigen::Index m = point.closure.jacobian.rows(), nf = point.step.mass.rows();
  if (!fits || end - out < SvdPartition::storedFactoredSize(m, nf)) return false;
  point.closure.partition.storeFactored(out);
  return true;
}

void TrajectoryDerivatives::unpackPoint(const double* in, PointDerivatives& point, std::vector<ResponseJacobian>& sensors) const {
  forEachMatrix(point, [&](Eigen::MatrixXd& m) { unpackMatrix(in, m); });
  sensors.resize(functional_sensors_.size());
  for (ResponseJacobian& J : sensors) {
    J.value = *in++;
    unpackMatrix(in, J.position);
    unpackMatrix(in, J.velocity);
    unpackMatrix(in, J.acceleration);
    unpackMatrix(in, J.parameters);
    unpackMatrix(in, J.multipliers);
  }
  const Eigen::Index m = point.closure.jacobian.rows(), nf = point.step.mass.rows();
  point.closure.partition.loadFactored(in, m, nf, point.step.mass);
}

Eigen::Index TrajectoryDerivatives::packedPointSize() const {
  // M, C_T, K_T, G_v, G_a (nf² each); ∂f/∂b, P_v, P_a (nf p); B, ∂ḃ/∂q, ∂b̈/∂q (m nf); ∂b/∂b,
  // ∂ḃ/∂b, ∂b̈/∂b (m p at most); per sensor its value, three rows of nf, one of at most p and one of
  // at most m (∂g/∂λ); and two numbers for the shape of each of those matrices (forEachMatrix's 14,
  // five per sensor); then B's
  // partition and its factorization of M (SvdPartition::storedFactoredSize). packPoint refuses a
  // point that would not fit.
  const Eigen::Index nf = freeCount(), p = variableCount(), m = constraintCount();
  const auto sensors = static_cast<Eigen::Index>(functional_sensors_.size());
  return 5 * nf * nf + 3 * nf * p + 3 * m * nf + 3 * m * p + sensors * (1 + 3 * nf + p + m) + 2 * (14 + 5 * sensors) +
         SvdPartition::storedFactoredSize(m, nf);
}

void TrajectoryDerivatives::simulateWhileEvaluating(int jobs) {
  early_.stride = packedPointSize();
  const auto capacity = static_cast<long>(kEarlyBytes / (8.0 * static_cast<double>(early_.stride)));
  const auto helpers = static_cast<std::size_t>(jobs - 2);  // beside this thread and the simulation's
  if (thread_scratch_.size() < helpers) thread_scratch_.resize(helpers);
  std::mutex mutex;
  std::condition_variable changed;
  long stored = -1;  // the last time point complete in the trajectory
  long next = 1;     // the next point to evaluate
  long last = 0;     // the last point to evaluate, once point 0 is stored
  int waiting = 0;
  bool stop = false;  // the simulation has ended
  // Evaluations that caught up with the simulation wait for a batch of new points: woken at every
  // step, they would cost the simulation's thread a system call a step.
  const auto batchStored = [&] { return stored >= std::min(next + kWakeBatch - 1, last); };
  const auto available = [&] { return next <= stored && next <= last; };
  const auto finished = [&] { return stored >= 0 && next > last; };  // every point to evaluate is taken
  const auto help = [&](Scratch& s) {
    s.sensors = functional_sensors_;  // every sensor a functional reads: the seeds are not known yet
    s.sensor_slot = functional_sensor_slot_;
    std::unique_lock lock(mutex);
    for (;;) {
      if (!stop && !finished() && !available()) {  // caught up with the simulation
        ++waiting;
        changed.wait(lock, [&] { return stop || finished() || batchStored(); });
        --waiting;
      }
      if (stop || next > last) return;
      const long k = next++;
      lock.unlock();
      try {
        stepAndClosureAt(k, s, s.point);
        double* const begin = early_.values.get() + (k - 1) * early_.stride;
        early_.ready[static_cast<std::size_t>(k - 1)] = packPoint(s.point, s.sensor_jacobians, begin, begin + early_.stride);
      } catch (...) {  // evaluated again when a sweep reaches it, which then raises the error
      }
      lock.lock();
    }
  };
  std::exception_ptr failure;
  {
    std::vector<std::jthread> threads;
    // The simulation on a thread of its own: its workspaces come from that thread's heap arena,
    // off the cache lines the evaluations read (thread_scratch_).
    threads.emplace_back([&] {
      try {
        evaluateDesign(problem_, functionals_, x_, simulation_, [&](long k) {
          std::unique_lock lock(mutex);
          if (k == 0) {
            last = std::min(capacity, static_cast<long>(simulation_.trajectory.time.size()) - 1);
            early_.values.reset(new double[static_cast<std::size_t>(std::max(last, 0L) * early_.stride)]);
            early_.ready.assign(static_cast<std::size_t>(std::max(last, 0L)), 0);
          }
          stored = k;
          const bool wake = waiting > 0 && batchStored();
          lock.unlock();
          if (wake) changed.notify_all();
        }, /*keep_step_matrices=*/true);
      } catch (...) {
        failure = std::current_exception();
      }
      {
        const std::lock_guard lock(mutex);
        stop = true;  // each evaluation finishes the point it is on
      }
      changed.notify_all();
    });
    for (std::size_t t = 0; t < helpers; ++t) threads.emplace_back([&, t] { help(helperScratch(t)); });
    help(scratch_);
  }  // joins
  if (failure) std::rethrow_exception(failure);
  early_.ready.resize(static_cast<std::size_t>(std::min(next, last + 1) - 1));  // the points taken
  early_.count = static_cast<Eigen::Index>(std::count(early_.ready.begin(), early_.ready.end(), 1));
}

TrajectoryDerivatives::Scratch& TrajectoryDerivatives::helperScratch(std::size_t t) {
  std::unique_ptr<Scratch>& scratch = thread_scratch_[t].scratch;
  if (!scratch) scratch = std::make_unique<Scratch>(model_);
  return *scratch;
}

bool TrajectoryDerivatives::takeEarly(Eigen::Index k, PointDerivatives& out, std::vector<ResponseJacobian>& sensors) {
  if (k < 1 || k > static_cast<Eigen::Index>(early_.ready.size()) || !early_.ready[static_cast<std::size_t>(k - 1)])
    return false;
  early_.ready[static_cast<std::size_t>(k - 1)] = 0;
  unpackPoint(early_.values.get() + (k - 1) * early_.stride, out, sensors);
  sensorSeeds(k, functional_sensor_slot_, sensors, out.seeds);
  return true;
}

TrajectoryDerivatives::PointStream::PointStream(TrajectoryDerivatives& derivatives, Eigen::Index from, Eigen::Index to,
                                                int jobs)
    : d_(derivatives),
      from_(from),
      direction_(to >= from ? 1 : -1),
      total_(static_cast<long>(std::abs(to - from) + 1)) {
  // The points evaluated during the simulation, 1 … E, lie at one end of the stream: the start of a
  // forward one, the end of a backward one. The ring holds the others.
  const auto early = static_cast<long>(d_.early_.ready.size());
  if (direction_ > 0) {
    begin_ = std::clamp<long>(early - static_cast<long>(from) + 1, 0, total_);
    count_ = total_ - begin_;
  } else {
    count_ = std::clamp<long>(static_cast<long>(from) - early, 0, total_);
  }
  const auto helpers = static_cast<std::size_t>(std::clamp<long>(jobs - 1, 0, std::max(count_ - 1, 0L)));
  // Alone, the sweep's thread evaluates a run at a time and needs no more slots than a run: fewer
  // matrices to size (a few hundred allocations instead of ten thousand) and to keep in cache.
  capacity_ = std::min(count_, helpers > 0 ? kAhead : kRun);
  slots_.resize(static_cast<std::size_t>(capacity_));
  failures_.resize(slots_.size());
  ready_.assign(slots_.size(), 0);
  if (d_.thread_scratch_.size() < helpers) d_.thread_scratch_.resize(helpers);
  for (std::size_t t = 0; t < helpers; ++t) helpers_.emplace_back([this, t] { help(d_.helperScratch(t)); });
}

TrajectoryDerivatives::PointStream::~PointStream() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
}

long TrajectoryDerivatives::PointStream::freeSlots() const {
  // A slot is free once the sweep has moved past its point: the one handed last may be in use.
  return std::max(handed_ - 1, 0L) + capacity_ - taken_;
}

bool TrajectoryDerivatives::PointStream::helpersMayResume() const {
  return freeSlots() >= std::min(kRun, count_ - taken_);
}

long TrajectoryDerivatives::PointStream::take() {
  if (taken_ >= count_ || freeSlots() <= 0) return -1;
  return taken_++;
}

void TrajectoryDerivatives::PointStream::evaluate(long n, Scratch& scratch) {
  const std::size_t i = slot(n);
  if (n + 1 < count_) d_.prefetch(pointOf(begin_ + n + 1));  // most often this thread's next
  try {
    d_.pointAt(pointOf(begin_ + n), scratch, slots_[i]);
    failures_[i] = nullptr;
  } catch (...) {
    failures_[i] = std::current_exception();
  }
}

void TrajectoryDerivatives::PointStream::help(Scratch& scratch) {
  std::unique_lock lock(mutex_);
  while (!stopping_ && taken_ < count_) {
    const long n = take();
    if (n < 0) {  // the buffer is full: wait for the sweep to free a run of slots
      ++waiting_helpers_;
      changed_.wait(lock, [this] { return stopping_ || helpersMayResume(); });
      --waiting_helpers_;
      continue;
    }
    lock.unlock();
    evaluate(n, scratch);
    lock.lock();
    ready_[slot(n)] = 1;
    changed_.notify_all();
  }
}

const TrajectoryDerivatives::PointDerivatives& TrajectoryDerivatives::PointStream::next() {
  const long position = position_++;
  if (position < begin_ || position >= begin_ + count_) {  // outside the ring: an early point, taken here
    const Eigen::Index k = pointOf(position);
    if (!d_.takeEarly(k, early_point_, early_sensors_)) d_.pointAt(k, d_.scratch_, early_point_);
    return early_point_;
  }
  std::unique_lock lock(mutex_);
  if (handed_ > 0) {  // the sweep is done with the point handed last: its slot is free
    ready_[slot(handed_ - 1)] = 0;
    // Waking a helper costs a system call: once per run of free slots, not once per point.
    if (waiting_helpers_ > 0 && helpersMayResume()) changed_.notify_all();
  }
  const long n = handed_++;
  while (!ready_[slot(n)]) {
    // A run of points at once: evaluating and sweeping in turn, point by point, costs 10 % more on
    // one thread than doing each in runs (the instruction caches of the two change hands).
    const long first = take();
    if (first < 0) {
      changed_.wait(lock);
      continue;
    }
    long end = first + 1;
    while (end - first < kRun && take() >= 0) ++end;
    lock.unlock();
    for (long mine = first; mine < end; ++mine) {
      evaluate(mine, d_.scratch_);
      lock.lock();
      ready_[slot(mine)] = 1;
      changed_.notify_all();
      lock.unlock();
    }
    lock.lock();
  }
  lock.unlock();
  if (failures_[slot(n)]) std::rethrow_exception(failures_[slot(n)]);
  return slots_[slot(n)];
}

}  // namespace mbsopt
