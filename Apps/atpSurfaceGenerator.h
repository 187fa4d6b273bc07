// Generates large test surfaces (a bumpy torus, optionally with holes) straight into a binary
// PLY file, streaming, so a mesh of any size can be made on a small machine.
#ifndef atpSurfaceGenerator_h
#define atpSurfaceGenerator_h

#include <cstdint>
#include <string>

namespace atp
{

struct SurfaceOptions
{
  std::uint64_t Triangles = 1000000; ///< at least this many (fewer with holes); the grid is rounded up
  int Holes = 0;                     ///< rectangular holes punched through, giving borders
};

/// Writes the surface to `path`; returns the number of triangles written. Throws
/// std::runtime_error (naming the file) when the file cannot be written completely.
std::uint64_t WriteBumpyTorusPly(const std::string& path, const SurfaceOptions& options);

}

#endif
