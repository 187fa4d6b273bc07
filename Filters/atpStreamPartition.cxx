#include "atpStreamPartition.h"

#include "atpProduceConsume.h"

#include <memory>
#include <vector>

namespace atp
{
namespace
{
constexpr std::size_t BatchTriangles = 1 << 16;
constexpr std::size_t BatchCount = 3;
/// Triangles the reading thread locates between two releases of its forest's pages.
constexpr std::uint64_t ReleaseInterval = std::uint64_t(1) << 20;

struct Batch
{
  std::vector<SoupTriangle> Triangles = std::vector<SoupTriangle>(BatchTriangles);
  /// The centroids and a node holding each, found by the reading thread, which has time to
  /// spare (the inserting one is the partitioning's bottleneck).
  std::unique_ptr<double[][3]> Centroids = std::make_unique<double[][3]>(BatchTriangles);
  std::vector<TetraForest::NodeIndex> Located = std::vector<TetraForest::NodeIndex>(BatchTriangles);
  std::size_t Count = 0;
  /// The splits inserting this batch made, for the reading thread to replay when the batch
  /// comes back to be refilled (batches come back in the order they were filled).
  std::vector<TetraForest::NodeIndex> Splits;
};
} // namespace

std::unique_ptr<Partitioner> PartitionStream(TriangleSource& source,
  const PartitionOptions& options, const std::function<void(std::uint64_t)>& progress)
{
  auto partitioner = std::make_unique<Partitioner>(source.Bounds(), options);
  // The reading thread's own copy of the forest, the inserting thread's as it stood a batch or
  // two ago: nothing the threads share changes under either.
  TetraForest copy(options.ScratchDirectory);
  TetraForest::LeafHint hint;
  const auto replay = [](TetraForest::NodeIndex) {};
  std::uint64_t located = 0, nextRelease = ReleaseInterval;
  std::uint64_t done = 0;
  ProduceConsume<Batch>(
    BatchCount,
    [&](Batch& batch) {
      for (const TetraForest::NodeIndex leaf : batch.Splits)
      {
        copy.SplitDiamond(leaf, replay);
      }
      batch.Splits.clear();
      batch.Count = source.Read(batch.Triangles.data(), batch.Triangles.size());
      for (std::size_t i = 0; i < batch.Count; ++i)
      {
        partitioner->Centroid(batch.Triangles[i], batch.Centroids[i]);
      }
      copy.LeavesContaining(batch.Centroids.get(), batch.Located.data(), batch.Count, hint);
      located += batch.Count;
      if (located >= nextRelease)
      {
        copy.ReleaseResident();
        nextRelease = located + ReleaseInterval;
      }
      return batch.Count > 0;
    },
    [&](Batch& batch) {
      partitioner->Insert(batch.Triangles.data(), batch.Centroids.get(), batch.Located.data(),
        batch.Count, batch.Splits);
      done += batch.Count;
      progress(done);
    });
  partitioner->SetBoundaryCheck(source.BoundaryCheck());
  return partitioner;
}

} // namespace atp
