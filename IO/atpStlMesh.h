// STL input, binary or ASCII. STL is a soup of independent triangles; its corners are welded by
// exact position so that shared edges, and therefore boundary edges, can be found. STL inputs
// are modest, so the welded mesh is held in memory.
#ifndef atpStlMesh_h
#define atpStlMesh_h

#include "atpPolygonMesh.h"

#include <memory>
#include <string>

namespace atp
{

/// Throws InputError naming the file and the problem.
std::unique_ptr<PolygonMesh> OpenStlMesh(const std::string& path);

} // namespace atp

#endif
