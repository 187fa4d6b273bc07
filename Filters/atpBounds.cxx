#include "atpBounds.h"

#include <CGAL/Min_sphere_of_spheres_d.h>
#include <CGAL/Min_sphere_of_spheres_d_traits_3.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>

namespace atp
{
namespace
{
/// Points by value: CGAL::Cartesian's reference-counted handles cost an allocation per point.
using Kernel = CGAL::Simple_cartesian<double>;
using Traits = CGAL::Min_sphere_of_spheres_d_traits_3<Kernel, double>;
using MinSphere = CGAL::Min_sphere_of_spheres_d<Traits>;

double Distance(const double a[3], const double b[3])
{
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
    (a[2] - b[2]) * (a[2] - b[2]));
}

/// CGAL's double-precision ball can miss an input by a rounding error: grow the radius until
/// every input is inside by direct measurement, so enclosure never depends on CGAL's precision.
Sphere Solve(const std::vector<Traits::Sphere>& balls)
{
  Sphere result;
  if (balls.empty())
  {
    return result;
  }
  MinSphere solver(balls.begin(), balls.end()); // CGAL computes lazily: not const
  auto c = solver.center_cartesian_begin();
  for (int a = 0; a < 3; ++a, ++c)
  {
    result.Center[a] = *c;
  }
  result.Radius = solver.radius();
  for (const Traits::Sphere& ball : balls)
  {
    const double center[3] = { ball.first.x(), ball.first.y(), ball.first.z() };
    result.Radius = std::max(result.Radius, Distance(result.Center, center) + ball.second);
  }
  return result;
}

double Length(const double v[3])
{
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// The angle whose cosine is `cosine`, which rounding may have taken just past -1 or 1.
double AngleOf(double cosine)
{
  return std::acos(std::clamp(cosine, -1.0, 1.0));
}

/// The cone around `axis` (not necessarily unit; zero means no common direction) that holds
/// unit directions `directions` each widened by its own half angle.
NormalCone ConeAround(double axis[3], const std::vector<std::array<double, 4>>& directions)
{
  NormalCone cone;
  cone.Empty = directions.empty();
  const double length = Length(axis);
  if (cone.Empty || length < 1e-12)
  {
    cone.Cos = cone.Empty ? 1 : -1;
    return cone;
  }
  for (int a = 0; a < 3; ++a)
  {
    cone.Axis[a] = axis[a] / length;
  }
  // Face normals have no width: the widest of them is the one of least cosine, so one arc
  // cosine serves them all (a patch has thousands).
  double halfAngle = 0;
  double leastCos = 1;
  for (const auto& d : directions)
  {
    if (d[3] == 0)
    {
      leastCos = std::min(leastCos, Dot(cone.Axis, d.data()));
    }
    else
    {
      halfAngle = std::max(halfAngle, AngleOf(Dot(cone.Axis, d.data())) + d[3]);
    }
  }
  halfAngle = std::max(halfAngle, AngleOf(leastCos));
  cone.Cos = halfAngle >= M_PI ? -1 : std::cos(halfAngle);
  return cone;
}

} // namespace

Sphere EnclosingSphere(const float* positions, std::size_t count)
{
  std::vector<Traits::Sphere> balls;
  balls.reserve(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    const float* p = positions + 3 * i;
    balls.emplace_back(Kernel::Point_3(p[0], p[1], p[2]), 0.0);
  }
  return Solve(balls);
}

Sphere EnclosingSphere(const std::vector<Sphere>& spheres)
{
  std::vector<Traits::Sphere> balls;
  balls.reserve(spheres.size());
  for (const Sphere& s : spheres)
  {
    if (!s.IsEmpty())
    {
      balls.emplace_back(Kernel::Point_3(s.Center[0], s.Center[1], s.Center[2]), s.Radius);
    }
  }
  return Solve(balls);
}

void StoreSphere(const Sphere& sphere, float out[4])
{
  if (sphere.IsEmpty())
  {
    std::fill(out, out + 4, 0.0f);
    return;
  }
  double stored[3];
  for (int a = 0; a < 3; ++a)
  {
    out[a] = float(sphere.Center[a]);
    stored[a] = out[a];
  }
  // A relative margin far above double rounding keeps containment tests exact for readers that
  // compute distances in float or double.
  const double radius = (sphere.Radius + Distance(stored, sphere.Center)) * (1 + 1e-6) + 1e-30;
  out[3] = std::nextafter(float(radius), INFINITY);
}

Sphere LoadSphere(const float in[4])
{
  Sphere s;
  if (in[3] == 0)
  {
    return s; // StoreSphere's empty sphere: any sphere it stores has a margin
  }
  for (int a = 0; a < 3; ++a)
  {
    s.Center[a] = in[a];
  }
  s.Radius = in[3];
  return s;
}

std::array<double, 3> FaceCross(const PatchMesh& patch, std::size_t t)
{
  const float* p[3];
  for (int c = 0; c < 3; ++c)
  {
    p[c] = &patch.Positions[3 * std::size_t(patch.Indices[3 * t + std::size_t(c)])];
  }
  double e[3], f[3];
  for (int a = 0; a < 3; ++a)
  {
    e[a] = double(p[1][a]) - p[0][a];
    f[a] = double(p[2][a]) - p[0][a];
  }
  return { { e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0] } };
}

NormalCone FaceNormalCone(const PatchMesh& patch)
{
  std::vector<std::array<double, 4>> normals;
  normals.reserve(patch.TriangleCount());
  double sum[3] = { 0, 0, 0 };
  for (std::size_t t = 0; t < patch.TriangleCount(); ++t)
  {
    std::array<double, 3> n = FaceCross(patch, t);
    const double area2 = Length(n.data());
    if (area2 == 0)
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      sum[a] += n[a]; // area weighted: large faces decide the axis
      n[a] /= area2;
    }
    normals.push_back({ { n[0], n[1], n[2], 0 } });
  }
  return ConeAround(sum, normals);
}

NormalCone EnclosingCone(const std::vector<NormalCone>& cones)
{
  std::vector<std::array<double, 4>> directions;
  double sum[3] = { 0, 0, 0 };
  for (const NormalCone& c : cones)
  {
    if (c.Empty)
    {
      continue;
    }
    if (c.Cos <= -1)
    {
      NormalCone all;
      all.Empty = false;
      all.Cos = -1;
      return all;
    }
    directions.push_back({ { c.Axis[0], c.Axis[1], c.Axis[2], AngleOf(c.Cos) } });
    for (int a = 0; a < 3; ++a)
    {
      sum[a] += c.Axis[a];
    }
  }
  return ConeAround(sum, directions);
}

void StoreCone(const NormalCone& cone, float axis[3], float& cosine)
{
  for (int a = 0; a < 3; ++a)
  {
    axis[a] = float(cone.Axis[a]);
  }
  // The float axis is off by ~1e-7 rad; widening by 1e-5 in cosine covers it.
  cosine = cone.Empty ? 1.0f : float(std::max(-1.0, cone.Cos - 1e-5));
}

NormalCone LoadCone(const float axis[3], float cosine)
{
  NormalCone cone;
  for (int a = 0; a < 3; ++a)
  {
    cone.Axis[a] = axis[a];
  }
  cone.Cos = cosine;
  cone.Empty = false;
  return cone;
}

} // namespace atp
