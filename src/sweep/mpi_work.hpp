// Sweeps spread over MPI processes (`mpirun -n K snapjump sweep ...`).
//
// Every process runs sweeps' runs; the next run to start comes from one counter that all
// processes increment atomically (MPI one-sided Fetch_and_op on a window held by process 0), so
// a process that finishes early takes the next run and long runs do not hold up short ones.
// MPI is started only when the program was launched by an MPI launcher.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace snapjump::sweep {

// True when an MPI launcher (Open MPI's mpirun, a PMI/PMIx launcher) started this process.
bool launched_by_mpi();
// True when this build has MPI support.
bool mpi_available();

class MpiWork {
 public:
  MpiWork();   // MPI_Init and the shared counter; throws std::runtime_error without MPI support
  ~MpiWork();  // MPI_Finalize
  MpiWork(const MpiWork&) = delete;
  MpiWork& operator=(const MpiWork&) = delete;

  [[nodiscard]] int rank() const;
  [[nodiscard]] int size() const;
  void barrier() const;
  // Process 0's list to every process.
  void broadcast(std::vector<std::size_t>& list) const;
  // The next position in the shared list (0, 1, 2, ... over all processes).
  [[nodiscard]] std::size_t next() const;
  // Lets MPI make progress while this process waits for its runs.
  void progress() const;
  // Sum of an integer over all processes.
  [[nodiscard]] long sum(long v) const;
  // Whether every process says ok (false if any says not).
  [[nodiscard]] bool all(bool ok) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace snapjump::sweep
