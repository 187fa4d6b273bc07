#include "atpPatchFetcher.h"

#include <chrono>

namespace atp
{

PatchFetcher::PatchFetcher(std::shared_ptr<const ModelFile> model, int threads)
  : Model(std::move(model))
{
  for (int t = 0; t < std::max(threads, 1); ++t)
  {
    Threads.emplace_back([this] { Work(); });
  }
}

PatchFetcher::~PatchFetcher()
{
  {
    std::lock_guard<std::mutex> lock(Mutex);
    Stopping = true;
  }
  Wake.notify_all();
  for (std::thread& t : Threads)
  {
    t.join();
  }
}

void PatchFetcher::Request(const std::vector<std::uint32_t>& nodes)
{
  {
    std::lock_guard<std::mutex> lock(Mutex);
    Queue.clear();
    for (const std::uint32_t node : nodes)
    {
      if (!Busy.count(node))
      {
        Queue.push_back(node);
      }
    }
  }
  Wake.notify_all();
}

void PatchFetcher::TakeFinished(std::size_t maxBytes, std::vector<RenderPatch>& out)
{
  std::lock_guard<std::mutex> lock(Mutex);
  std::size_t bytes = 0;
  while (!Finished.empty() && (bytes == 0 || bytes + Finished.front().Bytes() <= maxBytes))
  {
    bytes += Finished.front().Bytes();
    Busy.erase(Finished.front().Node);
    out.push_back(std::move(Finished.front()));
    Finished.pop_front();
  }
}

RenderPatch PatchFetcher::DecodeNow(std::uint32_t node) const
{
  try
  {
    PatchMesh mesh;
    Model->DecodePatch(node, mesh);
    Model->ReleasePatchPages(node);
    return MakeRenderPatch(mesh, node);
  }
  catch (const std::exception& e)
  {
    RenderPatch failed;
    failed.Node = node;
    failed.Error = e.what();
    return failed;
  }
}

void PatchFetcher::Work()
{
  std::unique_lock<std::mutex> lock(Mutex);
  for (;;)
  {
    Wake.wait(lock, [this] { return Stopping || !Queue.empty(); });
    if (Stopping)
    {
      return;
    }
    const std::uint32_t node = Queue.front();
    Queue.pop_front();
    Busy.insert(node);
    lock.unlock();
    const auto start = std::chrono::steady_clock::now();
    RenderPatch patch = DecodeNow(node);
    const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
    lock.lock();
    Finished.push_back(std::move(patch));
    ++Decoded;
    Seconds += took.count();
  }
}

std::uint64_t PatchFetcher::DecodedPatches() const
{
  std::lock_guard<std::mutex> lock(Mutex);
  return Decoded;
}

double PatchFetcher::DecodeSeconds() const
{
  std::lock_guard<std::mutex> lock(Mutex);
  return Seconds;
}

} // namespace atp
