// A patch: the indexed triangles one tetrahedron of the hierarchy holds, in full precision.
// The common currency of simplification, encoding and extraction. Plain C++: no VTK types.
#ifndef atpPatchMesh_h
#define atpPatchMesh_h

#include <cstddef>
#include <cstdint>
#include <vector>

namespace atp
{

/// PatchMesh::InputUses and CornerUses saturate here.
constexpr std::uint8_t ManyInputUses = 255;

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
  /// Both empty, or InputUses per vertex and CornerUses per corner (three per triangle):
  /// InputUses counts the input's triangles that use the vertex, up to ManyInputUses (that many
  /// or more; 0: not counted); CornerUses counts the input triangles at a corner's vertex that
  /// the triangle stands for. A leaf's triangles stand for themselves (1 each); a triangle a
  /// collapse removes hands its counts to the neighbor that takes its edge over, so they stay
  /// with the sheet they came from. Reading finds edges used an odd number of times only: an
  /// edge of four sheets, two in this patch, looks like an inner edge here while the other two
  /// lie in another patch, and there its vertices' counts fall short (VerticesUsedElsewhere).
  std::vector<std::uint8_t> InputUses;
  std::vector<std::uint8_t> CornerUses;

  std::size_t VertexCount() const { return Positions.size() / 3; }
  std::size_t TriangleCount() const { return Indices.size() / 3; }
  bool HasColors() const { return !Colors.empty(); }
  /// Whether InputUses and CornerUses are both empty or sized per vertex and per corner.
  bool UsesSized() const
  {
    return InputUses.empty() ? CornerUses.empty()
                             : InputUses.size() == VertexCount() && CornerUses.size() == Indices.size();
  }
};

/// Per vertex of `mesh`: 1 when input triangles of the vertex lie outside this patch (its
/// corners stand for fewer than InputUses) or cannot be told (ManyInputUses). Such a vertex on a
/// fan that looks whole here has more sheets elsewhere: it never moves, and is stored exactly
/// like a patch's border, or the sheets would part. Empty when the input's uses were not
/// counted.
inline std::vector<std::uint8_t> VerticesUsedElsewhere(const PatchMesh& mesh)
{
  std::vector<std::uint8_t> elsewhere;
  if (mesh.InputUses.empty())
  {
    return elsewhere;
  }
  std::vector<std::uint32_t> here(mesh.VertexCount(), 0);
  for (std::size_t c = 0; c < mesh.CornerUses.size(); ++c)
  {
    here[mesh.Indices[c]] += mesh.CornerUses[c];
  }
  elsewhere.resize(here.size());
  for (std::size_t v = 0; v < here.size(); ++v)
  {
    const std::uint8_t all = mesh.InputUses[v];
    elsewhere[v] = std::uint8_t(all != 0 && (all == ManyInputUses || here[v] < all));
  }
  return elsewhere;
}

} // namespace atp

#endif
