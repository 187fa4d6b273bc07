// Where construction's jobs run: on threads of this process (ThreadJobRunner) or on other
// processes, e.g. MPI workers on other machines (Apps/atpMpiBuild.h). Construction hands a
// runner one batch at a time (the leaves or the inner diamonds of one level); the runner stores
// results through the caller, always in job order, so the caller's bookkeeping and the model
// never depend on where or when a job ran. Jobs may be loaded on any thread: on many cores one
// thread could not read the inputs of all the others.
#ifndef atpPatchJobRunner_h
#define atpPatchJobRunner_h

#include "atpPatchJob.h"
#include "vtkATPFiltersModule.h"

#include <cstddef>
#include <functional>
#include <memory>

namespace atp
{

class VTKATPFILTERS_EXPORT PatchJobRunner
{
public:
  /// Fills job i. On any thread, several at once, in any order: it may only read what no
  /// StoreResult of the same Run changes.
  using LoadJob = std::function<void(std::size_t i, PatchJob& job)>;
  /// Takes the result of job i (on the calling thread, i ascending).
  using StoreResult = std::function<void(std::size_t i, PatchJobResult& result)>;

  virtual ~PatchJobRunner() = default;

  /// Called once per build, before its first batch.
  virtual void Begin(const PatchJobContext& context) = 0;
  /// Runs jobs [0, count): loads each, makes its patches, stores each. Jobs are loaded only a
  /// bounded number ahead of the next store, so memory stays bounded. Throws
  /// std::runtime_error when a job fails (naming the job), or what load or store throw.
  virtual void Run(std::size_t count, const LoadJob& load, const StoreResult& store) = 0;
};

/// Runs jobs on up to `threads` threads of this process (0: every core), a few per thread at a
/// time, each loaded by the thread that makes it.
VTKATPFILTERS_EXPORT std::unique_ptr<PatchJobRunner> MakeThreadJobRunner(int threads);

} // namespace atp

#endif
