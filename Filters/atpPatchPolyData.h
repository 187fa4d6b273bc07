// A PatchMesh (a decoded patch or an extracted cut) as an ordinary vtkPolyData.
#ifndef atpPatchPolyData_h
#define atpPatchPolyData_h

#include "atpPatchMesh.h"
#include "vtkATPFiltersModule.h"

#include "vtkSmartPointer.h"

class vtkPolyData;

namespace atp
{

/// Float points, triangles, point normals ("Normals") and, when the mesh has colors, RGBA
/// point scalars ("Colors").
VTKATPFILTERS_EXPORT vtkSmartPointer<vtkPolyData> PatchMeshToPolyData(const PatchMesh& mesh);

} // namespace atp

#endif
