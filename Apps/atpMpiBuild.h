// atp build --mpi: construction's jobs on MPI worker processes (paper 5.2, "Network parallel
// construction"). Rank 0 partitions the input and runs construction as usual, but every leaf
// and diamond job travels, with its triangles, to a free worker (ranks 1..N-1), so workers need
// no shared file system and hold one job at a time. Rank 0 takes results in job order through
// a small reorder buffer and writes the one model file, byte-identical to a single-process build.
#ifndef atpMpiBuild_h
#define atpMpiBuild_h

#include "atpPatchJobRunner.h"

#include <mpi.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace atp
{

/// MPI_Init on construction, MPI_Finalize on destruction.
class MpiSession
{
public:
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int Rank() const;
  int Size() const;
};

/// Whether the arguments of `atp build` ask for an MPI build (before MPI is started).
bool WantsMpi(int argc, char** argv);

/// The coordinator's runner (rank 0 of `comm`). Stops every worker when destroyed, after
/// waiting for the jobs they hold, so a failed build still ends every process.
class MpiJobRunner : public PatchJobRunner
{
public:
  /// Throws std::runtime_error when `comm` has no worker.
  explicit MpiJobRunner(MPI_Comm comm);
  ~MpiJobRunner() override;

  void Begin(const PatchJobContext& context) override;
  void Run(std::size_t count, const LoadJob& load, const StoreResult& store) override;

  struct WorkerStats
  {
    std::uint64_t Jobs = 0;
    std::uint64_t PeakMemoryBytes = 0; ///< the worker's peak resident memory
  };
  /// Waits for outstanding jobs, stops every worker and returns their figures (rank 1 first).
  std::vector<WorkerStats> Finish();

  int Workers() const { return int(Assigned.size()); }

private:
  /// Receives the next message from any busy worker: a result goes to the reorder buffer, a
  /// failure throws.
  void Collect(std::vector<std::uint8_t>& buffer);

  MPI_Comm Comm;
  /// Per worker: the index of the job it holds, or -1.
  std::vector<std::int64_t> Assigned;
  std::vector<WorkerStats> Stats;
  /// The reorder buffer: results that arrived before an earlier job's, by job index.
  std::map<std::size_t, PatchJobResult> Arrived;
  bool Finished = false;
};

/// A worker's whole life (ranks 1..N-1): build contexts and jobs from rank 0 until told to
/// stop. A job that fails is reported to rank 0, which ends the build. Returns the exit code.
///
/// Fault injection for tests only: ATP_MPI_TEST_FAULT=kill:K makes a worker kill itself
/// (SIGKILL) when it receives its K-th job, ATP_MPI_TEST_FAULT=throw:K makes that job fail.
int RunMpiWorker(MPI_Comm comm);

} // namespace atp

#endif
