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

struct Batch
{
  std::vector<SoupTriangle> Triangles = std::vector<SoupTriangle>(BatchTriangles);
  /// Computed by the reading thread, which has time to spare.
  std::unique_ptr<double[][3]> Centroids = std::make_unique<double[][3]>(BatchTriangles);
  std::size_t Count = 0;
};
} // namespace

std::unique_ptr<Partitioner> PartitionStream(TriangleSource& source,
  const PartitionOptions& options, const std::function<void(std::uint64_t)>& progress)
{
  auto partitioner = std::make_unique<Partitioner>(source.Bounds(), options);
  std::uint64_t done = 0;
  ProduceConsume<Batch>(
    BatchCount,
    [&](Batch& batch) {
      batch.Count = source.Read(batch.Triangles.data(), batch.Triangles.size());
      for (std::size_t i = 0; i < batch.Count; ++i)
      {
        partitioner->Centroid(batch.Triangles[i], batch.Centroids[i]);
      }
      return batch.Count > 0;
    },
    [&](Batch& batch) {
      partitioner->Insert(batch.Triangles.data(), batch.Centroids.get(), batch.Count);
      done += batch.Count;
      progress(done);
    });
  return partitioner;
}

} // namespace atp
