// Triangle buckets kept on disk behind a fixed pool of in-memory pages, so partitioning any
// number of triangles needs the same memory (paper 5.1: "triangle buckets are stored in
// secondary memory"). Pages of deleted buckets are reused, so the scratch file stays about the
// size of the live triangles. Evicted pages are written in batches by a background thread
// while the caller goes on filling other pages.
//
// A page is a small indexed mesh: the distinct corners (position, normal, color) of its
// triangles, each stored once, and per triangle three 16-bit corner numbers and its boundary
// bits. Triangles of one bucket come from one small region of a streamed mesh and share most
// corners, so a page holds about 2.5 times the triangles of a soup page (the brain: 21 bytes a
// triangle instead of 52; the paper's buckets held raw triangles, about 3 times the input, and
// it suggested compressed ones). Reading gives back the appended triangles bit for bit.
#ifndef atpBucketStore_h
#define atpBucketStore_h

#include "atpHugePageBuffer.h"
#include "atpScratchArray.h"
#include "atpScratchFile.h"
#include "atpTriangleSource.h"
#include "vtkATPFiltersModule.h"

#include <atomic>
#include <cstdint>
#include <future>
#include <memory>
#include <mutex>
#include <vector>

namespace atp
{

struct BucketStoreStats
{
  std::uint64_t BytesWritten = 0; ///< page write-backs to the scratch file
  std::uint64_t BytesRead = 0;    ///< page reads from the scratch file
  std::uint64_t PeakScratchBytes = 0;
};

class VTKATPFILTERS_EXPORT BucketStore
{
public:
  using BucketIndex = std::uint32_t;
  /// Large sequential writes, and a bucket's last, partly filled page wastes little disk
  /// (leaves are many).
  static constexpr std::size_t PageBytes = 16384;

  /// `colors`: corners keep their colors (otherwise they read back opaque white, and a corner
  /// takes a fifth less room).
  BucketStore(const std::string& scratchDirectory, std::size_t memoryBudgetBytes, bool colors);
  /// Waits for the background writes (their errors are lost: the store is going away).
  ~BucketStore();

  /// Throws std::runtime_error when the scratch file cannot be written (disk full).
  void Append(BucketIndex bucket, const SoupTriangle& triangle);
  std::uint64_t Count(BucketIndex bucket) const
  {
    return bucket < Buckets.Size() ? Buckets[bucket].Count : 0;
  }
  /// Starts loading what appending the triangle to the bucket will read: the bucket's record
  /// and last-triangle entry, its last page's header and the lookup slots of the triangle's
  /// corners. A caller that knows its next appends overlaps their cache misses, which are most
  /// of an append's time.
  /// Only a hint: it changes nothing, and does nothing for a page that is not in memory.
  void Prefetch(BucketIndex bucket, const SoupTriangle& triangle) const;
  /// Appends the bucket's triangles to `out`, in insertion order. Once appending has stopped,
  /// safe from several threads at once, and beside Discard of other buckets.
  void Read(BucketIndex bucket, std::vector<SoupTriangle>& out) const;
  /// Empties the bucket and recycles its pages.
  void Clear(BucketIndex bucket) { Empty(bucket, false); }
  /// After the last append: the pool's free frames and every corner lookup table go back to
  /// the system, and from now on the frames of emptied buckets too (Discard). Construction
  /// then holds only the pages still waiting to be read, fewer with every leaf.
  /// Throws std::runtime_error when a pending write-back fails (disk full).
  void StopAppending();
  /// Empties the bucket for good: as Clear, and its frames' memory goes back to the system.
  /// Once appending has stopped, safe from several threads at once, and beside Read of other
  /// buckets.
  void Discard(BucketIndex bucket) { Empty(bucket, true); }

  /// Gives the memory of the records that grow with the input (one per node of the forest, one
  /// per page of bucket data) back to the system; they come back as they are used.
  void ReleaseResident() const
  {
    Buckets.ReleaseResident();
    Pages.ReleaseResident();
  }

  BucketStoreStats Stats() const
  {
    BucketStoreStats stats = Counters;
    stats.BytesRead = BytesRead;
    return stats;
  }
  std::size_t PoolPages() const { return FramePage.size(); }

private:
  using PageIndex = std::uint32_t;
  static constexpr std::int32_t NotResident = -1;

