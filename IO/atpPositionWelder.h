// Welding by exact position in memory: the first vertex seen at a position (bit for bit)
// stands for every later one there. Used where patches are joined (MergePatches, a leaf's
// bucket) and, bucket by bucket, by the out-of-core CornerWelder.
#ifndef atpPositionWelder_h
#define atpPositionWelder_h

#include "vtkATPIOModule.h" // export macro

#include <cstdint>
#include <cstring>
#include <vector>

namespace atp
{

/// A position's bits with -0 read as +0 (the same point): the key positions are welded and
/// counted by.
inline void PositionBits(const float p[3], std::uint32_t out[3])
{
  for (int a = 0; a < 3; ++a)
  {
    const float coordinate = p[a] + 0.0f; // -0 + 0 is +0
    std::memcpy(&out[a], &coordinate, sizeof(float));
  }
}

/// A hash of a position's bits: PositionWelder's slots take its low bits, CornerWelder's buckets
/// its high ones.
inline std::uint64_t PositionHash(const std::uint32_t bits[3])
{
  std::uint64_t h = bits[0] * 0x9E3779B97F4A7C15ull;
  h ^= (h >> 29) ^ (bits[1] * 0xC2B2AE3D27D4EB4Full);
  h ^= (h >> 31) ^ (bits[2] * 0x165667B19E3779F9ull);
  return h ^ (h >> 32);
}

/// Numbers vertices by their exact position. Open addressing on the position bits; the table is
/// only looked up, so its layout cannot influence the numbering.
class VTKATPIO_EXPORT PositionWelder
{
public:
  /// For at most `maxVertices` distinct positions, stored in `positions` (room for 3 *
  /// maxVertices floats) in the order they are first seen.
  PositionWelder(std::size_t maxVertices, float* positions);
  /// Forgets every position, for at most `maxVertices` more in `positions`; the table's memory
  /// is kept for the next ones.
  void Reset(std::size_t maxVertices, float* positions);

  /// The number of the vertex at p; `added` tells whether it is new (its position then stored,
  /// numbered after all earlier ones). Throws std::logic_error rather than write past the
  /// room for maxVertices.
  std::uint32_t Weld(const float p[3], bool& added);
  /// Distinct positions seen so far.
  std::size_t Count() const { return Vertices; }

private:
  float* Positions = nullptr;
  std::size_t MaxVertices = 0;
  std::size_t Vertices = 0;
  std::vector<std::uint32_t> Slots; ///< vertex number + 1; 0 is empty
  std::size_t Mask = 0;
};

} // namespace atp

#endif
