#include "atpTetra.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace atp
{
namespace
{
using Wide = std::int64_t;

Wide SquaredLength(const LatticePoint& a, const LatticePoint& b)
{
  Wide s = 0;
  for (int k = 0; k < 3; ++k)
  {
    const Wide d = Wide(b[k]) - a[k];
    s += d * d;
  }
  return s;
}

LatticePoint Midpoint(const LatticePoint& a, const LatticePoint& b)
{
  return { (a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2 };
}

// Orientation of d relative to the plane through a, b, c (positive: one side, negative: the
// other). Doubles: lattice coordinates are at most 2^20, products of three differences stay
// far below 2^63 and the sign only decides a side, consistently for a given input.
double Orientation(const LatticePoint& a, const LatticePoint& b, const LatticePoint& c,
  const double d[3])
{
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = double(b[k]) - a[k];
    v[k] = double(c[k]) - a[k];
    w[k] = d[k] - a[k];
  }
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
    u[2] * (v[0] * w[1] - v[1] * w[0]);
}

std::array<double, 3> ToDouble(const LatticePoint& p)
{
  return { double(p[0]), double(p[1]), double(p[2]) };
}

// Axis orders of the six roots: root r holds the points with p[i] >= p[j] >= p[k].
constexpr int RootAxes[RootCount][3] = { { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 },
  { 2, 0, 1 }, { 2, 1, 0 } };

bool InsideCube(const LatticePoint& p)
{
  for (int k = 0; k < 3; ++k)
  {
    if (p[k] < 0 || p[k] > LatticeSize)
    {
      return false;
    }
  }
  return true;
}
} // namespace

Tetra MakeCanonical(const std::array<LatticePoint, 4>& p)
{
  static constexpr int Edges[6][4] = { { 0, 1, 2, 3 }, { 0, 2, 1, 3 }, { 0, 3, 1, 2 },
    { 1, 2, 0, 3 }, { 1, 3, 0, 2 }, { 2, 3, 0, 1 } };
  int longest = 0;
  Wide longestLength = -1;
  for (int e = 0; e < 6; ++e)
  {
    const Wide l = SquaredLength(p[Edges[e][0]], p[Edges[e][1]]);
    if (l > longestLength)
    {
      longestLength = l;
      longest = e;
    }
  }
  const int* e = Edges[longest];
  Tetra t{ { p[e[0]], p[e[1]], p[e[2]], p[e[3]] } };
  if (t.V[1] < t.V[0])
  {
    std::swap(t.V[0], t.V[1]);
  }
  if (t.V[3] < t.V[2])
  {
    std::swap(t.V[2], t.V[3]);
  }
  return t;
}

LatticePoint Tetra::SplitPoint() const
{
  return Midpoint(V[0], V[1]);
}

Tetra Tetra::Child(int which) const
{
  return MakeCanonical({ V[std::size_t(which & 1)], SplitPoint(), V[2], V[3] });
}

SplitPlane Tetra::Plane() const
{
  // Normal = (V2 - m) x (V3 - m): integer differences below 2^21, so every product is exact.
  const LatticePoint m = SplitPoint();
  std::int64_t u[3], v[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = std::int64_t(V[2][k]) - m[k];
    v[k] = std::int64_t(V[3][k]) - m[k];
  }
  std::int64_t n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
    u[0] * v[1] - u[1] * v[0] };
  // Its nonzero components share one magnitude (the plane is x_i = c or x_i +- x_j = c).
  const std::int64_t magnitude = std::max({ std::abs(n[0]), std::abs(n[1]), std::abs(n[2]) });
  if (magnitude == 0)
  {
    throw std::logic_error("atp::Tetra::Plane: the deepest level has no split plane");
  }
  std::int64_t side = 0;
  for (int k = 0; k < 3; ++k)
  {
    if (n[k] != 0 && std::abs(n[k]) != magnitude)
    {
      throw std::logic_error("atp::Tetra::Plane: a split plane outside the Kuhn family");
    }
    n[k] /= magnitude;
    side += n[k] * (std::int64_t(V[0][k]) - m[k]);
  }
  const std::int64_t orientation = side < 0 ? -1 : 1;
  SplitPlane plane;
  plane.Offset = 0;
  for (int k = 0; k < 3; ++k)
  {
    plane.Normal[k] = std::int8_t(orientation * n[k]);
    plane.Offset += plane.Normal[k] * m[k];
  }
  return plane;
}

