// A least-recently-used cache of per-patch values under a byte budget, where everything used in
// the current frame is pinned: a frame never evicts what it draws. Plain C++ and header-only, so
// that the policy is testable without a GPU; the mapper stores buffer objects in it.
#ifndef atpPatchCache_h
#define atpPatchCache_h

#include <cstddef>
#include <cstdint>
#include <functional>
#include <list>
#include <unordered_map>

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

  bool Contains(std::uint32_t key) const { return Entries.count(key) != 0; }

  /// The value, marked used by (and pinned for) this frame; null when absent.
  Value* Use(std::uint32_t key)
  {
    const auto found = Entries.find(key);
    if (found == Entries.end())
    {
      return nullptr;
    }
    Order.splice(Order.begin(), Order, found->second);
    if (found->second->LastFrame != Frame)
    {
      found->second->LastFrame = Frame;
      PinnedBytes += found->second->Bytes;
    }
    return &found->second->Item;
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
    // Pinned entries were moved to the front when used: the back holds the evictable ones.
    for (auto it = Order.end();;)
    {
      if (Bytes + bytes <= Budget && place())
      {
        return true;
      }
      do
      {
        if (it == Order.begin())
        {
          return false;
        }
        --it;
      } while (it->LastFrame == Frame);
      Release(it->Item);
      Bytes -= it->Bytes;
      Entries.erase(it->Key);
      it = Order.erase(it);
      ++Evictions;
    }
  }

  /// Stores a value of `bytes` (pinned for this frame); the caller made room first.
  Value& Insert(std::uint32_t key, Value value, std::size_t bytes)
  {
    Order.push_front(Entry{ key, std::move(value), bytes, Frame });
    Entries[key] = Order.begin();
    Bytes += bytes;
    PinnedBytes += bytes;
    return Order.front().Item;
  }

  void Clear()
  {
    for (Entry& e : Order)
    {
      Release(e.Item);
    }
    Order.clear();
    Entries.clear();
    Bytes = 0;
    PinnedBytes = 0;
  }

  std::size_t GetBytes() const { return Bytes; }
  std::size_t GetCount() const { return Entries.size(); }
  std::uint64_t GetEvictions() const { return Evictions; }

private:
  struct Entry
  {
    std::uint32_t Key;
    Value Item;
    std::size_t Bytes;
    std::uint64_t LastFrame;
  };

  ReleaseFunction Release;
  std::list<Entry> Order; ///< most recently used first
  std::unordered_map<std::uint32_t, typename std::list<Entry>::iterator> Entries;
  std::size_t Budget = std::size_t(512) << 20;
  std::size_t Bytes = 0;
  std::size_t PinnedBytes = 0; ///< of the entries used by this frame
  std::uint64_t Frame = 1;
  std::uint64_t Evictions = 0;
};

} // namespace atp

#endif
