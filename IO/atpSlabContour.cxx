#include "atpSlabContour.h"

#include "atpPolygonMesh.h" // MaxVertices, ToFloatCoordinate
#include "atpTriangleSource.h" // InputError
#include "atpVolumeSlabs.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <unordered_map>
#include <vector>

namespace atp
{
ContourSink::~ContourSink() = default;

namespace
{
std::string Number(double value)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

/// The slab's voxel values: its active scalars, else its only point array; one component.
vtkDataArray* SlabScalars(vtkImageData* slab, const std::string& name)
{
  vtkPointData* data = slab->GetPointData();
  vtkDataArray* scalars = data->GetScalars();
  if (!scalars && data->GetNumberOfArrays() == 1)
  {
    scalars = data->GetArray(0);
  }
  if (!scalars)
  {
    throw InputError(name + ": no voxel values (expected one scalar point array)");
  }
  if (scalars->GetNumberOfComponents() != 1)
  {
    throw InputError(name + ": " + std::to_string(scalars->GetNumberOfComponents()) +
      " components per voxel; only single-valued volumes can be contoured");
  }
  return scalars;
}

/// Throws naming the first NaN or infinite voxel of a floating-point slab.
template <typename Array>
void CheckFinite(Array* values, vtkImageData* slab, const std::string& name)
{
  if (!values)
  {
    return;
  }
  const auto* v = values->GetPointer(0);
  const vtkIdType count = values->GetNumberOfTuples();
  for (vtkIdType t = 0; t < count; ++t)
  {
    if (!std::isfinite(v[t]))
    {
      const int* extent = slab->GetExtent();
      const vtkIdType nx = extent[1] - extent[0] + 1, ny = extent[3] - extent[2] + 1;
      throw InputError(name + ": voxel (" + std::to_string(extent[0] + t % nx) + ", " +
        std::to_string(extent[2] + t / nx % ny) + ", " + std::to_string(extent[4] + t / (nx * ny)) +
        ") is " + (std::isnan(v[t]) ? "NaN" : "infinite") + "; the volume must be finite");
    }
  }
}

/// A vertex position in index coordinates, bit for bit.
struct PointKey
{
  std::array<std::uint32_t, 3> Bits;

  explicit PointKey(const float p[3]) { std::memcpy(this->Bits.data(), p, sizeof(this->Bits)); }
  bool operator==(const PointKey& other) const { return this->Bits == other.Bits; }
};

struct PointKeyHash
{
  std::size_t operator()(const PointKey& key) const
  {
    std::uint64_t h = key.Bits[0];
    h = h * 0x9E3779B97F4A7C15ull ^ key.Bits[1];
    h = h * 0x9E3779B97F4A7C15ull ^ key.Bits[2];
    return std::size_t(h ^ (h >> 29));
  }
};

using PointMap = std::unordered_map<PointKey, std::uint32_t, PointKeyHash>;

bool IsGridPoint(const float p[3])
{
  return p[0] == std::floor(p[0]) && p[1] == std::floor(p[1]) && p[2] == std::floor(p[2]);
}

/// The contour of one slab in index coordinates (origin 0, spacing 1, no rotation), so the
/// shared slice's vertices have an exact z and match between slabs bit for bit.
vtkSmartPointer<vtkPolyData> ContourInIndexSpace(
  vtkImageData* slab, vtkDataArray* scalars, double isoValue)
{
  vtkNew<vtkImageData> indexSpace;
  indexSpace->SetExtent(slab->GetExtent());
  indexSpace->GetPointData()->SetScalars(scalars);
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputData(indexSpace);
  contour->SetValue(0, isoValue);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  contour->Update();
  return contour->GetOutput();
}

/// Numbers the vertices of the whole surface, one number per position: a position on a slice
/// two slabs share gets the number the lower slab gave it, and points that flying edges makes
/// at one voxel from several edges (the iso value equals the voxel's value, or an intersection
/// rounds onto the voxel) are one vertex, as vtkMarchingCubes would merge them. Only such grid
/// points can coincide: any other point lies inside one edge, which makes one point.
class SlabWelder
{
public:
  SlabWelder(const std::string& name, ContourSink& sink)
    : Name(name)
    , Sink(sink)
  {
  }

