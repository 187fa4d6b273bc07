#include "atpPatchJobRunner.h"

#include "atpParallel.h"

#include <algorithm>
#include <optional>

namespace atp
{
namespace
{

class ThreadJobRunner : public PatchJobRunner
{
public:
  explicit ThreadJobRunner(int threads)
    : Threads(threads > 0 ? threads : HardwareThreads())
  {
  }

  void Begin(const PatchJobContext& context) override { Context.emplace(context); }

  void Run(std::size_t count, const LoadJob& load, const StoreResult& store) override
  {
    // A chunk big enough to keep every thread busy, small enough to bound memory.
    const std::size_t chunk = std::size_t(Threads) * 4;
    std::vector<PatchJob> jobs;
    std::vector<PatchJobResult> results;
    for (std::size_t first = 0; first < count; first += chunk)
    {
      const std::size_t size = std::min(chunk, count - first);
      jobs.assign(size, PatchJob());
      results.assign(size, PatchJobResult());
      for (std::size_t i = 0; i < size; ++i)
      {
        load(first + i, jobs[i]);
      }
      ParallelFor(size, Threads,
        [&](std::size_t i) { results[i] = MakePatches(*Context, std::move(jobs[i])); });
      for (std::size_t i = 0; i < size; ++i)
      {
        store(first + i, results[i]);
      }
    }
  }

private:
  const int Threads;
  std::optional<PatchJobContext> Context;
};

} // namespace

std::unique_ptr<PatchJobRunner> MakeThreadJobRunner(int threads)
{
  return std::make_unique<ThreadJobRunner>(threads);
}

} // namespace atp
