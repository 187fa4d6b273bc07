// The simplifier's collapse queues: one min-queue per region, each vertex waiting in at most
// one of them with one key that changes in place. A queue of superseded entries (pushed again
// at every re-pricing, skipped when popped) held about as many stale entries as live ones.
// Plain C++, header only.
#ifndef atpCollapseQueues_h
#define atpCollapseQueues_h

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace atp
{

class CollapseQueues
{
public:
  struct Entry
  {
    double Cost;
    std::uint32_t Vertex;
  };

  /// The order of every queue: cheapest first, ties by vertex. Bitwise rather than
  /// short-circuit: sifting compares siblings in an order no branch predictor learns.
  static bool Before(const Entry& a, const Entry& b)
  {
    return (a.Cost < b.Cost) | ((a.Cost == b.Cost) & (a.Vertex < b.Vertex));
  }

  CollapseQueues(std::size_t queueCount, std::size_t vertexCount)
    : Heaps(queueCount)
    , Slot(vertexCount, Absent)
    , QueueOf(vertexCount, 0)
  {
  }

  /// Until Order(), Set only appends: the first keys of all vertices are heaped at once, in
  /// linear time.
  void Order()
  {
    Ordered = true;
    for (std::vector<Entry>& heap : Heaps)
    {
      for (std::size_t i = heap.size() / 2; i-- > 0;)
      {
        SiftDown(heap, i);
      }
    }
  }

  /// Queues `vertex` in `queue` with `cost`, leaving the queue it waited in, if another.
  void Set(std::uint32_t vertex, std::size_t queue, double cost)
  {
    if (Slot[vertex] != Absent && QueueOf[vertex] != queue)
    {
      Remove(vertex);
    }
    std::vector<Entry>& heap = Heaps[queue];
    if (Slot[vertex] == Absent)
    {
      QueueOf[vertex] = std::uint32_t(queue);
      Slot[vertex] = std::uint32_t(heap.size());
      heap.push_back({ cost, vertex });
      if (Ordered)
      {
        SiftUp(heap, heap.size() - 1);
      }
      return;
    }
    const std::size_t i = Slot[vertex];
    const Entry old = heap[i];
    heap[i].Cost = cost;
    if (!Ordered)
    {
      return;
    }
    if (Before(heap[i], old))
    {
      SiftUp(heap, i);
    }
    else
    {
      SiftDown(heap, i);
    }
  }

  /// Takes `vertex` out of its queue, if it waits in one.
  void Remove(std::uint32_t vertex)
  {
    const std::uint32_t i = Slot[vertex];
    if (i == Absent)
    {
      return;
    }
    std::vector<Entry>& heap = Heaps[QueueOf[vertex]];
    Slot[vertex] = Absent;
    const Entry last = heap.back();
    heap.pop_back();
    if (i == heap.size())
    {
      return;
    }
    heap[i] = last;
    Slot[last.Vertex] = i;
    if (Ordered)
    {
      if (i > 0 && Before(last, heap[(i - 1) / 2]))
      {
        SiftUp(heap, i);
      }
      else
      {
        SiftDown(heap, i);
      }
    }
  }

  bool Empty(std::size_t queue) const { return Heaps[queue].empty(); }
  /// The cheapest entry of a queue that is not empty (after Order()).
  const Entry& Front(std::size_t queue) const { return Heaps[queue].front(); }
  bool Queued(std::uint32_t vertex) const { return Slot[vertex] != Absent; }

private:
  static constexpr std::uint32_t Absent = ~0u;

  void Place(std::vector<Entry>& heap, std::size_t i, const Entry& entry)
  {
    heap[i] = entry;
    Slot[entry.Vertex] = std::uint32_t(i);
  }

  void SiftUp(std::vector<Entry>& heap, std::size_t i)
  {
    const Entry entry = heap[i];
    while (i > 0)
    {
      const std::size_t parent = (i - 1) / 2;
      if (!Before(entry, heap[parent]))
      {
        break;
      }
      Place(heap, i, heap[parent]);
      i = parent;
    }
    Place(heap, i, entry);
  }

  void SiftDown(std::vector<Entry>& heap, std::size_t i)
  {
    const Entry entry = heap[i];
    const std::size_t n = heap.size();
    for (std::size_t child = 2 * i + 1; child < n; child = 2 * i + 1)
    {
      // The smaller child, without a branch on which it is.
      child += std::size_t(child + 1 < n && Before(heap[child + 1], heap[child]));
      if (!Before(heap[child], entry))
      {
        break;
      }
      Place(heap, i, heap[child]);
      i = child;
    }
    Place(heap, i, entry);
  }

  std::vector<std::vector<Entry>> Heaps;
  std::vector<std::uint32_t> Slot;    ///< per vertex: its index in its queue's heap, or Absent
  std::vector<std::uint32_t> QueueOf; ///< per vertex: the queue it waits in (when queued)
  bool Ordered = false;
};

} // namespace atp

#endif
