#include "atpTriangleSource.h"

#include "atpMeshTriangleSource.h"
#include "atpObjMesh.h"
#include "atpPlyMesh.h"
#include "atpPolyDataTriangleSource.h"
#include "atpStlMesh.h"
#include "atpVtpReader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cctype>

namespace atp
{
TriangleSource::~TriangleSource() = default;

void CheckCoordinateRange(const Box& bounds, const std::string& inputName)
{
  double largest = 0;
  for (int a = 0; a < 3 && !bounds.IsEmpty(); ++a)
  {
    largest = std::max({ largest, std::abs(bounds.Min[a]), std::abs(bounds.Max[a]) });
  }
  if (largest > MaxCoordinate)
  {
    char text[160];
    std::snprintf(text, sizeof text,
      ": a coordinate of magnitude %.3g; models keep positions and errors as 32-bit floats, so "
      "coordinates must lie within +-%.0e",
      largest, MaxCoordinate);
    throw InputError(inputName + text);
  }
}

std::unique_ptr<TriangleSource> OpenTriangleSource(
  const std::string& path, const std::string& scratchDirectory)
{
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  std::string extension =
    dot == std::string::npos || (slash != std::string::npos && dot < slash) ? "" : path.substr(dot);
  std::transform(extension.begin(), extension.end(), extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });

  std::unique_ptr<PolygonMesh> mesh;
  if (extension == ".ply")
  {
    mesh = OpenPlyMesh(path, scratchDirectory);
  }
  else if (extension == ".obj")
  {
    mesh = OpenObjMesh(path, scratchDirectory);
  }
  else if (extension == ".stl")
  {
    mesh = OpenStlMesh(path, scratchDirectory);
  }
  else if (extension == ".vtp")
  {
    return OpenPolyDataTriangleSource(ReadVtpFile(path), path, scratchDirectory);
  }
  else
  {
    throw InputError(
      path + ": unsupported file type '" + extension + "' (expected .ply, .obj, .stl or .vtp)");
  }
  return std::make_unique<MeshTriangleSource>(std::move(mesh), path, scratchDirectory);
}

} // namespace atp
