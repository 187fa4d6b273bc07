// Wavefront OBJ input: 'v' and 'f' lines, everything else ignored. A first pass over the file
// stores the vertices in a ScratchArray; faces, which may be interleaved with vertices and use
// relative (negative) indices, are then streamed in batches by later passes. Vertex colors come
// from the common extension "v x y z r g b" (fractions of 1) when every vertex has them.
#ifndef atpObjMesh_h
#define atpObjMesh_h

#include "atpPolygonMesh.h"

#include <memory>
#include <string>

namespace atp
{

/// Throws InputError naming the file (and line) and the problem.
std::unique_ptr<PolygonMesh> OpenObjMesh(
  const std::string& path, const std::string& scratchDirectory);

} // namespace atp

#endif
