#include "atpVolumeTriangleSource.h"

#include "atpMeshTriangleSource.h"
#include "atpPolygonMesh.h"
#include "atpResidentPages.h"
#include "atpScratchArray.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace atp
{
namespace
{
/// The welded surface in scratch arrays that grow by doubling; as a PolygonMesh it serves the
/// triangles in batches straight from the array.
class ScratchSurface final
  : public PolygonMesh
  , public ContourSink
{
public:
  explicit ScratchSurface(const std::string& scratchDirectory)
    : Positions(scratchDirectory, InitialCapacity)
    , Corners(scratchDirectory, InitialCapacity)
    , TriangleSizes(PolygonBatchFaces, 3)
  {
  }

  void AddVertices(const float* xyz, std::size_t count) override
  {
    this->Append(this->Positions, this->PositionCount, xyz, 3 * count);
  }

  void AddTriangles(const std::uint32_t* corners, std::size_t count) override
  {
    this->Append(this->Corners, this->CornerCount, corners, 3 * count);
  }

  VertexView Vertices() const override
  {
    VertexView view;
    view.Base = reinterpret_cast<const unsigned char*>(this->Positions.Data());
    view.Count = this->PositionCount / 3;
    view.FileBacked = true;
    return view;
  }

  void Rewind() override { this->NextCorner = 0; }

  bool NextBatch(PolygonBatch& batch) override
  {
    if (this->NextCorner >= this->CornerCount)
    {
      return false;
    }
    // Pages of the batch before last stay cached but leave the process (bounded memory).
    const std::size_t batchCorners = 3 * PolygonBatchFaces;
    if (this->NextCorner >= 2 * batchCorners)
    {
      ReleaseResidentPages(this->Corners.Data() + this->NextCorner - 2 * batchCorners,
        batchCorners * sizeof(std::uint32_t));
    }
    batch.Indices = this->Corners.Data() + this->NextCorner;
    batch.Sizes = this->TriangleSizes.data();
    batch.Count = std::min(PolygonBatchFaces, (this->CornerCount - this->NextCorner) / 3);
    this->NextCorner += 3 * batch.Count;
    return true;
  }

private:
  static constexpr std::size_t InitialCapacity = std::size_t(1) << 16;

  template <typename T>
  static void Append(ScratchArray<T>& array, std::size_t& used, const T* values, std::size_t n)
  {
    if (n == 0)
    {
      return; // a slab without surface: its arrays may be null, which memcpy must not see
    }
    if (used + n > array.Size())
    {
      array.Resize(std::max(used + n, 2 * array.Size()));
    }
    std::memcpy(array.Data() + used, values, n * sizeof(T));
    // Written pages go to the file, not the process: a slab's worth stays resident at most.
    ReleaseResidentPages(array.Data() + used, n * sizeof(T));
    used += n;
  }

  ScratchArray<float> Positions;
  ScratchArray<std::uint32_t> Corners;
  std::size_t PositionCount = 0, CornerCount = 0, NextCorner = 0;
  std::vector<std::uint32_t> TriangleSizes;
};
} // namespace

std::unique_ptr<TriangleSource> OpenVolumeTriangleSource(VolumeSlabReader& volume,
  const VolumeOptions& options, const std::string& scratchDirectory,
  SlabContourStats* contourStats, const std::function<void(double)>& progress)
{
  auto surface = std::make_unique<ScratchSurface>(scratchDirectory);
  const SlabContourStats stats =
    ContourSlabs(volume, options.IsoValue, options.SlabSlices, *surface, progress);
  if (contourStats)
  {
    *contourStats = stats;
  }
  return std::make_unique<MeshTriangleSource>(std::move(surface), volume.Name(), scratchDirectory);
}

std::unique_ptr<TriangleSource> OpenVolumeTriangleSource(const std::string& path,
  const VolumeOptions& options, const std::string& scratchDirectory,
  SlabContourStats* contourStats, const std::function<void(double)>& progress)
{
  VolumeSlabReader volume =
    VolumeSlabReader::Open(path, options.Raw ? &options.RawLayout : nullptr);
  return OpenVolumeTriangleSource(volume, options, scratchDirectory, contourStats, progress);
}

} // namespace atp
