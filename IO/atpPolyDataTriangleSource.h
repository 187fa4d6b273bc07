// Triangles of an in-memory vtkPolyData (pipeline input, or a .vtp read by VTK), through the
// same triangulation, degenerate and boundary path as the streamed formats.
#ifndef atpPolyDataTriangleSource_h
#define atpPolyDataTriangleSource_h

#include "atpTriangleSource.h"
#include "vtkATPIOModule.h"

#include <memory>
#include <string>

class vtkPolyData;

namespace atp
{

/// Polygons (fan-triangulated) and triangle strips of `mesh`; vertices and lines are ignored.
/// Vertex colors: the point data's active scalars, or else an array named RGB, RGBA or Colors,
/// when it has 3 or 4 unsigned char components.
/// `name` stands for the mesh in error messages. The source keeps a reference to `mesh`.
/// Throws InputError (no points, no triangles, non-finite coordinates, too many points).
VTKATPIO_EXPORT std::unique_ptr<TriangleSource> OpenPolyDataTriangleSource(
  vtkPolyData* mesh, const std::string& name, const std::string& scratchDirectory = "");

}

#endif