bool Tetra::Contains(const double p[3]) const
{
  for (const auto& f : Faces)
  {
    const auto opposite = ToDouble(V[f[3]]);
    const double s = Orientation(V[f[0]], V[f[1]], V[f[2]], opposite.data());
    const double q = Orientation(V[f[0]], V[f[1]], V[f[2]], p);
    if (q != 0 && (q > 0) != (s > 0))
    {
      return false;
    }
  }
  return true;
}

double Tetra::Volume() const
{
  const auto d = ToDouble(V[3]);
  return std::abs(Orientation(V[0], V[1], V[2], d.data())) / 6.0;
}

std::array<double, 3> Tetra::Centroid() const
{
  std::array<double, 3> c{};
  for (const auto& v : V)
  {
    for (int k = 0; k < 3; ++k)
    {
      c[k] += 0.25 * v[k];
    }
  }
  return c;
}

Tetra RootTetra(int root)
{
  const int* axes = RootAxes[root];
  LatticePoint p1{ 0, 0, 0 };
  p1[axes[0]] = LatticeSize;
  LatticePoint p2 = p1;
  p2[axes[1]] = LatticeSize;
  return MakeCanonical(
    { LatticePoint{ 0, 0, 0 }, p1, p2, LatticePoint{ LatticeSize, LatticeSize, LatticeSize } });
}

Tetra TetraOf(TetId id)
{
  Tetra t = RootTetra(id.RootIndex());
  for (int bit = id.Level() - 1; bit >= 0; --bit)
  {
    t = t.Child(int((id.Bits >> bit) & 1u));
  }
  return t;
}

int RootContaining(const double p[3])
{
  for (int r = 0; r < RootCount; ++r)
  {
    const int* a = RootAxes[r];
    if (p[a[0]] >= p[a[1]] && p[a[1]] >= p[a[2]])
    {
      return r;
    }
  }
  return 0; // unreachable for finite p: some axis order always holds
}

TetId Locate(const double p[3], int level)
{
  const int root = RootContaining(p);
  TetId id = TetId::Root(root);
  Tetra t = RootTetra(root);
  for (int l = 0; l < level; ++l)
  {
    const int c = t.ChildContaining(p);
    t = t.Child(c);
    id = id.Child(c);
  }
  return id;
}

DiamondId DiamondOf(const Tetra& t)
{
  const LatticePoint c = t.SplitPoint();
  return DiamondId{ std::uint64_t(c[0]) | (std::uint64_t(c[1]) << 21) |
    (std::uint64_t(c[2]) << 42) };
}

LatticePoint DiamondCenter(DiamondId d)
{
  constexpr std::uint64_t mask = (std::uint64_t(1) << 21) - 1;
  return { std::int32_t(d.Bits & mask), std::int32_t((d.Bits >> 21) & mask),
    std::int32_t((d.Bits >> 42) & mask) };
}

DiamondType TypeOf(const Tetra& t)
{
  int nonZero = 0;
  for (int k = 0; k < 3; ++k)
  {
    nonZero += t.V[1][k] != t.V[0][k];
  }
  return nonZero == 3 ? DiamondType::CubeDiagonal
                      : (nonZero == 2 ? DiamondType::FaceDiagonal : DiamondType::AxisEdge);
}

int FullMemberCount(DiamondType type)
{
  switch (type)
  {
    case DiamondType::CubeDiagonal:
      return 6;
    case DiamondType::FaceDiagonal:
      return 4;
    case DiamondType::AxisEdge:
      return 8;
  }
  return 0;
}

