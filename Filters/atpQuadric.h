// Quadric error metrics for the simplifier: Garland-Heckbert plane quadrics and Hoppe's (1999)
// attribute extension, where each attribute varies linearly over the plane of its triangle.
// Plain C++, header only: the simplifier evaluates these in its innermost loop.
#ifndef atpQuadric_h
#define atpQuadric_h

#include <cstddef>
#include <type_traits>

namespace atp
{

/// A quadric stored flat, so that one vertex's whole state is one contiguous record: A (6, the
/// upper triangle), B (3), C, then Hoppe's attribute part W, G (3 per attribute) and D (one per
/// attribute): Size(m) doubles for m attributes. Q(p, s) = p'Ap + 2b'p + c + the attribute
/// terms; an attribute s with the linear field s(p) = g.p + d over a triangle of weight w
/// contributes w (g.p + d - s)^2, whose p'gg'p, d g and d^2 terms go into A, B and C.
namespace Quadric
{

constexpr std::size_t Size(int attributes)
{
  return 11 + 4 * std::size_t(attributes);
}

/// What the plane n.p + d = 0 (n of unit length) with weight w contributes to A, B and C (the
/// first 10 doubles of a quadric).
inline void PlaneTerms(const double n[3], double d, double w, double terms[10])
{
  const double wn[3] = { w * n[0], w * n[1], w * n[2] };
  const double wd = w * d;
  terms[0] = wn[0] * n[0];
  terms[1] = wn[0] * n[1];
  terms[2] = wn[0] * n[2];
  terms[3] = wn[1] * n[1];
  terms[4] = wn[1] * n[2];
  terms[5] = wn[2] * n[2];
  terms[6] = wd * n[0];
  terms[7] = wd * n[1];
  terms[8] = wd * n[2];
  terms[9] = wd * d;
}

/// Adds the plane n.p + d = 0 (n of unit length), with weight w.
inline void AddPlane(double* q, const double n[3], double d, double w)
{
  double terms[10];
  PlaneTerms(n, d, w, terms);
  for (int i = 0; i < 10; ++i)
  {
    q[i] += terms[i];
  }
}

/// Sets q (Size(attributes) doubles) to a triangle's quadric, weighted by w: its plane
/// n.p + d = 0 (n of unit length) and the linear field g[3j..3j+3), d[j] of each attribute j.
/// Written at once rather than added into a zeroed record: the simplifier does this for every
/// triangle of every diamond. Fixed, when not negative, is the attribute count as a constant
/// (see EvaluateWith).
template <int Fixed>
inline void SetTriangleWith(double* q, const double n[3], double d, int attributes, const double* g,
  const double* offsets, double w)
{
  const int count = Fixed >= 0 ? Fixed : attributes;
  double a[10];
  PlaneTerms(n, d, w, a);
  double* G = q + 11;
  double* D = G + 3 * count;
  for (int j = 0; j < count; ++j)
  {
    const double* gj = g + 3 * j;
    const double wg[3] = { w * gj[0], w * gj[1], w * gj[2] };
    const double wdj = w * offsets[j];
    a[0] += wg[0] * gj[0];
    a[1] += wg[0] * gj[1];
    a[2] += wg[0] * gj[2];
    a[3] += wg[1] * gj[1];
    a[4] += wg[1] * gj[2];
    a[5] += wg[2] * gj[2];
    a[6] += wdj * gj[0];
    a[7] += wdj * gj[1];
    a[8] += wdj * gj[2];
    a[9] += wdj * offsets[j];
    G[3 * j] = wg[0];
    G[3 * j + 1] = wg[1];
    G[3 * j + 2] = wg[2];
    D[j] = wdj;
  }
  for (int i = 0; i < 10; ++i)
  {
    q[i] = a[i];
  }
  q[10] = count > 0 ? w : 0;
}

/// SetTriangleWith for any attribute count.
inline void SetTriangle(double* q, const double n[3], double d, int attributes, const double* g,
  const double* offsets, double w)
{
  SetTriangleWith<-1>(q, n, d, attributes, g, offsets, w);
}

/// q += r over n doubles (Size(m), or a longer record holding a quadric). Records never
/// overlap: restrict lets the compiler add them a vector at a time.
inline void Add(double* __restrict q, const double* __restrict r, std::size_t n)
{
  for (std::size_t i = 0; i < n; ++i)
  {
    q[i] += r[i];
  }
}

/// a += r, b += r and c += r over n doubles: a triangle's quadric read once for its three
/// corners' records (which never overlap).
inline void AddToCorners(double* __restrict a, double* __restrict b, double* __restrict c,
  const double* __restrict r, std::size_t n)
{
  for (std::size_t i = 0; i < n; ++i)
  {
    a[i] += r[i];
    b[i] += r[i];
    c[i] += r[i];
  }
}

/// Q(p, s): the error at position p with attribute values s. Fixed, when not negative, is the
/// attribute count as a constant, so that the attribute terms unroll (the simplifier prices
/// collapses in its innermost loop); otherwise `attributes` counts them.
template <int Fixed>
inline double EvaluateWith(const double* q, int attributes, const double p[3], const double* s)
{
  const int count = Fixed >= 0 ? Fixed : attributes;
  const double x = p[0], y = p[1], z = p[2];
  double e = x * (q[0] * x + 2 * (q[1] * y + q[2] * z + q[6])) + y * (q[3] * y + 2 * (q[4] * z + q[7])) +
    z * (q[5] * z + 2 * q[8]) + q[9];
  const double* G = q + 11;
  const double* D = G + 3 * count;
  for (int j = 0; j < count; ++j)
  {
    const double* gj = G + 3 * j;
    e += s[j] * (q[10] * s[j] - 2 * (gj[0] * x + gj[1] * y + gj[2] * z + D[j]));
  }
  return e;
}

/// Calls run(std::integral_constant<int, N>()) with N the attribute count as a constant for
/// the simplifier's counts (nothing, normals, colors, both), -1 for any other: the attribute
/// loops of the With functions then unroll.
template <typename Run>
inline decltype(auto) WithAttributeCount(int attributes, Run&& run)
{
  switch (attributes)
  {
    case 0:
      return run(std::integral_constant<int, 0>());
    case 3:
      return run(std::integral_constant<int, 3>());
    case 4:
      return run(std::integral_constant<int, 4>());
    case 7:
      return run(std::integral_constant<int, 7>());
    default:
      return run(std::integral_constant<int, -1>());
  }
}

/// Q(p, s) for any attribute count.
inline double Evaluate(const double* q, int attributes, const double p[3], const double* s)
{
  return WithAttributeCount(attributes,
    [&](auto fixed) { return EvaluateWith<decltype(fixed)::value>(q, attributes, p, s); });
}

} // namespace Quadric

} // namespace atp

#endif
