// The unit of construction work (paper 5.2): one leaf's triangles welded into its patch, or one
// diamond's children's patches merged and simplified into its members' patches, each patch
// encoded with its tight sphere and normal cone. A job is a pure function of its inputs and the
// build's context, so it runs the same on a thread or on another machine (atpPatchJobRunner.h),
// and the model is byte-identical wherever its jobs ran.
#ifndef atpPatchJob_h
#define atpPatchJob_h

#include "atpBounds.h"
#include "atpPatchCodec.h"
#include "atpPatchMesh.h"
#include "atpQuantizationGrid.h"
#include "atpTetra.h"
#include "atpTriangleSource.h"
#include "vtkATPFiltersModule.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace atp
{

/// What every job of one build shares; it follows from the input bounds and three options,
/// which is all that travels to another process.
struct VTKATPFILTERS_EXPORT PatchJobContext
{
  PatchJobContext(const Box& bounds, std::uint32_t patchBudget, bool colors, CacheOrder order);

  Box Bounds;
  /// Most triangles a member of a simplified diamond keeps.
  std::uint32_t PatchBudget;
  /// Whether patches keep vertex colors (the input has them).
  bool Colors;
  /// How every patch's triangles are ordered for the vertex cache.
  CacheOrder Order;
  QuantizationGrid Grid; ///< the model's one position grid
  LatticeFrame Frame;    ///< the partition's lattice, which places points in members
};

/// A leaf job has no members: its soup is welded. A diamond job simplifies the children's
/// patches of its members (in TetId order; children in member order, then child order).
struct PatchJob
{
  std::vector<SoupTriangle> Soup;
  std::vector<Tetra> Members;
  std::vector<PatchMesh> Children;
  /// The largest error of the children: the merged input is already that far off the original.
  double ChildError = 0;

  bool IsLeaf() const { return Members.empty(); }
};

/// A finished patch: the full-precision mesh (the parent diamond's input) and its encoding,
/// with the sphere and cone of what a reader decodes.
struct MadePatch
{
  PatchMesh Mesh;
  std::vector<std::uint8_t> Encoded;
  Sphere Tight;
  NormalCone Cone;
};

/// CPU seconds a job spent in each of its steps, on the thread that ran it.
struct JobCpuSeconds
{
  double Prepare = 0;  ///< welding a leaf's bucket, or merging a diamond's children
  double Simplify = 0; ///< a diamond's simplification (0 for a leaf)
  double Encode = 0;   ///< encoding the patches, with their spheres and cones
};

/// One patch per member (a leaf: one), and the diamond's figures.
struct PatchJobResult
{
  std::vector<MadePatch> Patches;
  double Error = 0; ///< object-space error of the patches (0 for a leaf)
  std::uint64_t Collapses = 0;
  /// Triangles above the diamond's quotas (QuotasOf): see SimplifyResult.
  std::uint64_t TrianglesOverQuotas = 0;
  std::uint64_t PiecesRemoved = 0; ///< pieces removed whole: see Simplify
  /// The diamond's triangles face either way at random: see SimplifyResult.
  bool FacingAtRandom = false;
  /// A leaf's copies of a triangle (the same corners in the same order) it dropped: see WeldSoup.
  std::uint64_t RepeatedTrianglesDropped = 0;
  JobCpuSeconds Cpu;
};

/// What a diamond job's simplification keeps: each member at most the budget, and the members
/// together at most half of what their children hold, each member's half capped at the budget,
/// so that each level halves as each bisection halves the volume. The members share the
/// halving: a smooth member may give up more than half where a rough one keeps more, as one
/// simplification of the whole diamond would. (atp-bench-simplify gives the simplifiers a
/// build's diamonds with these.)
struct DiamondQuotas
{
  std::vector<std::uint32_t> Members; ///< the budget, per member
  std::uint64_t Total = 0;
};
VTKATPFILTERS_EXPORT DiamondQuotas QuotasOf(const PatchJob& job, std::uint32_t budget);

/// Runs one job, freeing its inputs as soon as they are merged. Throws std::exception on
/// failure (e.g. an inconsistent mesh).
VTKATPFILTERS_EXPORT PatchJobResult MakePatches(const PatchJobContext& context, PatchJob job);

} // namespace atp

#endif
