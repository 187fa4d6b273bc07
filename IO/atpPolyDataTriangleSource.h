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
/// Vertex colors: the point data's active scalars when they are 3 or 4 unsigned chars, or else
/// the first array named RGB, RGBA or Colors, of 3 or 4 components of any type, converted as PLY
/// colors are (reals: fractions of 1; unsigned shorts: of 65535; other integers: of 255).
/// `name` stands for the mesh in error messages. The source keeps a reference to `mesh`.
/// Throws InputError (no points, no triangles, non-finite coordinates, too many points, an array
/// named as colors of another number of components or tuples than the points).
VTKATPIO_EXPORT std::unique_ptr<TriangleSource> OpenPolyDataTriangleSource(
  vtkPolyData* mesh, const std::string& name, const std::string& scratchDirectory = "");

}

#endif
