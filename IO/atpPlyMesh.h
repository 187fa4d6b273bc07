// PLY input (ASCII, binary little and big endian) as a PolygonMesh. The vertex element is read
// once into ScratchArrays (or, for little-endian float x, y, z and byte colors, used in place from
// a memory map of the file); the face element is streamed in batches and never held whole.
// Vertex colors are red, green, blue and optional alpha (or diffuse_red, ...).
#ifndef atpPlyMesh_h
#define atpPlyMesh_h

#include "atpPolygonMesh.h"

#include <memory>
#include <string>

namespace atp
{

/// Throws InputError naming the file and the problem.
std::unique_ptr<PolygonMesh> OpenPlyMesh(
  const std::string& path, const std::string& scratchDirectory);

} // namespace atp

#endif
