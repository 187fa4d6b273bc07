#include "atpPatchPolyData.h"

#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>

namespace atp
{

vtkSmartPointer<vtkPolyData> PatchMeshToPolyData(const PatchMesh& mesh)
{
  const vtkIdType vertices = vtkIdType(mesh.VertexCount());
  vtkNew<vtkFloatArray> positions;
  positions->SetNumberOfComponents(3);
  positions->SetNumberOfTuples(vertices);
  std::copy(mesh.Positions.begin(), mesh.Positions.end(), positions->GetPointer(0));
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(vtkIdType(mesh.Indices.size()));
  std::copy(mesh.Indices.begin(), mesh.Indices.end(), connectivity->GetPointer(0));

  vtkNew<vtkPoints> points;
  points->SetData(positions);
  vtkNew<vtkCellArray> triangles;
  triangles->SetData(3, connectivity);
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(points);
  polyData->SetPolys(triangles);
  if (!mesh.Normals.empty())
  {
    vtkNew<vtkFloatArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(vertices);
    std::copy(mesh.Normals.begin(), mesh.Normals.end(), normals->GetPointer(0));
    polyData->GetPointData()->SetNormals(normals);
  }
  if (mesh.HasColors())
  {
    vtkNew<vtkUnsignedCharArray> colors;
    colors->SetName("Colors");
    colors->SetNumberOfComponents(4);
    colors->SetNumberOfTuples(vertices);
    std::copy(mesh.Colors.begin(), mesh.Colors.end(), colors->GetPointer(0));
    polyData->GetPointData()->SetScalars(colors);
  }
  return polyData;
}

} // namespace atp
