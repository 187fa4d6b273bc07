// Triangles of indexed meshes for tests, compared by their corners' exact positions: two meshes
// hold the same triangles whatever their vertex numbering and triangle order.
#ifndef atpTestMeshTriangles_h
#define atpTestMeshTriangles_h

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

namespace atp
{
namespace test
{
using CornerBits = std::array<std::uint32_t, 3>; ///< float bits of a position
using TriangleBits = std::array<CornerBits, 3>;

inline CornerBits Bits(const float* p)
{
  CornerBits c;
  std::memcpy(c.data(), p, sizeof(c));
  return c;
}

/// Each triangle as its corners' float bits, rotated to start at the smallest (keeps winding),
/// sorted.
inline std::vector<TriangleBits> TriangleSet(
  const std::vector<float>& positions, const std::vector<std::uint32_t>& indices)
{
  std::vector<TriangleBits> set;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
  {
    TriangleBits tri;
    for (std::size_t c = 0; c < 3; ++c)
    {
      tri[c] = Bits(&positions[3 * std::size_t(indices[t + c])]);
    }
    std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
    set.push_back(tri);
  }
  std::sort(set.begin(), set.end());
  return set;
}

} // namespace test
} // namespace atp

#endif
