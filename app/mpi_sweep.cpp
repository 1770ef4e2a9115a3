#include "app/mpi_sweep.hpp"

#include <mpi.h>

#include <chrono>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <thread>

namespace mbsopt {

namespace {

enum Tag : int {
  kReady = 1,   ///< worker → 0: give me a task (no result yet)
  kResult = 2,  ///< worker → 0: the task's index (8 bytes) then its result's text; give me another
  kTask = 3,    ///< 0 → worker: the index of a task
  kStop = 4     ///< 0 → worker: no task is left
};

/// Rank 0's wait between polls: long beside MPI's latency, short beside a run.
constexpr auto kPollInterval = std::chrono::milliseconds(2);

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}

}  // namespace

bool launchedByMpi() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(variable)) return true;
  return false;
}

MpiSweep::MpiSweep() {
  check(MPI_Init(nullptr, nullptr), "MPI_Init");
  // Debian's sequential MUMPS (under Ipopt) defines stubs named MPI_Init and MPI_Comm_rank; bound to
  // them, MPI_Init initialises nothing (app/CMakeLists.txt links Open MPI first).
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized)
    throw std::runtime_error("MPI: MPI_Init is bound to a stub, not to Open MPI (link Open MPI before Ipopt's MUMPS)");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSweep::~MpiSweep() { MPI_Finalize(); }

std::string MpiSweep::broadcast(const std::string& text) const {
  unsigned long long length = text.size();
  check(MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD), "MPI_Bcast");
  std::string out = rank_ == 0 ? text : std::string(length, '\0');
  check(MPI_Bcast(out.data(), static_cast<int>(length), MPI_CHAR, 0, MPI_COMM_WORLD), "MPI_Bcast");
  return out;
}

void MpiSweep::distribute(const std::vector<std::size_t>& tasks, const std::function<std::string(std::size_t)>& work,
                          const std::function<void(std::size_t, const std::string&)>& store) const {
  if (size_ < 2) throw std::logic_error("MpiSweep::distribute needs at least two ranks");
  if (rank_ != 0) {
    std::string message;  // empty: ready
    for (int tag = kReady;;) {
      check(MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, tag, MPI_COMM_WORLD), "MPI_Send");
      unsigned long long task = 0;
      MPI_Status status;
      check(MPI_Recv(&task, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_ANY_TAG, MPI_COMM_WORLD, &status), "MPI_Recv");
      if (status.MPI_TAG == kStop) return;
      try {
        const std::string result = work(static_cast<std::size_t>(task));
        message.assign(reinterpret_cast<const char*>(&task), sizeof task);
        message += result;
      } catch (const std::exception& e) {
        std::cerr << "mbsopt: rank " << rank_ << ", task " << task << ": " << e.what() << '\n';
        MPI_Abort(MPI_COMM_WORLD, 1);
      }
      tag = kResult;
    }
  }
  std::size_t next = 0;
  int working = size_ - 1;
  while (working > 0) {
    int arrived = 0;
    MPI_Status status;
    check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status), "MPI_Iprobe");
    if (!arrived) {
      std::this_thread::sleep_for(kPollInterval);
      continue;
    }
    int length = 0;
    MPI_Get_count(&status, MPI_CHAR, &length);
    std::string message(static_cast<std::size_t>(length), '\0');
    check(MPI_Recv(message.data(), length, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
          "MPI_Recv");
    if (status.MPI_TAG == kResult) {
      unsigned long long task = 0;
      message.copy(reinterpret_cast<char*>(&task), sizeof task);
      store(static_cast<std::size_t>(task), message.substr(sizeof task));
    }
    if (next < tasks.size()) {
      const unsigned long long task = tasks[next++];
      check(MPI_Send(&task, 1, MPI_UNSIGNED_LONG_LONG, status.MPI_SOURCE, kTask, MPI_COMM_WORLD), "MPI_Send");
    } else {
      const unsigned long long none = 0;
      check(MPI_Send(&none, 1, MPI_UNSIGNED_LONG_LONG, status.MPI_SOURCE, kStop, MPI_COMM_WORLD), "MPI_Send");
      --working;
    }
  }
}

}  // namespace mbsopt
