// Joins the patches of a diamond's children into one indexed mesh for simplification.
#ifndef atpMergePatches_h
#define atpMergePatches_h

#include "atpPatchMesh.h"
#include "atpPositionWelder.h"
#include "vtkATPFiltersModule.h"

#include <cstdint>
#include <vector>

namespace atp
{

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
