// Byte ranges of one growable GPU buffer: where the mapper's cache keeps every patch, so that a
// frame binds one vertex layout and draws all of its patches with one call per index type
// instead of binding buffers patch by patch. Plain C++: the mapper owns the buffer itself.
#ifndef atpBufferArena_h
#define atpBufferArena_h

#include <cstddef>
#include <map>
#include <optional>

namespace atp
{

class BufferArena
{
public:
  /// Ranges start at multiples of `alignment` (the vertex stride, so that a patch's first vertex
  /// is a whole vertex index into the buffer) and are rounded up to one.
  explicit BufferArena(std::size_t alignment);

  /// Offset of a free range of `bytes` (rounded up), taken from the smallest free range that
  /// holds it (best fit keeps large ranges for large patches); none when no free range does.
  std::optional<std::size_t> Allocate(std::size_t bytes);
  /// Returns the range Allocate gave for `bytes`, joining it with free neighbours.
  void Free(std::size_t offset, std::size_t bytes);
  /// The buffer grew to `capacity` bytes (not less than now): the new end is free.
  void Grow(std::size_t capacity);
  /// Everything is free again, in a buffer of `capacity` bytes.
  void Reset(std::size_t capacity);

  std::size_t Rounded(std::size_t bytes) const;
  std::size_t GetCapacity() const { return Capacity; }
  std::size_t GetUsedBytes() const { return Used; }
  std::size_t GetAlignment() const { return Alignment; }

private:
  std::size_t Alignment;
  std::size_t Capacity = 0;
  std::size_t Used = 0;
  std::map<std::size_t, std::size_t> FreeRanges; ///< offset -> size, never adjacent
  std::multimap<std::size_t, std::size_t> BySize; ///< the same ranges: size -> offset

  void AddFree(std::size_t offset, std::size_t size);
  void RemoveFree(std::map<std::size_t, std::size_t>::iterator range);
};

} // namespace atp

#endif
