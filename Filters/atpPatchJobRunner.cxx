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
    // Enough jobs in flight to keep every thread busy while the caller writes, few enough to
    // bound memory.
    const std::size_t window = std::size_t(Threads) * 4;
    std::vector<PatchJobResult> results(window);
    OrderedPipeline(
      count, Threads, window,
      [&](std::size_t i) {
        PatchJob job;
        load(i, job);
        results[i % window] = MakePatches(*Context, std::move(job));
      },
      [&](std::size_t i) {
        store(i, results[i % window]);
        results[i % window] = PatchJobResult();
      });
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
