// Construction of the multiresolution model from a partitioned mesh (paper, section 5.2):
// bottom-up, level by level, every diamond merges its children's patches, simplifies them with
// its external boundary locked and one quota per member, and gets saturated errors and bounds;
// every patch is encoded, and the nodes and patches are written to one .atp file.
#ifndef atpConstruction_h
#define atpConstruction_h

#include "atpPartitioner.h"
#include "atpPatchCodec.h"
#include "vtkATPFiltersModule.h"

#include <cstdint>
#include <functional>
#include <string>

namespace atp
{

class PatchJobRunner;

struct ConstructionOptions
{
  /// Most triangles a tetrahedron of a simplified level holds (paper: a few thousand).
  std::uint32_t PatchBudget = 2000;
  int Threads = 0; ///< 0: every core
  /// Where the leaf and diamond jobs run; null: on Threads threads of this process.
  PatchJobRunner* Runner = nullptr;
  std::string ScratchDirectory;
  /// Stored in the model: screen-space error = ErrorScale * projected object-space error.
  float ErrorScale = 1;
  /// How patches order their triangles for the vertex cache (ModelFlagFastCacheOrder).
  CacheOrder Order = CacheOrder::Best;
};

/// CPU seconds by step of construction. The jobs' steps are summed over every job, wherever it
/// ran (threads of this process or MPI workers). Loading jobs runs where the runner loads them
/// (each thread of this process its own jobs; an MPI coordinator all); the others on the calling
/// thread.
struct ConstructionCpuSeconds
{
  double LeafWeld = 0;        ///< buckets welded into indexed patches
  double LeafEncode = 0;      ///< leaves encoded, with their spheres and cones
  double DiamondMerge = 0;    ///< the children's patches merged
  double DiamondSimplify = 0;
  double DiamondEncode = 0;   ///< simplified patches encoded, with their spheres and cones
  double LoadJobs = 0;        ///< reading the jobs' buckets and waiting patches
  /// Storing the patches in scratch files, saturating bounds, reporting progress.
  double StoreResults = 0;
  double WriteModel = 0;      ///< the model file, from the scratch files
};

struct ConstructionStats
{
  std::uint64_t Nodes = 0;
  std::uint64_t Diamonds = 0;          ///< simplified diamonds
  std::uint64_t StoredTriangles = 0;   ///< over all levels
  std::uint64_t Collapses = 0;
  /// Diamonds where locked or topologically constrained geometry kept the members above their
  /// quotas (QuotasOf: half of what their children hold in all, often well under the budget;
  /// kept, not fatal).
  std::uint64_t QuotaMisses = 0;
  std::uint64_t TrianglesOverQuotas = 0; ///< above the diamonds' quotas, summed
  /// Pieces (an isosurface's specks, separate triangles) removed whole where no collapse was
  /// left (Simplify).
  std::uint64_t PiecesRemoved = 0;
  /// Diamonds whose triangles face either way at random (SimplifyResult::FacingAtRandom): the
  /// input is not wound consistently, and its model shades speckled.
  std::uint64_t DiamondsFacingAtRandom = 0;
  /// Copies of an input triangle dropped from its leaf (WeldSoup); the model's InputTriangles
  /// leaves them out.
  std::uint64_t RepeatedTrianglesDropped = 0;
  /// Simplified patches above the patch budget, the renderer's unit of work (leaves hold up to
  /// the leaf capacity instead).
  std::uint64_t SimplifiedPatchesOverBudget = 0;
  std::uint64_t PatchBytes = 0;        ///< encoded patches
  std::uint64_t FileBytes = 0;
  std::uint64_t PeakScratchBytes = 0;  ///< intermediate patches and encoded patches on disk
  double CoarsestError = 0;            ///< saturated object-space error of the roots
  int Depth = 0;
  ConstructionCpuSeconds Cpu;
};

/// Called with the fraction done; it may throw to cancel (nothing is written then).
using ConstructionProgress = std::function<void(double fraction)>;

/// Builds the model and writes it to `outputPath` (atomically: a temporary file renamed at the
/// end). Consumes the partition's buckets. Throws std::runtime_error on failure.
VTKATPFILTERS_EXPORT ConstructionStats BuildModel(Partitioner& partition, const Box& bounds,
  const InputStats& input, const ConstructionOptions& options, const std::string& outputPath,
  const ConstructionProgress& progress = {});

} // namespace atp

#endif
