// Joins the patches of a diamond's children into one indexed mesh for simplification.
#ifndef atpMergePatches_h
#define atpMergePatches_h

#include "atpPatchMesh.h"
#include "vtkATPFiltersModule.h"

#include <cstdint>
#include <vector>

namespace atp
{

/// Numbers vertices by their exact position: the first vertex seen at a position (bit for bit)
/// stands for every later one there. Open addressing on the position bits; the table is only
/// looked up, so its layout cannot influence the numbering.
class VTKATPFILTERS_EXPORT PositionWelder
{
public:
  /// For at most `maxVertices` distinct positions, stored in `positions` (room for 3 *
  /// maxVertices floats) in the order they are first seen.
  PositionWelder(std::size_t maxVertices, float* positions);

  /// The number of the vertex at p; `added` tells whether it is new (its position then stored,
  /// numbered after all earlier ones). Throws std::logic_error rather than write past the
  /// room for maxVertices.
  std::uint32_t Weld(const float p[3], bool& added);
  /// Distinct positions seen so far.
  std::size_t Count() const { return Vertices; }

private:
  float* Positions;
  std::size_t MaxVertices;
  std::size_t Vertices = 0;
  std::vector<std::uint32_t> Slots; ///< vertex number + 1; 0 is empty
  std::size_t Mask = 0;
};

/// Concatenates the patches in order and welds vertices whose positions are bit-identical (the
/// first one's normal and color are kept: shared vertices carry the same attributes in every
/// patch). Triangles that the weld makes degenerate (a repeated corner) are dropped. Missing
/// BoundaryEdges read as 0; where only some patches have normals (colors), the others get +z
/// (opaque white).
/// Deterministic: the output depends only on the patches and their order. When
/// `trianglePatch` is given, it receives the index in `patches` of every output triangle.
VTKATPFILTERS_EXPORT PatchMesh MergePatches(const std::vector<const PatchMesh*>& patches,
  std::vector<std::uint32_t>* trianglePatch = nullptr);

} // namespace atp

#endif
