#include "atpBucketStore.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <cstring>
#include <new>
#include <stdexcept>

namespace atp
{

namespace
{
// A page: u16 corner count, u16 triangle count, the corners (position, normal, input uses, and
// color when the input has colors) from the front, the triangles (3 x u16 corner numbers, u8
// boundary bits) from the back.
constexpr std::size_t PageHeaderBytes = 4;
constexpr std::size_t TriangleBytes = 7;
constexpr std::size_t PositionNormalBytes = 3 * sizeof(float) + 2 * sizeof(std::int16_t);
/// A corner without color: its position, normal and input uses (SoupTriangle::InputUses).
constexpr std::size_t PlainCornerBytes = PositionNormalBytes + 1;
/// Corners of a page, at most: the page full of corners alone.
constexpr std::size_t MaxPageCorners = BucketStore::PageBytes / PositionNormalBytes;
/// Slots of a frame's corner table: a power of two at least twice the corners.
constexpr std::size_t CornerTableSlots = 2048;
static_assert(CornerTableSlots >= 2 * MaxPageCorners, "corner table load at most 1/2");
static_assert(PositionNormalBytes == 16, "a corner key is its position and normal");

std::uint16_t GetU16(const unsigned char* p)
{
  std::uint16_t v;
  std::memcpy(&v, p, sizeof(v));
  return v;
}

void PutU16(unsigned char* p, std::uint16_t v)
{
  std::memcpy(p, &v, sizeof(v));
}

/// The slot of a corner table where the lookup of the corner with these key words starts.
std::size_t FirstSlot(std::uint64_t low, std::uint64_t high)
{
  const std::uint64_t h = low * 0x9E3779B97F4A7C15ull ^ high * 0xC2B2AE3D27D4EB4Full;
  return std::size_t(h ^ (h >> 31)) & (CornerTableSlots - 1);
}
} // namespace

BucketStore::BucketStore(const std::string& scratchDirectory, std::size_t memoryBudgetBytes, bool colors)
  : Disk(scratchDirectory)
  , Buckets(scratchDirectory)
  , LastTriangles(LastTriangleSlots)
  , CornerBytes(PlainCornerBytes + (colors ? 4 : 0))
  , Pages(scratchDirectory)
{
  // At least a handful of frames so that a split (one bucket read, two appended) always fits.
  const std::size_t frameBytes = PageBytes + CornerTableSlots * sizeof(std::uint16_t);
  const std::size_t frames = std::max<std::size_t>(8, memoryBudgetBytes / frameBytes);
  try
  {
    Pool = HugePageBuffer(frames * PageBytes);
    CornerTableMemory = HugePageBuffer(frames * CornerTableSlots * sizeof(std::uint16_t));
  }
  catch (const std::bad_alloc&)
  {
    throw std::runtime_error("cannot reserve " + std::to_string((frames * frameBytes) >> 20) +
      " MiB for the triangle buckets (the bucket memory asked for): out of memory");
  }
  CornersIndexed.assign(frames, 0);
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
  if (Prefaulting.valid())
  {
    Prefaulting.wait();
  }
}

void BucketStore::PrefaultMoreFrames()
{
  const std::size_t frames = FramePage.size();
  if (PrefaultedFrames >= frames ||
    (Prefaulting.valid() && Prefaulting.wait_for(std::chrono::seconds(0)) != std::future_status::ready))
  {
    return;
  }
  const std::size_t first = PrefaultedFrames;
  const std::size_t count = std::min(PrefaultFrames, frames - first);
  PrefaultedFrames += count;
  Prefaulting = std::async(std::launch::async, [this, first, count] {
    Pool.Prefault(first * PageBytes, count * PageBytes);
    const std::size_t tableBytes = CornerTableSlots * sizeof(std::uint16_t);
    CornerTableMemory.Prefault(first * tableBytes, count * tableBytes);
  });
}

std::uint16_t* BucketStore::CornerTable(std::size_t frame) const
{
  return static_cast<std::uint16_t*>(CornerTableMemory.Data()) + frame * CornerTableSlots;
}

BucketStore::PageIndex BucketStore::NewPage()
{
  if (FreePages != NoPage)
  {
    const PageIndex page = FreePages;
    FreePages = Pages[page].Next;
    Pages[page].Next = NoPage;
    return page;
  }
  Pages.PushBack(Page());
  return PageIndex(Pages.Size() - 1);
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
    if (Pages[page].Frame == std::int32_t(frame))
    {
      Pages[page].Frame = NotResident;
      Pages[page].OnDisk = 1;
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
      Pages[page].Frame = NotResident;
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
  // Unused frames are handed out in order: map the next ones on another thread before they
  // are needed, so that this one does not stop to have huge pages zeroed.
  if (frame + PrefaultFrames / 2 >= PrefaultedFrames)
  {
    PrefaultMoreFrames();
  }
  return frame;
}

std::size_t BucketStore::Resident(PageIndex page, bool load)
{
  if (Pages[page].Frame != NotResident && States[std::size_t(Pages[page].Frame)] == FrameState::Writing)
  {
    FinishWrites(); // the writer may still be reading the frame: let it finish first
  }
  if (Pages[page].Frame != NotResident)
  {
    return std::size_t(Pages[page].Frame);
  }
  const std::size_t frame = FreeFrame();
  if (load && Pages[page].OnDisk)
  {
    Disk.ReadAt(std::uint64_t(page) * PageBytes, FrameData(frame), PageBytes);
    BytesRead += PageBytes;
  }
  if (!load || !Pages[page].OnDisk)
  {
    PutU16(FrameData(frame), 0); // a new page: no corners,
    PutU16(FrameData(frame) + 2, 0); // no triangles
  }
  States[frame] = FrameState::Resident;
  FramePage[frame] = page;
  FrameDirty[frame] = 0;
  CornersIndexed[frame] = 0;
  Pages[page].Frame = std::int32_t(frame);
  return frame;
}

BucketStore::Corner BucketStore::CornerOf(const SoupTriangle& triangle, int k) const
{
  // The words hold the bytes a page stores (position, normal, color), in memory order.
  Corner corner;
  std::memcpy(&corner.Low, triangle.V[k], sizeof(corner.Low));
  std::uint32_t z, normal;
  std::memcpy(&z, &triangle.V[k][2], sizeof(z));
  std::memcpy(&normal, triangle.Normals[k], sizeof(normal));
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  corner.High = z | std::uint64_t(normal) << 32;
#else
  corner.High = std::uint64_t(z) << 32 | normal;
#endif
  corner.Uses = triangle.InputUses[k];
  if (CornerBytes > PlainCornerBytes)
  {
    std::memcpy(&corner.Color, triangle.Colors[k], sizeof(corner.Color));
  }
  return corner;
}

BucketStore::Corner BucketStore::CornerAt(const unsigned char* bytes) const
{
  Corner corner;
  std::memcpy(&corner.Low, bytes, sizeof(corner.Low));
  std::memcpy(&corner.High, bytes + sizeof(corner.Low), sizeof(corner.High));
  corner.Uses = bytes[PositionNormalBytes];
  if (CornerBytes > PlainCornerBytes)
  {
    std::memcpy(&corner.Color, bytes + PlainCornerBytes, sizeof(corner.Color));
  }
  return corner;
}

void BucketStore::IndexCorners(std::size_t frame)
{
  std::uint16_t* table = CornerTable(frame);
  std::fill(table, table + CornerTableSlots, std::uint16_t(0));
  const unsigned char* page = FrameData(frame);
  const std::size_t corners = GetU16(page);
  for (std::size_t c = 0; c < corners; ++c)
  {
    const Corner corner = CornerAt(page + PageHeaderBytes + c * CornerBytes);
    std::size_t slot = FirstSlot(corner.Low, corner.High);
    while (table[slot] != 0)
    {
      slot = (slot + 1) & (CornerTableSlots - 1);
    }
    table[slot] = std::uint16_t(c + 1);
  }
  CornersIndexed[frame] = 1;
}

int BucketStore::CornerIndex(std::size_t frame, const Corner& corner)
{
  unsigned char* page = FrameData(frame);
  std::uint16_t* table = CornerTable(frame);
  std::size_t slot = FirstSlot(corner.Low, corner.High);
  for (; table[slot] != 0; slot = (slot + 1) & (CornerTableSlots - 1))
  {
    const std::size_t c = table[slot] - 1u;
    if (CornerAt(page + PageHeaderBytes + c * CornerBytes) == corner)
    {
      return int(c);
    }
  }
  const std::size_t corners = GetU16(page), triangles = GetU16(page + 2);
  // Room for this corner and the triangle that uses it (counted before its corners go in).
  if (PageHeaderBytes + (corners + 1) * CornerBytes + (triangles + 1) * TriangleBytes > PageBytes)
  {
    return -1;
  }
  unsigned char* bytes = page + PageHeaderBytes + corners * CornerBytes;
  std::memcpy(bytes, &corner.Low, sizeof(corner.Low));
  std::memcpy(bytes + sizeof(corner.Low), &corner.High, sizeof(corner.High));
  bytes[PositionNormalBytes] = corner.Uses;
  if (CornerBytes > PlainCornerBytes)
  {
    std::memcpy(bytes + PlainCornerBytes, &corner.Color, sizeof(corner.Color));
  }
  PutU16(page, std::uint16_t(corners + 1));
  table[slot] = std::uint16_t(corners + 1);
  return int(corners);
}

bool BucketStore::AddToPage(std::size_t frame, const SoupTriangle& triangle, BucketIndex bucket)
{
  if (!CornersIndexed[frame])
  {
    IndexCorners(frame);
  }
  unsigned char* page = FrameData(frame);
  const std::uint16_t cornersBefore = GetU16(page);
  const std::uint16_t triangles = GetU16(page + 2);
  if (PageHeaderBytes + cornersBefore * CornerBytes + (triangles + 1u) * TriangleBytes > PageBytes)
  {
    return false; // not even room for a triangle of known corners
  }
  // The record's room is reserved by the checks: each number goes in as it is found.
  unsigned char* record = page + PageBytes - (std::size_t(triangles) + 1) * TriangleBytes;
  LastTriangle& last = LastOf(bucket);
  const bool haveLast = last.Bucket == bucket;
  Corner corners[3];
  std::uint16_t numbers[3];
  for (int k = 0; k < 3; ++k)
  {
    corners[k] = CornerOf(triangle, k);
    int number = -1;
    for (int j = 0; j < 3 && haveLast && number < 0; ++j)
    {
      number = last.Corners[j] == corners[k] ? int(last.Numbers[j]) : -1;
    }
    number = number >= 0 ? number : CornerIndex(frame, corners[k]);
    if (number < 0)
    {
      // Full: forget the corners this triangle added, it goes to a new page.
      PutU16(page, cornersBefore);
      CornersIndexed[frame] = 0;
      return false;
    }
    numbers[k] = std::uint16_t(number);
    PutU16(record + 2 * k, numbers[k]);
  }
  record[6] = triangle.BoundaryEdges;
  PutU16(page + 2, std::uint16_t(triangles + 1));
  last.Bucket = bucket;
  // Element by element: std::copy of the corners became a call to memmove per triangle.
  for (int k = 0; k < 3; ++k)
  {
    last.Corners[k] = corners[k];
    last.Numbers[k] = numbers[k];
  }
  return true;
}

void BucketStore::Prefetch(BucketIndex bucket, const SoupTriangle& triangle) const
{
  if (bucket >= Buckets.Size())
  {
    return;
  }
  __builtin_prefetch(&LastTriangles[bucket & (LastTriangleSlots - 1)]);
  const PageIndex page = Buckets[bucket].LastPage;
  if (page == NoPage || Pages[page].Frame == NotResident)
  {
    return;
  }
  const std::size_t frame = std::size_t(Pages[page].Frame);
  __builtin_prefetch(FrameData(frame));
  if (!CornersIndexed[frame])
  {
    return;
  }
  const std::uint16_t* table = CornerTable(frame);
  for (int k = 0; k < 3; ++k)
  {
    const Corner corner = CornerOf(triangle, k);
    __builtin_prefetch(table + FirstSlot(corner.Low, corner.High));
  }
}

void BucketStore::Append(BucketIndex bucketIndex, const SoupTriangle& triangle)
{
  if (bucketIndex >= Buckets.Size())
  {
    Buckets.Resize(std::size_t(bucketIndex) + 1, Bucket());
  }
  Bucket& bucket = Buckets[bucketIndex];
  const PageIndex lastPage = bucket.LastPage;
  std::size_t frame = lastPage == NoPage ? 0 : Resident(lastPage, true);
  if (lastPage == NoPage || !AddToPage(frame, triangle, bucketIndex))
  {
    const PageIndex page = NewPage();
    (lastPage == NoPage ? bucket.FirstPage : Pages[lastPage].Next) = page;
    bucket.LastPage = page;
    ForgetLast(bucketIndex); // its numbers were the old page's
    frame = Resident(page, false);
    AddToPage(frame, triangle, bucketIndex); // an empty page holds any triangle
  }
  FrameDirty[frame] = 1;
  FrameReferenced[frame] = 1;
  ++bucket.Count;
}

void BucketStore::Read(BucketIndex bucketIndex, std::vector<SoupTriangle>& out) const
{
  if (bucketIndex >= Buckets.Size())
  {
    return;
  }
  const Bucket& bucket = Buckets[bucketIndex];
  out.reserve(out.size() + bucket.Count);
  std::vector<unsigned char> buffer;
  for (PageIndex page = bucket.FirstPage; page != NoPage; page = Pages[page].Next)
  {
    if (Pages[page].Frame != NotResident)
    {
      // Also for a frame being written: the writer only reads it too.
      Unpack(FrameData(std::size_t(Pages[page].Frame)), out);
    }
    else
    {
      buffer.resize(PageBytes);
      Disk.ReadAt(std::uint64_t(page) * PageBytes, buffer.data(), PageBytes);
      BytesRead += PageBytes;
      Unpack(buffer.data(), out);
    }
  }
}

void BucketStore::Unpack(const unsigned char* page, std::vector<SoupTriangle>& out) const
{
  const std::size_t corners = GetU16(page), triangles = GetU16(page + 2);
  if (PageHeaderBytes + corners * CornerBytes + triangles * TriangleBytes > PageBytes)
  {
    throw std::runtime_error("triangle bucket scratch file: a page reads back corrupt");
  }
  for (std::size_t t = 0; t < triangles; ++t)
  {
    const unsigned char* record = page + PageBytes - (t + 1) * TriangleBytes;
    SoupTriangle triangle;
    std::memset(&triangle, 255, sizeof(triangle)); // colors not kept read back opaque white
    triangle.BoundaryEdges = record[6];
    for (int k = 0; k < 3; ++k)
    {
      const std::size_t c = GetU16(record + 2 * k);
      if (c >= corners)
      {
        throw std::runtime_error("triangle bucket scratch file: a page reads back corrupt");
      }
      const unsigned char* corner = page + PageHeaderBytes + c * CornerBytes;
      std::memcpy(triangle.V[k], corner, 3 * sizeof(float));
      std::memcpy(triangle.Normals[k], corner + 3 * sizeof(float), 2 * sizeof(std::int16_t));
      triangle.InputUses[k] = corner[PositionNormalBytes];
      if (CornerBytes > PlainCornerBytes)
      {
        std::memcpy(triangle.Colors[k], corner + PlainCornerBytes, sizeof(triangle.Colors[k]));
      }
    }
    out.push_back(triangle);
  }
}

void BucketStore::StopAppending()
{
  FinishWrites();
  if (Prefaulting.valid())
  {
    Prefaulting.wait(); // it must not map frames again after they are released
  }
  PrefaultedFrames = FramePage.size();
  Pool.StopHugePages();
  CornerTableMemory.StopHugePages();
  // Runs of free frames, one call each (the never used ones are one run at the end).
  std::vector<std::size_t> free = FreeFrames;
  std::sort(free.begin(), free.end());
  for (std::size_t first = 0, last; first < free.size(); first = last)
  {
    for (last = first + 1; last < free.size() && free[last] == free[last - 1] + 1; ++last)
    {
    }
    Pool.Release(free[first] * PageBytes, (last - first) * PageBytes);
  }
  // Rebuilt from its page if a frame is ever appended to again.
  CornerTableMemory.Release(0, CornerTableMemory.Size());
  std::fill(CornersIndexed.begin(), CornersIndexed.end(), 0);
}

void BucketStore::Empty(BucketIndex bucketIndex, bool releaseMemory)
{
  if (bucketIndex >= Buckets.Size())
  {
    return;
  }
  Bucket& bucket = Buckets[bucketIndex];
  std::vector<std::size_t> freedFrames;
  std::vector<PageIndex> freedOnDisk;
  {
    // Only the lists of free frames and pages are shared with other buckets' Empty.
    const std::lock_guard<std::mutex> lock(Recycling);
    for (PageIndex page = bucket.FirstPage, next; page != NoPage; page = next)
    {
      next = Pages[page].Next;
      if (Pages[page].Frame != NotResident)
      {
        const std::size_t frame = std::size_t(Pages[page].Frame);
        if (States[frame] == FrameState::Resident)
        {
          States[frame] = FrameState::Free;
          FramePage[frame] = -1;
          FrameDirty[frame] = 0;
          FrameReferenced[frame] = 0;
          FreeFrames.push_back(frame);
          if (releaseMemory)
          {
            freedFrames.push_back(frame);
          }
        }
        // A frame being written is freed when its batch finishes.
        Pages[page].Frame = NotResident;
      }
      if (Pages[page].OnDisk)
      {
        freedOnDisk.push_back(page);
      }
      Pages[page].OnDisk = 0;
      Pages[page].Next = FreePages;
      FreePages = page;
    }
  }
  for (std::size_t frame : freedFrames)
  {
    Pool.Release(frame * PageBytes, PageBytes);
  }
  for (PageIndex page : freedOnDisk)
  {
    // Construction empties buckets for good: their disk space goes back at once.
    Disk.Release(std::uint64_t(page) * PageBytes, PageBytes);
  }
  bucket = Bucket(); // its next append starts a page, which forgets its last triangle
}

} // namespace atp
