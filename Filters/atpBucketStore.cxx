#include "atpBucketStore.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace atp
{

BucketStore::BucketStore(
  const std::string& scratchDirectory, std::size_t memoryBudgetBytes, std::size_t recordBytes)
  : Disk(scratchDirectory)
  , RecordBytes(recordBytes)
  , PageBytes(PageRecords * recordBytes)
{
  if (recordBytes != sizeof(SoupTriangle) && recordBytes != SoupBytesWithoutColors)
  {
    throw std::invalid_argument("BucketStore: unsupported record size");
  }
  // At least a handful of frames so that a split (one bucket read, two appended) always fits.
  const std::size_t frames = std::max<std::size_t>(8, memoryBudgetBytes / PageBytes);
  Pool.reset(new unsigned char[frames * PageBytes]);
  States.assign(frames, FrameState::Free);
  FramePage.assign(frames, -1);
  FrameDirty.assign(frames, 0);
  FrameReferenced.assign(frames, 0);
  for (std::size_t f = frames; f-- > 0;)
  {
    FreeFrames.push_back(f);
  }
}

BucketStore::~BucketStore()
{
  if (InFlight.Done.valid())
  {
    InFlight.Done.wait();
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

void BucketStore::FinishWrites()
{
  if (!InFlight.Done.valid())
  {
    return;
  }
  InFlight.Done.get(); // rethrows a write error (disk full)
  for (const auto& [frame, page] : InFlight.Frames)
  {
    // A page cleared meanwhile no longer maps to this frame: only the frame is freed.
    if (PageFrame[page] == std::int32_t(frame))
    {
      PageFrame[page] = NotResident;
      PageOnDisk[page] = 1;
    }
    States[frame] = FrameState::Free;
    FramePage[frame] = -1;
    FreeFrames.push_back(frame);
  }
  InFlight.Frames.clear();
}

void BucketStore::StartEvictions()
{
  // An eighth of the pool per batch: large sequential-ish writes, while the other frames
  // keep taking appends.
  const std::size_t frames = FramePage.size();
  const std::size_t wanted = std::max<std::size_t>(1, frames / 8);
  std::size_t found = 0;
  for (std::size_t step = 0; step < 2 * frames && found < wanted; ++step)
  {
    // Clock (second chance): skip recently used frames once, clearing their bit.
    const std::size_t frame = ClockHand;
    ClockHand = (ClockHand + 1) % frames;
    if (States[frame] != FrameState::Resident)
    {
      continue;
    }
    if (FrameReferenced[frame])
    {
      FrameReferenced[frame] = 0;
      continue;
    }
    ++found;
    const PageIndex page = PageIndex(FramePage[frame]);
    if (!FrameDirty[frame])
    {
      PageFrame[page] = NotResident;
      States[frame] = FrameState::Free;
      FramePage[frame] = -1;
      FreeFrames.push_back(frame);
      continue;
    }
    States[frame] = FrameState::Writing;
    FrameDirty[frame] = 0;
    InFlight.Frames.emplace_back(frame, page);
    const std::uint64_t end = (std::uint64_t(page) + 1) * PageBytes;
    Counters.BytesWritten += PageBytes;
    Counters.PeakScratchBytes = std::max(Counters.PeakScratchBytes, end);
  }
  if (!InFlight.Frames.empty())
  {
    std::sort(InFlight.Frames.begin(), InFlight.Frames.end(),
      [](const auto& a, const auto& b) { return a.second < b.second; }); // file order
    InFlight.Done = std::async(std::launch::async, [this, batch = InFlight.Frames] {
      for (const auto& [frame, page] : batch)
      {
        Disk.WriteAt(std::uint64_t(page) * PageBytes, FrameData(frame), PageBytes);
      }
    });
  }
}

std::size_t BucketStore::FreeFrame()
{
  // Keep a batch of writes ahead of need, so appends rarely wait for the disk.
  if (!InFlight.Done.valid() && FreeFrames.size() < std::max<std::size_t>(1, FramePage.size() / 8))
  {
    StartEvictions();
  }
  while (FreeFrames.empty())
  {
    FinishWrites();
    if (FreeFrames.empty())
    {
      StartEvictions();
    }
  }
  const std::size_t frame = FreeFrames.back();
  FreeFrames.pop_back();
  return frame;
}

std::size_t BucketStore::Resident(PageIndex page, bool load)
{
  if (PageFrame[page] != NotResident && States[std::size_t(PageFrame[page])] == FrameState::Writing)
  {
    FinishWrites(); // the writer may still be reading the frame: let it finish first
  }
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
  States[frame] = FrameState::Resident;
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
  std::memcpy(FrameData(frame) + slot * RecordBytes, &triangle, RecordBytes);
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
      // Also for a frame being written: the writer only reads it too.
      Unpack(FrameData(std::size_t(PageFrame[page])), n, &out[first]);
    }
    else
    {
      // Packed records are never longer than SoupTriangles: read them into place, then spread.
      unsigned char* packed = reinterpret_cast<unsigned char*>(&out[first]);
      Disk.ReadAt(std::uint64_t(page) * PageBytes, packed, n * RecordBytes);
      Counters.BytesRead += n * RecordBytes;
      Unpack(packed, n, &out[first]);
    }
    first += n;
    left -= n;
  }
}

void BucketStore::Unpack(const unsigned char* packed, std::size_t count, SoupTriangle* out) const
{
  // Backwards: a record's destination never overlaps a packed record not yet moved.
  for (std::size_t i = count; i-- > 0;)
  {
    unsigned char* to = reinterpret_cast<unsigned char*>(&out[i]);
    std::memmove(to, packed + i * RecordBytes, RecordBytes);
    std::memset(to + RecordBytes, 255, sizeof(SoupTriangle) - RecordBytes);
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
      if (States[frame] == FrameState::Resident)
      {
        States[frame] = FrameState::Free;
        FramePage[frame] = -1;
        FrameDirty[frame] = 0;
        FrameReferenced[frame] = 0;
        FreeFrames.push_back(frame);
      }
      // A frame being written is freed when its batch finishes.
      PageFrame[page] = NotResident;
    }
    if (PageOnDisk[page])
    {
      // Construction empties buckets for good: their disk space goes back at once.
      Disk.Release(std::uint64_t(page) * PageBytes, PageBytes);
    }
    PageOnDisk[page] = 0;
    FreePages.push_back(page);
  }
  bucket = Bucket();
}

} // namespace atp
