// Two stages of a stream on two threads: a new thread produces batches while the caller's
// thread consumes them, in order, through a few recycled batches. Reading a mesh overlaps what
// is done with it (the first pass over the faces, partitioning the triangles).
#ifndef atpProduceConsume_h
#define atpProduceConsume_h

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>

namespace atp
{

/// `produce(Batch&)` fills a batch on a new thread and returns false, leaving it unused, at
/// the end of the stream; `consume(Batch&)` runs on the calling thread for each filled batch, in
/// the order they were produced. `batches` batches (default-constructed once, then recycled)
/// bound the memory. An exception from either side stops both and reaches the caller once the
/// producing thread has been joined; the consumer's wins when both throw.
template<typename Batch, typename Produce, typename Consume>
void ProduceConsume(std::size_t batches, const Produce& produce, const Consume& consume)
{
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::unique_ptr<Batch>> empty, full;
  bool cancelled = false;
  for (std::size_t i = 0; i < batches; ++i)
  {
    empty.push_back(std::make_unique<Batch>());
  }
  // Null: cancelled (taking), or the end of the stream (given to the consumer).
  const auto take = [&](std::deque<std::unique_ptr<Batch>>& queue) {
    std::unique_lock<std::mutex> lock(mutex);
    changed.wait(lock, [&] { return cancelled || !queue.empty(); });
    std::unique_ptr<Batch> batch;
    if (!cancelled)
    {
      batch = std::move(queue.front());
      queue.pop_front();
    }
    return batch;
  };
  const auto give = [&](std::deque<std::unique_ptr<Batch>>& queue, std::unique_ptr<Batch> batch) {
    std::lock_guard<std::mutex> lock(mutex);
    queue.push_back(std::move(batch));
    changed.notify_all();
  };

  std::exception_ptr producerError;
  std::thread producer([&] {
    try
    {
      while (std::unique_ptr<Batch> batch = take(empty))
      {
        if (!produce(*batch))
        {
          break;
        }
        give(full, std::move(batch));
      }
    }
    catch (...)
    {
      producerError = std::current_exception();
    }
    give(full, nullptr);
  });
  try
  {
    while (std::unique_ptr<Batch> batch = take(full))
    {
      consume(*batch);
      give(empty, std::move(batch));
    }
  }
  catch (...)
  {
    {
      std::lock_guard<std::mutex> lock(mutex);
      cancelled = true;
      changed.notify_all();
    }
    producer.join();
    throw;
  }
  producer.join();
  if (producerError)
  {
    std::rethrow_exception(producerError);
  }
}

} // namespace atp

#endif
