// The isosurface of a volume, contoured slab by slab so memory holds one slab of the volume and
// its triangles, never the whole. Consecutive slabs share a slice and the vertices on that
// slice are welded, so the triangles are those of contouring the whole volume at once (same
// cells, same marching cubes cases) and the surface has no gap, no duplicate and no extra
// boundary at the seams. Vertices are one per position, as vtkMarchingCubes merges them.
#ifndef atpSlabContour_h
#define atpSlabContour_h

#include "vtkATPIOModule.h" // export macro

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>

namespace atp
{

class VolumeSlabReader;

/// Receives the welded surface as it is made: vertices numbered from 0 in the order given, and
/// triangles (three vertex numbers each) that use only vertices already given.
class VTKATPIO_EXPORT ContourSink
{
public:
  virtual ~ContourSink();
  /// `count` vertices, x, y, z each, in world coordinates.
  virtual void AddVertices(const float* xyz, std::size_t count) = 0;
  virtual void AddTriangles(const std::uint32_t* corners, std::size_t count) = 0;
};

struct SlabContourStats
{
  std::array<int, 3> Dimensions{ { 0, 0, 0 } }; ///< voxels along x, y, z
  int Slabs = 0;
  /// Smallest and largest voxel value (as VolumeSlabReader::ValueSlope and ValueIntercept
  /// scale the stored values, like the iso value).
  std::array<double, 2> DataRange{ { 0, 0 } };
  std::uint64_t Vertices = 0;
  std::uint64_t Triangles = 0;
};

/// Default slices per slab: for a 1000 x 1000 slice of 16-bit voxels, 128 MiB of volume.
constexpr int DefaultSlabSlices = 64;

/// Contours `volume` at `isoValue` (vtkFlyingEdges3D on each slab of `slabSlices` slices, at
/// least 2) into `sink`, in order of increasing z. The triangles are those of vtkFlyingEdges3D
/// on the whole volume; the vertices are its points welded by position (in voxel coordinates,
/// as floats): flying edges makes one point per edge, so where the iso value equals a voxel's
/// value several coincide there and its surface would be open. Throws InputError naming the
/// volume: multi-component or
/// missing scalars, a NaN or infinite voxel, fewer than 2 voxels along an axis, no surface at
/// `isoValue` (the message gives the data range), or more than 2^32-1 vertices. `progress`,
/// when given, is called after each slab with the fraction of the volume done (and may throw
/// to cancel).
VTKATPIO_EXPORT SlabContourStats ContourSlabs(VolumeSlabReader& volume, double isoValue,
  int slabSlices, ContourSink& sink, const std::function<void(double)>& progress = nullptr);

} // namespace atp

#endif