  /// Hands the slab's new vertices and its triangles to the sink. `sharesBelow`: firstSlice is
  /// shared with the slab before; `sharesAbove`: lastSlice is shared with the next.
  void Add(vtkPolyData* surface, vtkImageData* slab, int firstSlice, int lastSlice,
    bool sharesBelow, bool sharesAbove, SlabContourStats& stats)
  {
    const double* toWorld = slab->GetIndexToPhysicalMatrix()->GetData();
    vtkPoints* points = surface->GetPoints();
    const vtkIdType count = points ? points->GetNumberOfPoints() : 0;
    this->Ids.resize(std::size_t(count));
    this->NewVertices.clear();
    this->Above.clear();
    this->GridPoints.clear();
    for (vtkIdType i = 0; i < count; ++i)
    {
      double position[3];
      points->GetPoint(i, position);
      const float p[3] = { float(position[0]), float(position[1]), float(position[2]) };
      const PointKey key(p);
      PointMap* shared = sharesBelow && p[2] == float(firstSlice) ? &this->Below
        : IsGridPoint(p)                                          ? &this->GridPoints
                                                                  : nullptr;
      if (shared)
      {
        const auto found = shared->find(key);
        if (found != shared->end())
        {
          this->Ids[std::size_t(i)] = found->second;
          continue;
        }
      }
      if (this->NextId >= MaxVertices)
      {
        throw InputError(this->Name + ": the surface has more than 2^32-1 vertices");
      }
      const std::uint32_t id = std::uint32_t(this->NextId++);
      this->Ids[std::size_t(i)] = id;
      if (shared)
      {
        shared->emplace(key, id);
      }
      if (sharesAbove && p[2] == float(lastSlice))
      {
        this->Above.emplace(key, id);
      }
      for (int row = 0; row < 3; ++row)
      {
        const double* m = toWorld + 4 * row;
        this->NewVertices.push_back(
          ToFloatCoordinate(m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3]));
      }
    }
    this->Triangles.clear();
    auto cells = vtk::TakeSmartPointer(surface->GetPolys()->NewIterator());
    for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
    {
      vtkIdType size;
      const vtkIdType* corners;
      cells->GetCurrentCell(size, corners);
      for (vtkIdType c = 0; c < size; ++c) // flying edges makes triangles only
      {
        this->Triangles.push_back(this->Ids[std::size_t(corners[c])]);
      }
    }
    this->Sink.AddVertices(this->NewVertices.data(), this->NewVertices.size() / 3);
    this->Sink.AddTriangles(this->Triangles.data(), this->Triangles.size() / 3);
    stats.Vertices += this->NewVertices.size() / 3;
    stats.Triangles += this->Triangles.size() / 3;
    this->Below.swap(this->Above);
  }

private:
  std::string Name;
  ContourSink& Sink;
  std::uint64_t NextId = 0;
  /// Vertices on the slice shared with the slab below and on the one shared with the slab
  /// above; grid points of this slab elsewhere.
  PointMap Below, Above, GridPoints;
  std::vector<std::uint32_t> Ids;
  std::vector<float> NewVertices;
  std::vector<std::uint32_t> Triangles;
};
} // namespace

SlabContourStats ContourSlabs(VolumeSlabReader& volume, double isoValue, int slabSlices,
  ContourSink& sink, const std::function<void(double)>& progress)
{
  const std::string& name = volume.Name();
  const std::array<int, 6>& whole = volume.WholeExtent();
  SlabContourStats stats;
  for (int axis = 0; axis < 3; ++axis)
  {
    stats.Dimensions[axis] = whole[2 * axis + 1] - whole[2 * axis] + 1;
  }
  if (*std::min_element(stats.Dimensions.begin(), stats.Dimensions.end()) < 2)
  {
    throw InputError(name + ": a volume needs at least 2 voxels along each axis, this one is " +
      std::to_string(stats.Dimensions[0]) + "x" + std::to_string(stats.Dimensions[1]) + "x" +
      std::to_string(stats.Dimensions[2]));
  }
  const int step = std::max(2, slabSlices) - 1;
  // The voxels hold stored values; the iso value and the range are in the values they stand for.
  const double slope = volume.ValueSlope(), intercept = volume.ValueIntercept();
  const double storedIsoValue = (isoValue - intercept) / slope;
  stats.DataRange = { { HUGE_VAL, -HUGE_VAL } };
  SlabWelder welder(name, sink);
  for (int first = whole[4]; first < whole[5]; first += step)
  {
    const int last = std::min(first + step, whole[5]);
    vtkSmartPointer<vtkImageData> slab = volume.ReadSlab(first, last);
    vtkDataArray* scalars = SlabScalars(slab, name);
    CheckFinite(vtkFloatArray::FastDownCast(scalars), slab, name);
    CheckFinite(vtkDoubleArray::FastDownCast(scalars), slab, name);
    double range[2];
    scalars->GetRange(range, 0);
    const double a = slope * range[0] + intercept, b = slope * range[1] + intercept;
    stats.DataRange[0] = std::min(stats.DataRange[0], std::min(a, b));
    stats.DataRange[1] = std::max(stats.DataRange[1], std::max(a, b));
    vtkSmartPointer<vtkPolyData> surface = ContourInIndexSpace(slab, scalars, storedIsoValue);
    welder.Add(surface, slab, first, last, first > whole[4], last < whole[5], stats);
    ++stats.Slabs;
    if (progress)
    {
      progress(double(last - whole[4]) / double(whole[5] - whole[4]));
    }
  }
  if (stats.Triangles == 0)
  {
    throw InputError(name + ": no surface at iso value " + Number(isoValue) +
      " (the voxel values range from " + Number(stats.DataRange[0]) + " to " +
      Number(stats.DataRange[1]) + ")");
  }
  return stats;
}

} // namespace atp
