#include "atpBucketStore.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace atp
{

BucketStore::BucketStore(const std::string& scratchDirectory, std::size_t memoryBudgetBytes)
  : Disk(scratchDirectory)
{
  // At least a handful of frames so that a split (one bucket read, two appended) always fits.
  const std::size_t frames = std::max<std::size_t>(8, memoryBudgetBytes / PageBytes);
  Pool.reset(new SoupTriangle[frames * PageRecords]);
  FramePage.assign(frames, -1);
  FrameDirty.assign(frames, 0);
  FrameReferenced.assign(frames, 0);
  for (std::size_t f = frames; f-- > 0;)
  {
    FreeFrames.push_back(f);
  }
}

BucketStore::PageIndex BucketStore::NewPage()
{
  if (!FreePages.empty())
  {
    const PageIndex page = FreePages.back();
    FreePages.pop_back();
    return page;
  }
  PageFrame.push_back(NotResident);
  PageOnDisk.push_back(0);
  return PageIndex(PageFrame.size() - 1);
}

std::size_t BucketStore::FreeFrame()
{
  if (!FreeFrames.empty())
  {
    const std::size_t frame = FreeFrames.back();
    FreeFrames.pop_back();
    return frame;
  }
  // Clock (second chance) eviction: cheap and close to LRU.
  for (;;)
  {
    const std::size_t frame = ClockHand;
    ClockHand = (ClockHand + 1) % FramePage.size();
    if (FrameReferenced[frame])
    {
      FrameReferenced[frame] = 0;
      continue;
    }
    const PageIndex page = PageIndex(FramePage[frame]);
    if (FrameDirty[frame])
    {
      const std::uint64_t offset = std::uint64_t(page) * PageBytes;
      Disk.WriteAt(offset, FrameData(frame), PageBytes);
      Counters.BytesWritten += PageBytes;
      Counters.PeakScratchBytes = std::max(Counters.PeakScratchBytes, offset + PageBytes);
      PageOnDisk[page] = 1;
    }
    PageFrame[page] = NotResident;
    FramePage[frame] = -1;
    return frame;
  }
}

std::size_t BucketStore::Resident(PageIndex page, bool load)
{
  if (PageFrame[page] != NotResident)
  {
    return std::size_t(PageFrame[page]);
  }
  const std::size_t frame = FreeFrame();
  if (load && PageOnDisk[page])
  {
    Disk.ReadAt(std::uint64_t(page) * PageBytes, FrameData(frame), PageBytes);
    Counters.BytesRead += PageBytes;
  }
  FramePage[frame] = page;
  FrameDirty[frame] = 0;
  PageFrame[page] = std::int32_t(frame);
  return frame;
}

void BucketStore::Append(BucketIndex bucketIndex, const SoupTriangle& triangle)
{
  if (bucketIndex >= Buckets.size())
  {
    Buckets.resize(std::size_t(bucketIndex) + 1);
  }
  Bucket& bucket = Buckets[bucketIndex];
  const std::size_t slot = std::size_t(bucket.Count % PageRecords);
  std::size_t frame;
  if (slot == 0)
  {
    const PageIndex page = NewPage();
    bucket.Pages.push_back(page);
    frame = Resident(page, false);
  }
  else
  {
    frame = Resident(bucket.Pages.back(), true);
  }
  FrameData(frame)[slot] = triangle;
  FrameDirty[frame] = 1;
  FrameReferenced[frame] = 1;
  ++bucket.Count;
}

void BucketStore::Read(BucketIndex bucketIndex, std::vector<SoupTriangle>& out) const
{
  if (bucketIndex >= Buckets.size())
  {
    return;
  }
  const Bucket& bucket = Buckets[bucketIndex];
  std::size_t first = out.size();
  out.resize(first + bucket.Count);
  std::uint64_t left = bucket.Count;
  for (const PageIndex page : bucket.Pages)
  {
    const std::size_t n = std::size_t(std::min<std::uint64_t>(left, PageRecords));
    if (PageFrame[page] != NotResident)
    {
      std::memcpy(&out[first], &Pool[std::size_t(PageFrame[page]) * PageRecords],
        n * sizeof(SoupTriangle));
    }
    else
    {
      Disk.ReadAt(std::uint64_t(page) * PageBytes, &out[first], n * sizeof(SoupTriangle));
      Counters.BytesRead += n * sizeof(SoupTriangle);
    }
    first += n;
    left -= n;
  }
}

void BucketStore::Clear(BucketIndex bucketIndex)
{
  if (bucketIndex >= Buckets.size())
  {
    return;
  }
  Bucket& bucket = Buckets[bucketIndex];
  for (const PageIndex page : bucket.Pages)
  {
    if (PageFrame[page] != NotResident)
    {
      const std::size_t frame = std::size_t(PageFrame[page]);
      FramePage[frame] = -1;
      FrameDirty[frame] = 0;
      FrameReferenced[frame] = 0;
      FreeFrames.push_back(frame);
      PageFrame[page] = NotResident;
    }
    PageOnDisk[page] = 0;
    FreePages.push_back(page);
  }
  bucket = Bucket();
}

} // namespace atp
