// What `atp verify` checks of a model's bounds beyond what opening it checks (the file's
// structure) and the checksums: what each node says of its patch, against the decoded patch,
// and the saturation over diamonds and down the tree (docs/atp-format.md). A sphere or cone that
// misses part of its patch culls visible triangles; saturated values that differ within a
// diamond, or a saturated sphere that does not nest in its parent's, break the cut.
#ifndef atpModelBoundsCheck_h
#define atpModelBoundsCheck_h

#include "atpCutIndex.h"
#include "atpModelFile.h"
#include "atpPatchMesh.h"
#include "vtkATPFiltersModule.h"

#include <string>
#include <vector>

namespace atp
{

/// Node `i` of a model with `header` against its decoded patch: the node's triangle and vertex
/// counts are the patch's, the patch has colors as the header says, the node's sphere holds every vertex, its
/// cone (a unit axis, unless it holds every direction) every face normal (degenerate faces
/// aside) and its saturated sphere its sphere. Each problem reads "node I: what is wrong"; at
/// most one of each kind.
VTKATPFILTERS_EXPORT std::vector<std::string> PatchProblems(
  const ModelHeader& header, std::size_t i, const ModelNode& node, const PatchMesh& patch);

/// Every diamond's members (`diamonds`, built from `model`) hold one saturated error and one
/// saturated sphere, and a node's saturated sphere lies within its parent's. Each problem reads
/// "node I: what is wrong".
VTKATPFILTERS_EXPORT std::vector<std::string> SaturationProblems(
  const ModelFile& model, const CutIndex& diamonds);

} // namespace atp

#endif
