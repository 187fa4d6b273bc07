// STL input, binary or ASCII. STL is a soup of independent triangles; its corners are welded by
// exact position so that shared edges, and therefore boundary edges, can be found. The welding
// and the welded mesh are out of core (PositionWelder, scratch arrays): memory does not grow with
// the file.
#ifndef atpStlMesh_h
#define atpStlMesh_h

#include "atpPolygonMesh.h"

#include <memory>
#include <string>

namespace atp
{

/// Scratch data goes to `scratchDirectory`. Throws InputError naming the file and the problem.
std::unique_ptr<PolygonMesh> OpenStlMesh(const std::string& path, const std::string& scratchDirectory);

} // namespace atp

#endif
