#include "atpMemberLocator.h"

#include <algorithm>
#include <cmath>

namespace atp
{

namespace
{
/// A barycentric coordinate above this puts a point inside its member whatever the rounding.
constexpr double ClearlyInside = 1e-6;
/// DeepMemberOf's margin: a convex combination of points this far inside a member is still
/// above ClearlyInside after rounding (about 1e-13 here).
constexpr double DeeplyInside = 2 * ClearlyInside;
}

MemberLocator::MemberLocator(const std::vector<Tetra>& members, const LatticeFrame& frame)
  : Frame(frame)
{
  for (const Tetra& t : members)
  {
    // Solve p = v0 + M * (b1, b2, b3) for the barycentrics b1..b3 (b0 = 1 - b1 - b2 - b3).
    double m[3][3];
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        m[r][c] = double(t.V[c + 1][r]) - double(t.V[0][r]);
      }
    }
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
      m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
      m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    double inv[3][3];
    inv[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
    inv[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
    inv[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
    inv[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
    inv[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
    inv[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
    inv[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
    inv[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
    inv[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
    Barycentric b;
    for (int r = 0; r < 3; ++r)
    {
      // b_{r+1} = inv[r] . (p - v0)
      double offset = 0;
      for (int c = 0; c < 3; ++c)
      {
        b.Rows[r + 1][c] = inv[r][c];
        offset -= inv[r][c] * double(t.V[0][c]);
      }
      b.Rows[r + 1][3] = offset;
    }
    for (int c = 0; c < 4; ++c)
    {
      b.Rows[0][c] = (c == 3 ? 1.0 : 0.0) - b.Rows[1][c] - b.Rows[2][c] - b.Rows[3][c];
    }
    Members.push_back(b);
  }
}

double MemberLocator::Inside(std::size_t m, const double q[3]) const
{
  double inside = INFINITY;
  for (const auto& row : Members[m].Rows)
  {
    inside = std::min(inside, row[0] * q[0] + row[1] * q[1] + row[2] * q[2] + row[3]);
  }
  return inside;
}

void MemberLocator::ToLattice(const double p[3], double q[3]) const
{
  const double scale = Frame.Scale();
  for (int a = 0; a < 3; ++a)
  {
    q[a] = (p[a] - Frame.Origin()[a]) * scale;
  }
}

int MemberLocator::MemberOf(const double p[3], int likely) const
{
  double q[3];
  ToLattice(p, q);
  if (likely >= 0 && std::size_t(likely) < Members.size() && Inside(std::size_t(likely), q) > ClearlyInside)
  {
    return likely;
  }
  int best = 0;
  double bestInside = -INFINITY;
  for (std::size_t m = 0; m < Members.size(); ++m)
  {
    const double inside = Inside(m, q);
    // Well inside one member (rounding is about 1e-13 here): no other can beat it.
    if (inside > ClearlyInside)
    {
      return int(m);
    }
    if (inside > bestInside)
    {
      bestInside = inside;
      best = int(m);
    }
  }
  return best;
}

int MemberLocator::DeepMemberOf(const double p[3], int likely) const
{
  double q[3];
  ToLattice(p, q);
  if (likely >= 0 && std::size_t(likely) < Members.size() && Inside(std::size_t(likely), q) > DeeplyInside)
  {
    return likely;
  }
  // Members' interiors are disjoint: at most one holds p this deeply.
  for (std::size_t m = 0; m < Members.size(); ++m)
  {
    if (Inside(m, q) > DeeplyInside)
    {
      return int(m);
    }
  }
  return -1;
}

} // namespace atp
