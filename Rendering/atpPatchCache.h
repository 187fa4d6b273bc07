// A least-recently-used cache of per-patch values under a byte budget, where everything used in
// the current frame is pinned: a frame never evicts what it draws. Plain C++ and header-only, so
// that the policy is testable without a GPU; the mapper stores buffer objects in it.
#ifndef atpPatchCache_h
#define atpPatchCache_h

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace atp
{

template <typename Value>
class PatchCache
{
public:
  /// Called with every value that leaves the cache (evicted or cleared), to free it.
  using ReleaseFunction = std::function<void(Value&)>;

  explicit PatchCache(ReleaseFunction release)
    : Release(std::move(release))
  {
  }
  ~PatchCache() { Clear(); }
  PatchCache(const PatchCache&) = delete;
  PatchCache& operator=(const PatchCache&) = delete;

  void SetBudget(std::size_t bytes) { Budget = bytes; }
  std::size_t GetBudget() const { return Budget; }
  /// Starts a new frame: what the previous frames used may be evicted again.
  void NewFrame()
  {
    ++Frame;
    PinnedBytes = 0;
  }

  bool Contains(std::uint32_t key) const { return SlotOf(key) != None; }

  /// The value, marked used by (and pinned for) this frame; null when absent. Valid until the
  /// next Insert.
  Value* Use(std::uint32_t key)
  {
    const std::uint32_t slot = SlotOf(key);
    if (slot == None)
    {
      return nullptr;
    }
    Entry& e = Entries[slot];
    if (e.LastFrame != Frame)
    {
      e.LastFrame = Frame;
      PinnedBytes += e.Bytes;
      Unlink(slot);
      LinkFront(slot);
    }
    return &e.Item;
  }

  /// Makes room for a value of `bytes` by evicting the least recently used values not pinned
  /// by this frame, until the budget has room and `place` (which finds the value its storage,
  /// such as a free range of a buffer, and may fail while that is fragmented) succeeds. False
  /// when even evicting all of them cannot; nothing is evicted when the pinned values alone
  /// leave no room in the budget.
  bool MakeRoom(std::size_t bytes, const std::function<bool()>& place)
  {
    if (PinnedBytes + bytes > Budget)
    {
      return false;
    }
    // Pinned entries were moved to the front when used: from the back, the first pinned entry
    // ends the evictable ones.
    for (;;)
    {
      if (Bytes + bytes <= Budget && place())
      {
        return true;
      }
      if (Back == None || Entries[Back].LastFrame == Frame)
      {
        return false;
      }
      Remove(Back);
      ++Evictions;
    }
  }

  /// Stores a value of `bytes` (pinned for this frame) under a key not in the cache; the caller
  /// made room first. Valid until the next Insert.
  Value& Insert(std::uint32_t key, Value value, std::size_t bytes)
  {
    std::uint32_t slot = None;
    if (FreeSlots.empty())
    {
      slot = std::uint32_t(Entries.size());
      Entries.emplace_back();
    }
    else
    {
      slot = FreeSlots.back();
      FreeSlots.pop_back();
    }
    Entry& e = Entries[slot];
    e.Key = key;
    e.Item = std::move(value);
    e.Bytes = bytes;
    e.LastFrame = Frame;
    LinkFront(slot);
    if (key >= Slots.size())
    {
      Slots.resize(std::size_t(key) + 1, None);
    }
    Slots[key] = slot;
    ++Count;
    Bytes += bytes;
    PinnedBytes += bytes;
    return e.Item;
  }

  void Clear()
  {
    while (Back != None)
    {
      Remove(Back);
    }
    Entries.clear();
    FreeSlots.clear();
    PinnedBytes = 0;
  }

  std::size_t GetBytes() const { return Bytes; }
  std::size_t GetCount() const { return Count; }
  std::uint64_t GetEvictions() const { return Evictions; }

private:
  static constexpr std::uint32_t None = ~std::uint32_t(0);

  /// Entries live in one array, linked from the most recently used (Front) to the least (Back),
  /// and keys, which are node indices, find theirs through a flat array: the cut pins tens of
  /// thousands of patches a frame, and a hash map and list nodes made each a few cache misses.
  struct Entry
  {
    std::uint32_t Key = 0;
    std::uint32_t Previous = None, Next = None; ///< towards Front, towards Back
    Value Item{};
    std::size_t Bytes = 0;
    std::uint64_t LastFrame = 0;
  };

  std::uint32_t SlotOf(std::uint32_t key) const { return key < Slots.size() ? Slots[key] : None; }

  void Unlink(std::uint32_t slot)
  {
    Entry& e = Entries[slot];
    (e.Previous == None ? Front : Entries[e.Previous].Next) = e.Next;
    (e.Next == None ? Back : Entries[e.Next].Previous) = e.Previous;
  }

  void LinkFront(std::uint32_t slot)
  {
    Entry& e = Entries[slot];
    e.Previous = None;
    e.Next = Front;
    (Front == None ? Back : Entries[Front].Previous) = slot;
    Front = slot;
  }

  /// Releases and unlinks an entry, freeing its slot.
  void Remove(std::uint32_t slot)
  {
    Entry& e = Entries[slot];
    Release(e.Item);
    Unlink(slot);
    Slots[e.Key] = None;
    Bytes -= e.Bytes;
    --Count;
    FreeSlots.push_back(slot);
  }

  ReleaseFunction Release;
  std::vector<Entry> Entries;
  std::vector<std::uint32_t> FreeSlots;
  std::vector<std::uint32_t> Slots; ///< key -> entry, None when absent
  std::uint32_t Front = None, Back = None;
  std::size_t Count = 0;
  std::size_t Budget = std::size_t(512) << 20;
  std::size_t Bytes = 0;
  std::size_t PinnedBytes = 0; ///< of the entries used by this frame
  std::uint64_t Frame = 1;
  std::uint64_t Evictions = 0;
};

} // namespace atp

#endif
