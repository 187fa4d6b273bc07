// The normal of a triangle of an indexed mesh, for tests: the cross product of two edges,
// computed in double from the float corners (twice the area long; zero for a degenerate face).
#ifndef atpTestFaceNormal_h
#define atpTestFaceNormal_h

#include "atpPatchMesh.h"

#include <array>
#include <cstddef>

namespace atp
{
namespace test
{

inline std::array<double, 3> FaceNormal(const atp::PatchMesh& mesh, std::size_t t)
{
  const float* p[3];
  for (int k = 0; k < 3; ++k)
  {
    p[k] = &mesh.Positions[3 * std::size_t(mesh.Indices[3 * t + std::size_t(k)])];
  }
  const double e[3] = { double(p[1][0]) - p[0][0], double(p[1][1]) - p[0][1], double(p[1][2]) - p[0][2] };
  const double f[3] = { double(p[2][0]) - p[0][0], double(p[2][1]) - p[0][1], double(p[2][2]) - p[0][2] };
  return { { e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0] } };
}

inline bool IsZero(const std::array<double, 3>& v)
{
  return v[0] == 0 && v[1] == 0 && v[2] == 0;
}

} // namespace test
} // namespace atp

#endif
