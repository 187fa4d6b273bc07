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
#include <deque>
#include <list>
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

/// The coordinator's runner (rank 0 of `comm`). Each worker holds the job it works on and the
/// next one, so it never waits for the coordinator's answer (a network round trip on a
/// cluster). Stops every worker when destroyed, after waiting for the jobs they hold, so a
/// failed build still ends every process.
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
    std::uint64_t JobBytes = 0;        ///< shipped to the worker (jobs with their triangles)
    std::uint64_t ResultBytes = 0;     ///< shipped back
    std::uint64_t PeakMemoryBytes = 0; ///< the worker's peak resident memory
  };
  /// Waits for outstanding jobs, stops every worker and returns their figures (rank 1 first).
  std::vector<WorkerStats> Finish();

  int Workers() const { return int(Queued.size()); }
  /// CPU seconds the coordinator spent from Begin() to Finish(): loading, shipping and storing
  /// jobs, what bounds how many workers one coordinator can feed.
  double CoordinatorCpuSeconds() const { return CoordinatorCpu; }

private:
  /// Loads job `index` and sends it to `worker` without waiting for the transfer.
  void Dispatch(std::size_t index, std::size_t worker, const LoadJob& load);
  /// Receives the next message from any worker: a result goes to the reorder buffer, a
  /// failure throws.
  void Collect(std::vector<std::uint8_t>& buffer);
  /// Frees the buffers of sends that are done; with `all`, waits for every send first.
  void ReclaimSends(bool all);

  struct PendingSend
  {
    MPI_Request Request = MPI_REQUEST_NULL;
    std::vector<std::uint8_t> Bytes;
  };

  MPI_Comm Comm;
  /// Per worker: the indices of the jobs it holds, oldest first (it answers in order).
  std::vector<std::deque<std::size_t>> Queued;
  std::list<PendingSend> Sends;
  std::vector<WorkerStats> Stats;
  /// The reorder buffer: results that arrived before an earlier job's, by job index.
  std::map<std::size_t, PatchJobResult> Arrived;
  bool Finished = false;
  double CoordinatorCpu = 0; ///< from Begin() (negative until Finish())
};

/// A worker's whole life (ranks 1..N-1): build contexts and jobs from rank 0 until told to
/// stop. A job that fails is reported to rank 0, which ends the build. Returns the exit code.
///
/// Fault injection for tests only: ATP_MPI_TEST_FAULT=kill:K makes a worker kill itself
/// (SIGKILL) when it receives its K-th job, ATP_MPI_TEST_FAULT=throw:K makes that job fail.
int RunMpiWorker(MPI_Comm comm);

} // namespace atp

#endif
