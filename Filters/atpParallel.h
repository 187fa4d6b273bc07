// Runs independent jobs on worker threads ahead of an ordered writer. Results are written in
// index order by the calling thread, so output never depends on which thread ran what (builds
// are byte-identical whatever the thread count).
#ifndef atpParallel_h
#define atpParallel_h

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace atp
{

/// For i in [0, count): work(i), then store(i). work runs on up to `threads` threads (the
/// caller's included, when it has nothing to store), which take the jobs in index order; the
/// caller runs every store, in index order. At most `window` jobs are between their release to
/// the threads and their store, which bounds memory; stores overlap the work, with no barrier
/// between batches. The first exception in index order stops everything and is rethrown once
/// every thread has stopped (a store's at once, a work's when its store is due).
template<typename Work, typename Store>
void OrderedPipeline(
  std::size_t count, int threads, std::size_t window, const Work& work, const Store& store)
{
  window = std::max<std::size_t>(1, window);
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::size_t> waiting;          // released, not yet taken by a thread
  std::vector<char> finished(window, 0);     // per slot (index % window): work done
  std::vector<std::exception_ptr> errors(window);
  bool stopping = false;

  const auto run = [&](std::size_t i, std::unique_lock<std::mutex>& lock) {
    lock.unlock();
    std::exception_ptr error;
    try
    {
      work(i);
    }
    catch (...)
    {
      error = std::current_exception();
    }
    lock.lock();
    errors[i % window] = error;
    finished[i % window] = 1;
    changed.notify_all();
  };
  const auto helper = [&]() {
    std::unique_lock<std::mutex> lock(mutex);
    for (;;)
    {
      changed.wait(lock, [&]() { return stopping || !waiting.empty(); });
      if (stopping)
      {
        return;
      }
      const std::size_t i = waiting.front();
      waiting.pop_front();
      run(i, lock);
    }
  };
  const std::size_t helpers =
    std::min<std::size_t>(count, std::size_t(std::max(1, threads))) - (count > 0);
  std::vector<std::thread> pool;
  // Stops and joins the helpers however this function is left.
  struct Joiner
  {
    std::mutex& Mutex;
    std::condition_variable& Changed;
    bool& Stopping;
    std::vector<std::thread>& Pool;
    ~Joiner()
    {
      {
        std::lock_guard<std::mutex> lock(Mutex);
        Stopping = true;
      }
      Changed.notify_all();
      for (std::thread& t : Pool)
      {
        t.join();
      }
    }
  } joiner{ mutex, changed, stopping, pool };
  for (std::size_t t = 0; t < helpers; ++t)
  {
    pool.emplace_back(helper);
  }

  std::size_t next = 0; // the next job to start
  for (std::size_t due = 0; due < count;)
  {
    std::unique_lock<std::mutex> lock(mutex);
    if (next < count && next - due < window)
    {
      while (next < count && next - due < window)
      {
        waiting.push_back(next++);
      }
      changed.notify_all();
    }
    const std::size_t slot = due % window;
    if (!finished[slot] && !waiting.empty())
    {
      // Nothing to store yet: lend a hand, the oldest job first.
      const std::size_t i = waiting.front();
      waiting.pop_front();
      run(i, lock);
      continue;
    }
    changed.wait(lock, [&]() { return finished[slot] != 0; });
    finished[slot] = 0;
    const std::exception_ptr error = errors[slot];
    errors[slot] = nullptr;
    lock.unlock();
    if (error)
    {
      std::rethrow_exception(error);
    }
    store(due++);
  }
}

/// The default worker count: every core.
inline int HardwareThreads()
{
  return int(std::max(1u, std::thread::hardware_concurrency()));
}

} // namespace atp

#endif
