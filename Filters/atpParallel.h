// Runs independent jobs on worker threads. Results go to slots chosen by index, so output never
// depends on which thread ran what (builds are byte-identical whatever the thread count).
#ifndef atpParallel_h
#define atpParallel_h

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace atp
{

/// Calls job(i) for i in [0, count) on up to `threads` threads (the caller's included). If jobs
/// throw, the exception of the lowest index is rethrown once all threads have stopped.
template<typename Job>
void ParallelFor(std::size_t count, int threads, const Job& job)
{
  std::vector<std::exception_ptr> errors(count);
  std::atomic<std::size_t> next{ 0 };
  std::atomic<bool> failed{ false };
  const auto work = [&]() {
    for (std::size_t i = next++; i < count && !failed; i = next++)
    {
      try
      {
        job(i);
      }
      catch (...)
      {
        errors[i] = std::current_exception();
        failed = true;
      }
    }
  };
  const std::size_t helpers = std::min<std::size_t>(count, std::size_t(std::max(1, threads))) - (count > 0);
  std::vector<std::thread> pool;
  for (std::size_t t = 0; t < helpers; ++t)
  {
    pool.emplace_back(work);
  }
  work();
  for (std::thread& t : pool)
  {
    t.join();
  }
  for (const std::exception_ptr& e : errors)
  {
    if (e)
    {
      std::rethrow_exception(e);
    }
  }
}

/// The default worker count: every core.
inline int HardwareThreads()
{
  return int(std::max(1u, std::thread::hardware_concurrency()));
}

} // namespace atp

#endif
