// The diamond cut (paper, section 4): a stateless top-down traversal of the node forest that
// refines a node while its saturated error, seen from the viewer, exceeds the tolerance. Errors
// and spheres are saturated (equal over a diamond, monotone down the tree), so the nodes kept
// always form whole diamonds: a conforming, crack-free cut. Plain C++: no VTK, no OpenGL.
#ifndef atpCut_h
#define atpCut_h

#include "atpModelFile.h"
#include "atpPatchMesh.h"
#include "vtkATPFiltersModule.h"

#include <cstdint>
#include <vector>

namespace atp
{

/// A perspective viewer, as far as the error test needs one.
struct ViewPoint
{
  double Eye[3] = { 0, 0, 0 };
  double ViewAngleDegrees = 30;   ///< vertical field of view
  double ViewportHeight = 600;    ///< pixels
  double TolerancePixels = 1;
};

/// Pixels that an object-space error at the nearest point of the node's saturated sphere
/// covers on screen (scaled by the model's calibrated ErrorScale); infinite when the eye is
/// inside the sphere, so nodes around the viewer always refine.
VTKATPFILTERS_EXPORT double ProjectedError(
  const ModelNode& node, const ViewPoint& view, double errorScale);

/// Indices of the nodes of the cut for `view`, in traversal order.
VTKATPFILTERS_EXPORT std::vector<std::uint32_t> SelectCut(
  const ModelFile& model, const ViewPoint& view);

/// The same with `errorScale` in place of the model's own ErrorScale (to calibrate it).
VTKATPFILTERS_EXPORT std::vector<std::uint32_t> SelectCut(
  const ModelFile& model, const ViewPoint& view, double errorScale);

/// The cut made of every node at `level`, plus the leaves above it.
VTKATPFILTERS_EXPORT std::vector<std::uint32_t> SelectLevel(const ModelFile& model, int level);

/// Decodes the nodes' patches (each checked against its checksum first) into one mesh, with
/// vertices shared between patches welded by their bit-identical positions. Throws ModelError
/// or PatchFormatError for corrupt data.
VTKATPFILTERS_EXPORT PatchMesh ExtractCut(
  const ModelFile& model, const std::vector<std::uint32_t>& nodes);

} // namespace atp

#endif
