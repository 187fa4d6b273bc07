#include "atpPolyDataTriangleSource.h"

#include "atpMeshTriangleSource.h"
#include "atpPolygonMesh.h"

#include "vtkAOSDataArrayTemplate.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstdint>
#include <vector>

namespace atp
{
namespace
{
/// The point colors (see OpenPolyDataTriangleSource) as unsigned chars: `array` itself when it
/// holds them, else a converted copy; null when there are none.
vtkSmartPointer<vtkAOSDataArrayTemplate<unsigned char>> FindColors(vtkPolyData* mesh, const std::string& name)
{
  vtkPointData* data = mesh ? mesh->GetPointData() : nullptr;
  if (!data)
  {
    return nullptr;
  }
  const vtkIdType points = mesh->GetNumberOfPoints();
  auto* scalars = vtkArrayDownCast<vtkAOSDataArrayTemplate<unsigned char>>(data->GetScalars());
  if (scalars && (scalars->GetNumberOfComponents() == 3 || scalars->GetNumberOfComponents() == 4) &&
    scalars->GetNumberOfTuples() == points)
  {
    return scalars;
  }
  for (const char* colorName : { "RGB", "RGBA", "Colors" })
  {
    vtkDataArray* array = data->GetArray(colorName);
    if (!array)
    {
      continue;
    }
    const int components = array->GetNumberOfComponents();
    if (components != 3 && components != 4)
    {
      throw InputError(name + ": the point array " + colorName + " has " + std::to_string(components) +
        " components; colors have 3 (RGB) or 4 (RGBA)");
    }
    if (array->GetNumberOfTuples() != points)
    {
      throw InputError(name + ": the point array " + colorName + " has " +
        std::to_string(array->GetNumberOfTuples()) + " tuples for " + std::to_string(points) + " points");
    }
    if (auto* bytes = vtkArrayDownCast<vtkAOSDataArrayTemplate<unsigned char>>(array))
    {
      return bytes;
    }
    auto converted = vtkSmartPointer<vtkAOSDataArrayTemplate<unsigned char>>::New();
    converted->SetNumberOfComponents(components);
    converted->SetNumberOfTuples(array->GetNumberOfTuples());
    const int type = array->GetDataType();
    const ColorStorage storage = type == VTK_FLOAT || type == VTK_DOUBLE ? ColorStorage::Real
      : (type == VTK_UNSIGNED_SHORT ? ColorStorage::UInt16 : ColorStorage::OtherInteger);
    for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
    {
      for (int k = 0; k < components; ++k)
      {
        converted->SetTypedComponent(i, k, ColorByte(array->GetComponent(i, k), storage));
      }
    }
    return converted;
  }
  return nullptr;
}

/// A PolygonMesh over a vtkPolyData: points copied once as floats (the soup's precision), colors
/// read in place, the polygons and the triangles of strips handed out in batches.
class PolyDataMesh final : public PolygonMesh
{
public:
  PolyDataMesh(vtkPolyData* mesh, const std::string& name)
    : Name(name)
    , Mesh(mesh)
  {
    const vtkIdType count = mesh && mesh->GetPoints() ? mesh->GetNumberOfPoints() : 0;
    if (count > vtkIdType(UINT32_MAX))
    {
      throw InputError(name + ": more than 2^32-1 points");
    }
    this->Positions.resize(std::size_t(count) * 3);
    for (vtkIdType i = 0; i < count; ++i)
    {
      double p[3];
      mesh->GetPoint(i, p);
      for (int k = 0; k < 3; ++k)
      {
        this->Positions[std::size_t(3 * i + k)] = ToFloatCoordinate(p[k]);
      }
    }
    this->Colors = FindColors(mesh, name);
    this->Rewind();
  }

  VertexView Vertices() const override
  {
    VertexView view;
    view.Base = reinterpret_cast<const unsigned char*>(this->Positions.data());
    view.Count = this->Positions.size() / 3;
    if (this->Colors)
    {
      view.Colors = this->Colors->GetPointer(0);
      view.ColorComponents = this->Colors->GetNumberOfComponents();
      view.ColorStride = std::size_t(view.ColorComponents);
    }
    return view;
  }

  void Rewind() override
  {
    this->Polys = this->Mesh ? this->Iterate(this->Mesh->GetPolys()) : nullptr;
    this->Strips = this->Mesh ? this->Iterate(this->Mesh->GetStrips()) : nullptr;
  }

  bool NextBatch(PolygonBatch& batch) override
  {
    this->Indices.clear();
    this->Sizes.clear();
    constexpr std::size_t BatchPolygons = 4096;
    vtkIdType size;
    const vtkIdType* ids;
    while (this->Sizes.size() < BatchPolygons && this->Polys && !this->Polys->IsDoneWithTraversal())
    {
      this->Polys->GetCurrentCell(size, ids);
      this->Add(ids, size);
      this->Polys->GoToNextCell();
    }
    while (this->Sizes.size() < BatchPolygons && this->Strips && !this->Strips->IsDoneWithTraversal())
    {
      // Strip triangle k is (k, k+1, k+2), every other one flipped to keep the orientation.
      this->Strips->GetCurrentCell(size, ids);
      for (vtkIdType k = 0; k + 2 < size; ++k)
      {
        const vtkIdType triangle[3] = { ids[k], ids[k + 1 + (k & 1)], ids[k + 2 - (k & 1)] };
        this->Add(triangle, 3);
      }
      this->Strips->GoToNextCell();
    }
    if (this->Sizes.empty())
    {
      return false;
    }
    batch.Indices = this->Indices.data();
    batch.Sizes = this->Sizes.data();
    batch.Count = this->Sizes.size();
    return true;
  }

private:
  vtkSmartPointer<vtkCellArrayIterator> Iterate(vtkCellArray* cells)
  {
    if (!cells)
    {
      return nullptr;
    }
    vtkSmartPointer<vtkCellArrayIterator> it = vtk::TakeSmartPointer(cells->NewIterator());
    it->GoToFirstCell();
    return it;
  }

  void Add(const vtkIdType* ids, vtkIdType size)
  {
    const vtkIdType count = vtkIdType(this->Positions.size() / 3);
    for (vtkIdType c = 0; c < size; ++c)
    {
      if (ids[c] < 0 || ids[c] >= count)
      {
        throw InputError(this->Name + ": point index " + std::to_string(ids[c]) + " out of range (mesh has " +
          std::to_string(count) + " points)");
      }
      this->Indices.push_back(std::uint32_t(ids[c]));
    }
    this->Sizes.push_back(std::uint32_t(size));
  }

  std::string Name;
  vtkSmartPointer<vtkPolyData> Mesh;
  std::vector<float> Positions;
  vtkSmartPointer<vtkAOSDataArrayTemplate<unsigned char>> Colors; ///< Mesh's own, or converted
  vtkSmartPointer<vtkCellArrayIterator> Polys, Strips;
  std::vector<std::uint32_t> Indices, Sizes;
};
} // namespace

std::unique_ptr<TriangleSource> OpenPolyDataTriangleSource(
  vtkPolyData* mesh, const std::string& name, const std::string& scratchDirectory)
{
  return std::make_unique<MeshTriangleSource>(
    std::make_unique<PolyDataMesh>(mesh, name), name, scratchDirectory);
}

}
