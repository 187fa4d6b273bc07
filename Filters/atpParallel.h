// Runs independent jobs on worker threads between an ordered reader and an ordered writer.
// Jobs are read and their results written in index order by the calling thread, so output never
// depends on which thread ran what (builds are byte-identical whatever the thread count).
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

/// For i in [0, count): load(i), then work(i), then store(i). The caller runs every load and
/// store, each in index order; work runs on up to `threads` threads (the caller's included,
/// when it has nothing to load or store). At most `window` jobs are between their load and
/// their store, which bounds memory; loads and stores overlap the work, with no barrier
/// between batches. The first exception in index order stops everything and is rethrown once
/// every thread has stopped (a load's or a store's at once, a work's when its store is due).
template<typename Load, typename Work, typename Store>
void OrderedPipeline(std::size_t count, int threads, std::size_t window, const Load& load,
  const Work& work, const Store& store)
{
  window = std::max<std::size_t>(1, window);
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::size_t> loaded;           // waiting for a thread
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
      changed.wait(lock, [&]() { return stopping || !loaded.empty(); });
      if (stopping)
      {
        return;
      }
      const std::size_t i = loaded.front();
      loaded.pop_front();
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

  std::size_t next = 0; // the next job to load
  for (std::size_t due = 0; due < count;)
  {
    while (next < count && next - due < window)
    {
      load(next);
      {
        std::lock_guard<std::mutex> lock(mutex);
        loaded.push_back(next++);
      }
      changed.notify_one();
    }
    std::unique_lock<std::mutex> lock(mutex);
    const std::size_t slot = due % window;
    if (!finished[slot] && !loaded.empty())
    {
      // Nothing to store yet: lend a hand, the oldest job first.
      const std::size_t i = loaded.front();
      loaded.pop_front();
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
