#include "atpStreamPartition.h"

#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace atp
{
namespace
{
constexpr std::size_t BatchTriangles = 1 << 16;
constexpr int BatchCount = 3;

struct Batch
{
  std::vector<SoupTriangle> Triangles = std::vector<SoupTriangle>(BatchTriangles);
  std::size_t Count = 0;
};

/// Hands batches between the reader (fills empty ones) and the partitioner (drains full ones).
class BatchExchange
{
public:
  BatchExchange()
  {
    for (int i = 0; i < BatchCount; ++i)
    {
      Empty.push_back(std::make_unique<Batch>());
    }
  }

  std::unique_ptr<Batch> TakeEmpty() { return Take(Empty); }
  std::unique_ptr<Batch> TakeFull() { return Take(Full); }
  void GiveEmpty(std::unique_ptr<Batch> b) { Give(Empty, std::move(b)); }
  /// A null batch tells the partitioner the stream has ended.
  void GiveFull(std::unique_ptr<Batch> b) { Give(Full, std::move(b)); }

  void Cancel()
  {
    std::lock_guard<std::mutex> lock(Mutex);
    Cancelled = true;
    Changed.notify_all();
  }

private:
  std::unique_ptr<Batch> Take(std::deque<std::unique_ptr<Batch>>& queue)
  {
    std::unique_lock<std::mutex> lock(Mutex);
    Changed.wait(lock, [&] { return Cancelled || !queue.empty(); });
    if (Cancelled)
    {
      return nullptr;
    }
    auto b = std::move(queue.front());
    queue.pop_front();
    return b;
  }
  void Give(std::deque<std::unique_ptr<Batch>>& queue, std::unique_ptr<Batch> b)
  {
    std::lock_guard<std::mutex> lock(Mutex);
    queue.push_back(std::move(b));
    Changed.notify_all();
  }

  std::mutex Mutex;
  std::condition_variable Changed;
  std::deque<std::unique_ptr<Batch>> Empty, Full;
  bool Cancelled = false;
};
} // namespace

std::unique_ptr<Partitioner> PartitionStream(TriangleSource& source,
  const PartitionOptions& options, const std::function<void(std::uint64_t)>& progress)
{
  auto partitioner = std::make_unique<Partitioner>(source.Bounds(), options);
  BatchExchange exchange;
  std::exception_ptr readerError;
  std::thread reader([&] {
    try
    {
      for (;;)
      {
        std::unique_ptr<Batch> batch = exchange.TakeEmpty();
        if (!batch)
        {
          return; // cancelled by the partitioner
        }
        batch->Count = source.Read(batch->Triangles.data(), batch->Triangles.size());
        if (batch->Count == 0)
        {
          exchange.GiveFull(nullptr);
          return;
        }
        exchange.GiveFull(std::move(batch));
      }
    }
    catch (...)
    {
      readerError = std::current_exception();
      exchange.GiveFull(nullptr);
    }
  });

  std::uint64_t done = 0;
  try
  {
    while (std::unique_ptr<Batch> batch = exchange.TakeFull())
    {
      partitioner->Insert(batch->Triangles.data(), batch->Count);
      done += batch->Count;
      exchange.GiveEmpty(std::move(batch));
      progress(done);
    }
  }
  catch (...)
  {
    exchange.Cancel();
    reader.join();
    throw;
  }
  reader.join();
  if (readerError)
  {
    std::rethrow_exception(readerError);
  }
  return partitioner;
}

} // namespace atp
