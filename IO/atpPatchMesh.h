// A patch: the indexed triangles one tetrahedron of the hierarchy holds, in full precision.
// The common currency of simplification, encoding and extraction. Plain C++: no VTK types.
#ifndef atpPatchMesh_h
#define atpPatchMesh_h

#include <cstddef>
#include <cstdint>
#include <vector>

namespace atp
{

struct PatchMesh
{
  std::vector<float> Positions;        ///< x, y, z per vertex (input coordinates)
  std::vector<float> Normals;          ///< unit x, y, z per vertex
  std::vector<std::uint8_t> Colors;    ///< r, g, b, a per vertex, or empty when the input has none
  std::vector<std::uint32_t> Indices;  ///< three per triangle
  /// Per triangle, bit i: the edge from corner i to corner (i+1)%3 is a boundary edge of the
  /// input mesh (not a border between patches); bit 3 + i: an edge of three or more triangles
  /// of the input, whose ends never move (SoupTriangle::BoundaryEdges). Kept through
  /// simplification.
  std::vector<std::uint8_t> BoundaryEdges;

  std::size_t VertexCount() const { return Positions.size() / 3; }
  std::size_t TriangleCount() const { return Indices.size() / 3; }
  bool HasColors() const { return !Colors.empty(); }
};

} // namespace atp

#endif
