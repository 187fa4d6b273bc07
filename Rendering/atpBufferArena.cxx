#include "atpBufferArena.h"

#include <iterator>
#include <stdexcept>

namespace atp
{

BufferArena::BufferArena(std::size_t alignment)
  : Alignment(alignment)
{
  if (alignment == 0)
  {
    throw std::invalid_argument("BufferArena: alignment must be positive");
  }
}

std::size_t BufferArena::Rounded(std::size_t bytes) const
{
  return (bytes + Alignment - 1) / Alignment * Alignment;
}

void BufferArena::AddFree(std::size_t offset, std::size_t size)
{
  FreeRanges.emplace(offset, size);
  BySize.emplace(size, offset);
}

void BufferArena::RemoveFree(std::map<std::size_t, std::size_t>::iterator range)
{
  auto bySize = BySize.lower_bound(range->second);
  while (bySize->second != range->first)
  {
    ++bySize;
  }
  BySize.erase(bySize);
  FreeRanges.erase(range);
}

std::optional<std::size_t> BufferArena::Allocate(std::size_t bytes)
{
  const std::size_t size = Rounded(bytes == 0 ? 1 : bytes);
  const auto best = BySize.lower_bound(size);
  if (best == BySize.end())
  {
    return std::nullopt;
  }
  const std::size_t offset = best->second;
  const std::size_t rest = best->first - size;
  RemoveFree(FreeRanges.find(offset));
  if (rest > 0)
  {
    AddFree(offset + size, rest);
  }
  Used += size;
  return offset;
}

void BufferArena::Free(std::size_t offset, std::size_t bytes)
{
  std::size_t size = Rounded(bytes == 0 ? 1 : bytes);
  Used -= size;
  const auto next = FreeRanges.lower_bound(offset);
  if (next != FreeRanges.begin())
  {
    const auto previous = std::prev(next);
    if (previous->first + previous->second == offset)
    {
      offset = previous->first;
      size += previous->second;
      RemoveFree(previous);
    }
  }
  const auto following = FreeRanges.find(offset + size);
  if (following != FreeRanges.end())
  {
    size += following->second;
    RemoveFree(following);
  }
  AddFree(offset, size);
}

void BufferArena::Grow(std::size_t capacity)
{
  capacity = capacity / Alignment * Alignment;
  if (capacity <= Capacity)
  {
    return;
  }
  const std::size_t oldCapacity = Capacity;
  Capacity = capacity;
  Used += capacity - oldCapacity; // Free below takes the new part off again
  Free(oldCapacity, capacity - oldCapacity);
}

void BufferArena::Reset(std::size_t capacity)
{
  FreeRanges.clear();
  BySize.clear();
  Capacity = 0;
  Used = 0;
  Grow(capacity);
}

} // namespace atp
