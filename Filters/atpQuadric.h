// Quadric error metrics for the simplifier: Garland-Heckbert plane quadrics and Hoppe's (1999)
// attribute extension, where each attribute varies linearly over the plane of its triangle.
// Plain C++, header only: the simplifier evaluates these in its innermost loop.
#ifndef atpQuadric_h
#define atpQuadric_h

#include <cstddef>

namespace atp
{

/// Sum of weighted squared distances to planes: Q(p) = p'Ap + 2b'p + c.
struct Quadric
{
  double A00 = 0, A01 = 0, A02 = 0, A11 = 0, A12 = 0, A22 = 0;
  double B0 = 0, B1 = 0, B2 = 0;
  double C = 0;

  /// The plane n.p + d = 0 (n of unit length), with weight w.
  void AddPlane(const double n[3], double d, double w)
  {
    A00 += w * n[0] * n[0];
    A01 += w * n[0] * n[1];
    A02 += w * n[0] * n[2];
    A11 += w * n[1] * n[1];
    A12 += w * n[1] * n[2];
    A22 += w * n[2] * n[2];
    B0 += w * d * n[0];
    B1 += w * d * n[1];
    B2 += w * d * n[2];
    C += w * d * d;
  }

  void Add(const Quadric& q)
  {
    A00 += q.A00;
    A01 += q.A01;
    A02 += q.A02;
    A11 += q.A11;
    A12 += q.A12;
    A22 += q.A22;
    B0 += q.B0;
    B1 += q.B1;
    B2 += q.B2;
    C += q.C;
  }

  double Evaluate(const double p[3]) const
  {
    const double x = p[0], y = p[1], z = p[2];
    return x * (A00 * x + 2 * (A01 * y + A02 * z + B0)) + y * (A11 * y + 2 * (A12 * z + B1)) +
      z * (A22 * z + 2 * B2) + C;
  }
};

/// The attribute half of Hoppe's quadric, stored flat as W, then G (3 per attribute), then D
/// (one per attribute): Stride(m) doubles for m attributes. An attribute s with the linear field
/// s(p) = g.p + d over a triangle of weight w contributes w (g.p + d - s)^2; its p'gg'p, d g and
/// d^2 terms go into the position Quadric, the rest is kept here.
namespace AttributeQuadric
{

inline std::size_t Stride(int attributes)
{
  return 1 + 4 * std::size_t(attributes);
}

/// Adds the triangle of plane quadric `q` and attribute part `a` whose attribute j has the
/// field g[3j..3j+3), d[j], weighted by w.
inline void AddField(Quadric& q, double* a, int attributes, const double* g, const double* d, double w)
{
  a[0] += w;
  double* G = a + 1;
  double* D = G + 3 * attributes;
  for (int j = 0; j < attributes; ++j)
  {
    const double* gj = g + 3 * j;
    q.A00 += w * gj[0] * gj[0];
    q.A01 += w * gj[0] * gj[1];
    q.A02 += w * gj[0] * gj[2];
    q.A11 += w * gj[1] * gj[1];
    q.A12 += w * gj[1] * gj[2];
    q.A22 += w * gj[2] * gj[2];
    q.B0 += w * d[j] * gj[0];
    q.B1 += w * d[j] * gj[1];
    q.B2 += w * d[j] * gj[2];
    q.C += w * d[j] * d[j];
    G[3 * j] += w * gj[0];
    G[3 * j + 1] += w * gj[1];
    G[3 * j + 2] += w * gj[2];
    D[j] += w * d[j];
  }
}

inline void Add(double* a, const double* b, int attributes)
{
  for (std::size_t i = 0, n = Stride(attributes); i < n; ++i)
  {
    a[i] += b[i];
  }
}

/// The attribute terms of the full quadric at position p with attribute values s; add the
/// position Quadric's Evaluate(p) for the whole error.
inline double Evaluate(const double* a, int attributes, const double p[3], const double* s)
{
  const double* G = a + 1;
  const double* D = G + 3 * attributes;
  double e = 0;
  for (int j = 0; j < attributes; ++j)
  {
    const double* gj = G + 3 * j;
    e += s[j] * (a[0] * s[j] - 2 * (gj[0] * p[0] + gj[1] * p[1] + gj[2] * p[2] + D[j]));
  }
  return e;
}

} // namespace AttributeQuadric

} // namespace atp

#endif