std::vector<TetId> DiamondMembers(TetId id)
{
  const Tetra t = TetraOf(id);
  const LatticePoint a = t.V[0], b = t.V[1], m = t.SplitPoint();
  LatticePoint d;
  for (int k = 0; k < 3; ++k)
  {
    d[k] = b[k] - a[k];
  }
  auto offset = [](LatticePoint p, int axis, std::int32_t delta) {
    p[axis] += delta;
    return p;
  };

  // The opposite edges of all members, from the shape of the three diamond types (figure 3c).
  std::vector<std::array<LatticePoint, 2>> opposite;
  switch (TypeOf(t))
  {
    case DiamondType::CubeDiagonal:
      // A monotone axis path from a to b, in each of the six axis orders.
      for (const auto& axes : RootAxes)
      {
        const LatticePoint p = offset(a, axes[0], d[axes[0]]);
        opposite.push_back({ p, offset(p, axes[1], d[axes[1]]) });
      }
      break;
    case DiamondType::FaceDiagonal:
    {
      const int k = d[0] == 0 ? 0 : (d[1] == 0 ? 1 : 2);
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      const std::int32_t g = std::abs(d[i]) / 2;
      for (const LatticePoint& corner : { offset(a, i, d[i]), offset(a, j, d[j]) })
      {
        for (const std::int32_t side : { -g, g })
        {
          opposite.push_back({ corner, offset(m, k, side) });
        }
      }
      break;
    }
    case DiamondType::AxisEdge:
    {
      const int i = d[0] != 0 ? 0 : (d[1] != 0 ? 1 : 2);
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      const std::int32_t g = std::abs(d[i]) / 2;
      for (const std::int32_t s : { -g, g })
      {
        for (const std::int32_t u : { -g, g })
        {
          const LatticePoint cubeCenter = offset(offset(m, j, s), k, u);
          opposite.push_back({ offset(m, j, s), cubeCenter });
          opposite.push_back({ offset(m, k, u), cubeCenter });
        }
      }
      break;
    }
  }

  std::vector<TetId> members;
  for (const auto& e : opposite)
  {
    if (!InsideCube(e[0]) || !InsideCube(e[1]))
    {
      continue;
    }
    const Tetra member = MakeCanonical({ a, b, e[0], e[1] });
    const auto c = member.Centroid();
    const TetId memberId = Locate(c.data(), id.Level());
    if (!(TetraOf(memberId) == member))
    {
      throw std::logic_error("atp::DiamondMembers: diamond geometry disagrees with the hierarchy");
    }
    members.push_back(memberId);
  }
  std::sort(members.begin(), members.end());
  return members;
}

std::uint64_t MortonCode(std::uint32_t x, std::uint32_t y, std::uint32_t z)
{
  const auto spread = [](std::uint64_t v) {
    // Spreads 21 bits so that two zero bits separate each.
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
  };
  return spread(x) | spread(y) << 1 | spread(z) << 2;
}

std::uint64_t CentroidMorton(const Tetra& t)
{
  std::uint32_t c[3];
  for (int k = 0; k < 3; ++k)
  {
    const Wide sum = Wide(t.V[0][k]) + t.V[1][k] + t.V[2][k] + t.V[3][k];
    c[k] = std::uint32_t(sum / 4);
  }
  return MortonCode(c[0], c[1], c[2]);
}

LatticeFrame::LatticeFrame(const double boxMin[3], const double boxMax[3])
{
  double extent = 0;
  for (int k = 0; k < 3; ++k)
  {
    Origin_[k] = boxMin[k];
    extent = std::max(extent, boxMax[k] - boxMin[k]);
  }
  if (!(extent > 0))
  {
    extent = 1; // a single point or a flat box still gets a valid cube
  }
  // A hair of slack so that points at the box maximum round into the cube.
  Scale_ = LatticeSize / (extent * (1 + 1e-9));
}

void LatticeFrame::ToLattice(const float p[3], double out[3]) const
{
  for (int k = 0; k < 3; ++k)
  {
    out[k] = std::min(double(LatticeSize), std::max(0.0, (p[k] - Origin_[k]) * Scale_));
  }
}

void LatticeFrame::ToWorld(const LatticePoint& q, double out[3]) const
{
  for (int k = 0; k < 3; ++k)
  {
    out[k] = Origin_[k] + q[k] / Scale_;
  }
}

} // namespace atp
