#include "atpPrefetcher.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <vector>

namespace atp
{

Prefetcher::Prefetcher(std::shared_ptr<const ModelFile> model,
  std::shared_ptr<const CutIndex> index, double lookAheadSeconds)
  : Model(std::move(model))
  , Selector(*Model, std::move(index))
  , LookAhead(lookAheadSeconds)
{
  Thread = std::thread([this] { Run(); });
}

Prefetcher::~Prefetcher()
{
  {
    std::lock_guard<std::mutex> lock(Mutex);
    Stopping = true;
  }
  Changed.notify_all();
  Thread.join();
}

void Prefetcher::Observe(const ViewPoint& view, double errorScale, double seconds)
{
  {
    std::lock_guard<std::mutex> lock(Mutex);
    if (HasLatest)
    {
      Previous = Latest;
      PreviousSeconds = LatestSeconds;
      HasPrevious = true;
    }
    Latest = view;
    LatestSeconds = seconds;
    HasLatest = true;
    Scale = errorScale;
    HasNew = true;
  }
  Changed.notify_all();
}

void Prefetcher::Run()
{
  std::unique_lock<std::mutex> lock(Mutex);
  for (;;)
  {
    Changed.wait(lock, [this] { return Stopping || HasNew; });
    if (Stopping)
    {
      return;
    }
    // Linear prediction: where the eye will be LookAhead seconds after the latest view, if it
    // keeps its velocity. The frustum moves with it; rotation is not predicted.
    ViewPoint predicted = Latest;
    const double dt = LatestSeconds - PreviousSeconds;
    if (HasPrevious && dt > 1e-6)
    {
      const double factor = LookAhead / dt;
      for (int a = 0; a < 3; ++a)
      {
        const double shift = (Latest.Eye[a] - Previous.Eye[a]) * factor;
        predicted.Eye[a] += shift;
        for (int p = 0; p < predicted.PlaneCount; ++p)
        {
          predicted.Planes[p][3] -= predicted.Planes[p][a] * shift;
        }
      }
    }
    std::copy(predicted.Eye, predicted.Eye + 3, PredictedEye);
    const double scale = Scale;
    HasNew = false;
    if (PassCount > 0 && SameView(predicted, LastPredicted) && scale == LastScale)
    {
      Changed.notify_all(); // a still camera: the pages are advised already
      continue;
    }
    LastPredicted = predicted;
    LastScale = scale;
    Busy = true;
    lock.unlock();

    Selector.Select(predicted, scale, ResidentFunction(), Cut);
    Advise(Cut.Drawn);

    lock.lock();
    Busy = false;
    ++PassCount;
    Changed.notify_all();
  }
}

void Prefetcher::Advise(const std::vector<std::uint32_t>& nodes)
{
  const std::uintptr_t page = std::uintptr_t(::sysconf(_SC_PAGESIZE));
  std::vector<unsigned char> resident;
  std::uint64_t advised = 0;
  for (const std::uint32_t n : nodes)
  {
    const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(Model->PatchData(n)) & ~(page - 1);
    const std::uintptr_t end =
      reinterpret_cast<std::uintptr_t>(Model->PatchData(n)) + Model->Node(n).PatchBytes;
    const std::size_t pages = (end - begin + page - 1) / page;
    resident.resize(pages);
    void* address = reinterpret_cast<void*>(begin);
    if (::mincore(address, end - begin, resident.data()) != 0)
    {
      continue;
    }
    const std::size_t missing =
      std::size_t(std::count_if(resident.begin(), resident.end(), [](unsigned char r) { return (r & 1) == 0; }));
    if (missing > 0 && ::madvise(address, end - begin, MADV_WILLNEED) == 0)
    {
      advised += missing;
    }
  }
  std::lock_guard<std::mutex> lock(Mutex);
  Advised += advised;
}

void Prefetcher::LastPredictedEye(double eye[3]) const
{
  std::lock_guard<std::mutex> lock(Mutex);
  std::copy(PredictedEye, PredictedEye + 3, eye);
}

std::uint64_t Prefetcher::Passes() const
{
  std::lock_guard<std::mutex> lock(Mutex);
  return PassCount;
}

std::uint64_t Prefetcher::AdvisedPages() const
{
  std::lock_guard<std::mutex> lock(Mutex);
  return Advised;
}

void Prefetcher::Wait() const
{
  std::unique_lock<std::mutex> lock(Mutex);
  Changed.wait(lock, [this] { return Stopping || (!HasNew && !Busy); });
}

} // namespace atp
