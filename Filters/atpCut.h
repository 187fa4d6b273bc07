// The diamond cut (paper, section 4): a stateless top-down traversal of the node forest that
// culls branches outside the view frustum or facing away, and refines a node while its
// saturated error, seen from the viewer, exceeds the tolerance. Errors and spheres are
// saturated (equal over a diamond, monotone down the tree), so the nodes kept always form
// whole diamonds: a conforming, crack-free cut. Plain C++: no VTK, no OpenGL.
#ifndef atpCut_h
#define atpCut_h

#include "atpCutIndex.h"
#include "atpModelFile.h"
#include "atpPatchMesh.h"
#include "vtkATPFiltersModule.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace atp
{

/// A viewer, as far as the cut needs one. Coordinates are the model's own.
struct ViewPoint
{
  double Eye[3] = { 0, 0, 0 };
  double ViewAngleDegrees = 30;   ///< vertical field of view (perspective)
  double ViewportHeight = 600;    ///< pixels
  double TolerancePixels = 1;
  /// Parallel projection: the viewport shows 2 * ParallelScale units vertically, and
  /// Direction (unit, from the eye into the scene) is the direction of projection.
  bool Parallel = false;
  double ParallelScale = 1;
  double Direction[3] = { 0, 0, -1 };
  /// Frustum planes, inside where a*x + b*y + c*z + d >= 0 with (a, b, c) of unit length.
  /// None: nothing is culled by the frustum.
  int PlaneCount = 0;
  double Planes[6][4] = {};
  /// Drop patches (and branches) whose every normal faces away from the eye. Only for closed,
  /// one-sided surfaces.
  bool BackfaceCulling = false;
  /// The view is in the model's coordinates, which the actor's matrix may stretch unevenly
  /// (a scale of 1, 1, 0.1; a shear): Linear, row-major, is that matrix's linear part (model
  /// vectors to the camera's units), and Stretch the most it lengthens a vector (its largest
  /// singular value). Errors and distances are measured in the camera's units: an error across
  /// the squashed axis, seen from far along it, is not its model-space size over a model-space
  /// distance.
  double Linear[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  double Stretch = 1;
};

/// Whether two views ask for the same cut (same eye, planes, projection and tolerance).
VTKATPFILTERS_EXPORT bool SameView(const ViewPoint& a, const ViewPoint& b);

/// True when the sphere (center, radius) lies entirely outside one of the view's planes.
VTKATPFILTERS_EXPORT bool OutsideFrustum(const float sphere[4], const ViewPoint& view);

/// True when every normal of `cone`, at every point of the sphere, faces away from the eye.
VTKATPFILTERS_EXPORT bool FacesAway(
  const CullingCone& cone, const float sphere[4], const ViewPoint& view);

/// One cut: what to draw and what is missing to draw the cut the view asks for.
struct CutResult
{
  std::vector<std::uint32_t> Drawn;   ///< visible, non-empty patches, in traversal order
  /// Patches the view needs that are not resident, coarser first: a node whose diamond would
  /// refine waits (and is drawn) until all the children of all its diamond's members are.
  std::vector<std::uint32_t> Missing;
  /// Resident patches such a waiting diamond will need: keep them loaded.
  std::vector<std::uint32_t> Held;
  std::size_t Visited = 0;            ///< nodes the traversal looked at
  bool Complete() const { return Missing.empty(); }
};

/// Tells whether a node's patch can be drawn now (loaded, decoded, uploaded: the caller's
/// business). Empty patches should always count as resident.
using ResidentFunction = std::function<bool(std::uint32_t node)>;

/// Selects cuts of one model, frame after frame. Holds scratch memory, so one per thread;
/// the CutIndex may be shared.
class VTKATPFILTERS_EXPORT CutSelector
{
public:
  CutSelector(const ModelFile& model, std::shared_ptr<const CutIndex> index);

  /// The cut for `view`. With `resident` (may be empty: everything is resident), a diamond
  /// refines only when all its children are resident and every diamond above it refines, so
  /// the cut stays conforming while patches load.
  void Select(const ViewPoint& view, double errorScale, const ResidentFunction& resident,
    CutResult& out);

  const CutIndex& Index() const { return *IndexRef; }

private:
  bool Refines(std::uint32_t diamond);
  /// Records a patch the cut needs, in Missing or Held, once per call; returns whether it is
  /// resident.
  bool Need(std::uint32_t node);

  const ModelFile& Model;
  std::shared_ptr<const CutIndex> IndexRef;
  // Per call: the view, and a memo of refinement decisions per diamond, valid where stamped.
  const ViewPoint* View = nullptr;
  double ErrorFactor = 1; ///< error scale times pixels per unit
  const ResidentFunction* Resident = nullptr;
  CutResult* Out = nullptr;
  std::uint32_t Stamp = 0;
  std::vector<std::uint32_t> DecisionStamp;
  std::vector<std::uint8_t> Decision;
  std::vector<std::uint32_t> NeedStamp;
  std::vector<std::uint32_t> Stack;
};

/// The full cut for `view` (no residency limit) with the model's ErrorScale. Builds a
/// CutIndex: for one-off cuts (a CutSelector serves many).
VTKATPFILTERS_EXPORT std::vector<std::uint32_t> SelectCut(
  const ModelFile& model, const ViewPoint& view);

/// The cut made of every node at `level`, plus the leaves above it.
VTKATPFILTERS_EXPORT std::vector<std::uint32_t> SelectLevel(const ModelFile& model, int level);

/// Decodes the nodes' patches (each checked against its checksum first) into one mesh, with
/// vertices shared between patches welded by their bit-identical positions. When
/// `trianglePatch` is given, it receives for every output triangle the position in `nodes` of
/// the patch it came from. Throws ModelError or PatchFormatError for corrupt data.
VTKATPFILTERS_EXPORT PatchMesh ExtractCut(const ModelFile& model,
  const std::vector<std::uint32_t>& nodes, std::vector<std::uint32_t>* trianglePatch = nullptr);

} // namespace atp

#endif
