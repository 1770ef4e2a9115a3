// A sweep's runs spread over the ranks of an MPI job (Open MPI; `mpirun -n N mbsopt benchmark …`,
// or `srun` under Slurm): rank 0 hands out one run at a time to whichever rank asks next (runs take
// from seconds to minutes, so a static split would leave ranks idle) and receives each finished
// run's record, which it writes; the other ranks only run. Rank 0 polls for messages with short
// sleeps in between, so that it does not take a core from the ranks that work.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace mbsopt {

/// Whether a process manager (mpirun, srun) started this process as a rank of an MPI job: its
/// environment says so (Open MPI's OMPI_COMM_WORLD_SIZE, PMIx's PMIX_RANK, PMI's PMI_RANK).
bool launchedByMpi();

/// MPI from MPI_Init to MPI_Finalize (one per process).
class MpiSweep {
 public:
  MpiSweep();
  ~MpiSweep();
  MpiSweep(const MpiSweep&) = delete;
  MpiSweep& operator=(const MpiSweep&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }

  /// Rank 0's text, on every rank.
  std::string broadcast(const std::string& text) const;

  /// On rank 0: hands `tasks` out, one at a time, to ranks 1 … size − 1 as they ask, calls
  /// store(task, result) for each result as it arrives, and tells every rank to stop once all are
  /// done. On the others: work(task) for each task handed to it, its result sent back. Needs
  /// size ≥ 2. A worker's exception ends the job (MPI_Abort) after saying which task it was.
  void distribute(const std::vector<std::size_t>& tasks, const std::function<std::string(std::size_t)>& work,
                  const std::function<void(std::size_t, const std::string&)>& store) const;

 private:
  int rank_ = 0, size_ = 1;
};

}  // namespace mbsopt
