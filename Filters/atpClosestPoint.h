// The point of a triangle nearest to a given point, by the Voronoi region of the triangle it
// falls in (Ericson, Real-Time Collision Detection, 5.1.5). One piece for the simplifier's
// error measure and the simplification benchmark's distances and interpolated normals.
// Plain C++, header only.
#ifndef atpClosestPoint_h
#define atpClosestPoint_h

#include <algorithm>

namespace atp
{

/// A point of triangle (a, b, c), Point = a + S (b - a) + T (c - a): its barycentric weights
/// are 1 - S - T, S and T.
struct TrianglePoint
{
  double Point[3] = { 0, 0, 0 };
  double S = 0;
  double T = 0;
};

/// The point of triangle (a, b, c) nearest to p.
inline TrianglePoint ClosestOnTriangle(const double p[3], const double a[3], const double b[3], const double c[3])
{
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int i = 0; i < 3; ++i)
  {
    ab[i] = b[i] - a[i];
    ac[i] = c[i] - a[i];
    ap[i] = p[i] - a[i];
    bp[i] = p[i] - b[i];
    cp[i] = p[i] - c[i];
  }
  const auto dot = [](const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  const auto at = [&](double s, double t) {
    TrianglePoint q;
    for (int i = 0; i < 3; ++i)
    {
      q.Point[i] = a[i] + s * ab[i] + t * ac[i];
    }
    q.S = s;
    q.T = t;
    return q;
  };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp), d5 = dot(ab, cp), d6 = dot(ac, cp);
  const double va = d3 * d6 - d5 * d4, vb = d5 * d2 - d1 * d6, vc = d1 * d4 - d3 * d2;
  if (d1 <= 0 && d2 <= 0)
  {
    return at(0, 0); // corner a
  }
  if (d3 >= 0 && d4 <= d3)
  {
    return at(1, 0); // corner b
  }
  if (d6 >= 0 && d5 <= d6)
  {
    return at(0, 1); // corner c
  }
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
  {
    return at(d1 / (d1 - d3), 0); // edge ab
  }
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
  {
    return at(0, d2 / (d2 - d6)); // edge ac
  }
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
  {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return at(1 - w, w); // edge bc
  }
  // va + vb + vc is |ab x ac|^2, which rounding leaves inexact to about 1e-16 of |ab|^2 |ac|^2.
  const double denominator = va + vb + vc;
  if (denominator > 1e-12 * dot(ab, ab) * dot(ac, ac))
  {
    return at(vb / denominator, vc / denominator);
  }
  // No area to speak of (a sliver whose corners are all but collinear): the nearest of the
  // points nearest on its three sides, which lie within rounding of the face. Never nearer than
  // the face: the error measure stays an upper bound.
  TrianglePoint best;
  double best2 = -1;
  const double ends[3][2][2] = { { { 0, 0 }, { 1, 0 } }, { { 0, 0 }, { 0, 1 } }, { { 1, 0 }, { 0, 1 } } };
  for (const auto& side : ends)
  {
    const TrianglePoint from = at(side[0][0], side[0][1]), to = at(side[1][0], side[1][1]);
    double along[3], off[3];
    for (int i = 0; i < 3; ++i)
    {
      along[i] = to.Point[i] - from.Point[i];
      off[i] = p[i] - from.Point[i];
    }
    const double length2 = dot(along, along);
    const double w = length2 > 0 ? std::min(1.0, std::max(0.0, dot(off, along) / length2)) : 0;
    const TrianglePoint q =
      at(side[0][0] + w * (side[1][0] - side[0][0]), side[0][1] + w * (side[1][1] - side[0][1]));
    double d[3];
    for (int i = 0; i < 3; ++i)
    {
      d[i] = p[i] - q.Point[i];
    }
    if (best2 < 0 || dot(d, d) < best2)
    {
      best = q;
      best2 = dot(d, d);
    }
  }
  return best;
}

} // namespace atp

#endif
