// The normal of a triangle of an indexed mesh, for tests: the cross product of two edges,
// computed in double from the float corners (twice the area long; zero for a degenerate face);
// and the angles the cone tests compare normals by.
#ifndef atpTestFaceNormal_h
#define atpTestFaceNormal_h

#include "atpPatchMesh.h"

#include <algorithm>
#include <array>
#include <cmath>
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

/// The angle whose cosine is `cosine`, which rounding may have taken just past -1 or 1.
inline double AngleOfCosine(double cosine)
{
  return std::acos(std::max(-1.0, std::min(1.0, cosine)));
}

/// The angle between two directions of any length.
inline double AngleBetween(const double a[3], const double b[3])
{
  const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  const double lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  return AngleOfCosine((a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb));
}

} // namespace test
} // namespace atp

#endif