  /// A corner as words: the bytes of its position and normal (its key), and of its color
  /// (0 when colors are not kept). Built from a triangle's fields without a byte buffer, whose
  /// narrow stores read back as words stall the processor.
  struct Corner
  {
    std::uint64_t Low = 0, High = 0;
    std::uint32_t Color = 0;
    std::uint8_t Uses = 0;
    bool operator==(const Corner& o) const
    {
      return Low == o.Low && High == o.High && Color == o.Color && Uses == o.Uses;
    }
  };
  static constexpr PageIndex NoPage = ~PageIndex(0);
  /// 16 bytes: there is one per node of the forest. Its pages form a list (Page::Next).
  struct Bucket
  {
    std::uint64_t Count = 0;
    PageIndex FirstPage = NoPage, LastPage = NoPage;
  };
  /// The corners of the last triangle appended to a bucket and their numbers in its last page:
  /// the next triangle, a stream neighbour, mostly shares them, and finding them here touches
  /// no page memory. Kept for the recently appended buckets only (a few are active at a time),
  /// in a table of fixed size rather than in every bucket.
  struct LastTriangle
  {
    BucketIndex Bucket = ~BucketIndex(0); ///< none
    std::uint16_t Numbers[3] = { 0, 0, 0 };
    Corner Corners[3];
  };
  static constexpr std::size_t LastTriangleSlots = 8192;
  LastTriangle& LastOf(BucketIndex bucket) { return LastTriangles[bucket & (LastTriangleSlots - 1)]; }
  /// Forgets the bucket's last triangle: its last page starts anew.
  void ForgetLast(BucketIndex bucket)
  {
    LastTriangle& last = LastOf(bucket);
    if (last.Bucket == bucket)
    {
      last.Bucket = ~BucketIndex(0);
    }
  }

  enum class FrameState : char
  {
    Free,
    Resident,
    Writing ///< content valid and readable, being written by the background thread
  };
  struct WriteBatch
  {
    std::vector<std::pair<std::size_t, PageIndex>> Frames; // frame, page
    std::future<void> Done;
  };

  PageIndex NewPage();
  /// Frame holding `page` for writing into it; reads it back from disk when `load` and it
  /// was evicted.
  std::size_t Resident(PageIndex page, bool load);
  std::size_t FreeFrame();
  /// Adds the triangle to the page in `frame` if its new corners fit; false when full.
  bool AddToPage(std::size_t frame, const SoupTriangle& triangle, BucketIndex bucket);
  /// Corner k of the triangle as words.
  Corner CornerOf(const SoupTriangle& triangle, int k) const;
  /// The corner stored at `bytes` in a page.
  Corner CornerAt(const unsigned char* bytes) const;
  /// The corner's number in the page in `frame`, added if new; -1 when it does not fit.
  int CornerIndex(std::size_t frame, const Corner& corner);
  /// Fills in the corner lookup of the page in `frame` from its corners.
  void IndexCorners(std::size_t frame);
  /// Appends the triangles of one page to `out`.
  void Unpack(const unsigned char* page, std::vector<SoupTriangle>& out) const;
  void Empty(BucketIndex bucket, bool releaseMemory);
  /// Picks not recently used frames: clean ones are freed now, dirty ones go to a new
  /// background write batch.
  void StartEvictions();
  /// Waits for the batch in flight, if any, and frees its frames.
  void FinishWrites();
  /// Maps the next PrefaultFrames frames of the pool on a background thread, unless the last
  /// ones are still being mapped.
  void PrefaultMoreFrames();
  unsigned char* FrameData(std::size_t frame) const
  {
    return static_cast<unsigned char*>(Pool.Data()) + frame * PageBytes;
  }
  std::uint16_t* CornerTable(std::size_t frame) const;

  ScratchFile Disk;
  ScratchArray<Bucket> Buckets; ///< in a scratch file's mapping, see ReleaseResident
  std::vector<LastTriangle> LastTriangles;
  /// Bytes of one corner: position, normal, and color when kept.
  const std::size_t CornerBytes;
  // Pages of the pool cost memory only once they are used; huge pages make filling it cheap.
  HugePageBuffer Pool;
  /// Per frame, an open-addressing table from corner bytes to corner number + 1 (0: empty),
  /// for appending; valid only when CornersIndexed.
  HugePageBuffer CornerTableMemory;
  std::vector<char> CornersIndexed;
  // Per frame: its state, the page it holds (or none), whether it changed since loaded, and
  // the clock's reference bit.
  std::vector<FrameState> States;
  std::vector<std::int64_t> FramePage;
  std::vector<char> FrameDirty, FrameReferenced;
  std::vector<std::size_t> FreeFrames;
  std::size_t ClockHand = 0;
  /// One per page of bucket data (a billion triangles fill over a million): its frame, or
  /// NotResident (then its content, if any, is on disk at its slot), and the next page of its
  /// bucket, or of the recycled pages.
  struct Page
  {
    std::int32_t Frame = NotResident;
    PageIndex Next = NoPage;
    std::uint32_t OnDisk = 0;
  };
  ScratchArray<Page> Pages;
  PageIndex FreePages = NoPage; ///< the first recycled page

  WriteBatch InFlight;
  /// 8 MiB of pool at a time; frames below PrefaultedFrames are mapped or being mapped.
  static constexpr std::size_t PrefaultFrames = 512;
  std::size_t PrefaultedFrames = 0;
  std::future<void> Prefaulting;
  BucketStoreStats Counters;
  /// Held by Empty while it adds to the free frames and pages: construction discards buckets
  /// on several threads at once.
  std::mutex Recycling;
  mutable std::atomic<std::uint64_t> BytesRead{ 0 }; // Read counts too, on any thread
};

} // namespace atp

#endif
