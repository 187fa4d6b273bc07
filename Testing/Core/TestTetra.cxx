// The tetrahedron hierarchy: ids, exact geometry, bisection, diamonds, point location, Morton.
#include "atpTetra.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

using namespace atp;

namespace
{
std::int64_t SquaredLength(const LatticePoint& a, const LatticePoint& b)
{
  std::int64_t s = 0;
  for (int k = 0; k < 3; ++k)
  {
    const std::int64_t d = std::int64_t(b[k]) - a[k];
    s += d * d;
  }
  return s;
}

/// Every tetrahedron of the full tree down to `level`.
std::vector<TetId> AllAtLevel(int level)
{
  std::vector<TetId> ids;
  for (int r = 0; r < RootCount; ++r)
  {
    ids.push_back(TetId::Root(r));
  }
  for (int l = 0; l < level; ++l)
  {
    std::vector<TetId> next;
    for (const TetId id : ids)
    {
      next.push_back(id.Child(0));
      next.push_back(id.Child(1));
    }
    ids.swap(next);
  }
  return ids;
}

TetId RandomPath(std::mt19937_64& rng, int level)
{
  TetId id = TetId::Root(int(rng() % RootCount));
  for (int l = 0; l < level; ++l)
  {
    id = id.Child(int(rng() & 1));
  }
  return id;
}
} // namespace

TEST(TetId, EncodesRootLevelAndPath)
{
  for (int r = 0; r < RootCount; ++r)
  {
    TetId id = TetId::Root(r);
    EXPECT_EQ(id.Level(), 0);
    EXPECT_EQ(id.RootIndex(), r);
    EXPECT_TRUE(id.IsValid());
    for (int l = 1; l <= MaxLevel; ++l)
    {
      const int which = (l * 7 + r) % 2;
      const TetId child = id.Child(which);
      EXPECT_EQ(child.Level(), l);
      EXPECT_EQ(child.RootIndex(), r);
      EXPECT_EQ(child.ChildIndex(), which);
      EXPECT_EQ(child.Parent(), id);
      id = child;
    }
  }
  EXPECT_FALSE(TetId{ 0 }.IsValid());
  EXPECT_FALSE(TetId{ 15 }.IsValid()); // root index 7 does not exist
}

TEST(Tetra, RootsTileTheCube)
{
  double volume = 0;
  for (int r = 0; r < RootCount; ++r)
  {
    const Tetra t = RootTetra(r);
    EXPECT_EQ(t.V[0], (LatticePoint{ 0, 0, 0 }));
    EXPECT_EQ(t.V[1], (LatticePoint{ LatticeSize, LatticeSize, LatticeSize }));
    volume += t.Volume();
  }
  EXPECT_DOUBLE_EQ(volume, double(LatticeSize) * LatticeSize * LatticeSize);
}

TEST(Tetra, LongestEdgeIsUniqueAndBisectionIsExact)
{
  std::mt19937_64 rng(1);
  for (int trial = 0; trial < 300; ++trial)
  {
    const TetId id = RandomPath(rng, MaxLevel);
    Tetra t = RootTetra(id.RootIndex());
    for (int bit = id.Level() - 1; bit >= 0; --bit)
    {
      const std::int64_t split = SquaredLength(t.V[0], t.V[1]);
      const std::int64_t others[] = { SquaredLength(t.V[0], t.V[2]), SquaredLength(t.V[0], t.V[3]),
        SquaredLength(t.V[1], t.V[2]), SquaredLength(t.V[1], t.V[3]),
        SquaredLength(t.V[2], t.V[3]) };
      for (const std::int64_t o : others)
      {
        ASSERT_LT(o, split) << "longest edge not unique at level " << id.Level() - bit - 1;
      }
      const LatticePoint m = t.SplitPoint();
      for (int k = 0; k < 3; ++k)
      {
        ASSERT_EQ(2 * std::int64_t(m[k]), std::int64_t(t.V[0][k]) + t.V[1][k]) << "midpoint off lattice";
      }
      const auto children = t.Children();
      EXPECT_NEAR(children[0].Volume() + children[1].Volume(), t.Volume(), 1e-9 * t.Volume());
      EXPECT_NEAR(children[0].Volume(), children[1].Volume(), 1e-9 * t.Volume());
      t = children[(id.Bits >> bit) & 1u];
    }
    EXPECT_EQ(t, TetraOf(id));
  }
}

TEST(Tetra, SplitPlaneIsOneOfTheKuhnPlanesAndSeparatesTheChildren)
{
  // The compact plane (normal of -1, 0, 1, integer offset) must be the exact bisecting plane
  // at every depth: through the split point and the opposite edge, V[0] on child 0's side.
  std::mt19937_64 rng(5);
  const auto value = [](const SplitPlane& plane, const LatticePoint& p) {
    std::int64_t s = -std::int64_t(plane.Offset);
    for (int k = 0; k < 3; ++k)
    {
      s += std::int64_t(plane.Normal[k]) * p[k];
    }
    return s;
  };
  for (int trial = 0; trial < 200; ++trial)
  {
    const TetId id = RandomPath(rng, MaxLevel);
    Tetra t = RootTetra(id.RootIndex());
    for (int bit = id.Level() - 1; bit >= 0; --bit)
    {
      const SplitPlane plane = t.Plane();
      int nonzero = 0;
      for (const std::int8_t n : plane.Normal)
      {
        ASSERT_LE(std::abs(int(n)), 1);
        nonzero += n != 0;
      }
      ASSERT_GE(nonzero, 1);
      ASSERT_LE(nonzero, 2);
      ASSERT_EQ(value(plane, t.SplitPoint()), 0);
      ASSERT_EQ(value(plane, t.V[2]), 0);
      ASSERT_EQ(value(plane, t.V[3]), 0);
      ASSERT_GT(value(plane, t.V[0]), 0);
      ASSERT_LT(value(plane, t.V[1]), 0);
      for (int c = 0; c < 2; ++c)
      {
        const std::array<double, 3> centroid = t.Child(c).Centroid();
        ASSERT_EQ(plane.ChildContaining(centroid.data()), c);
      }
      t = t.Child(int((id.Bits >> bit) & 1u));
    }
  }
}

TEST(Tetra, ShapesRepeatEveryThreeLevels)
{
  // Longest-edge bisection of the Kuhn cube split yields similar tetrahedra: the split edge
  // shrinks by half every three levels, so cells never degenerate.
  std::mt19937_64 rng(2);
  for (int trial = 0; trial < 50; ++trial)
  {
    const TetId id = RandomPath(rng, MaxLevel);
    for (int l = 0; l + 3 <= MaxLevel; ++l)
    {
      const TetId a{ id.Bits >> (MaxLevel - l) }, b{ id.Bits >> (MaxLevel - l - 3) };
      const Tetra ta = TetraOf(a), tb = TetraOf(b);
      EXPECT_EQ(SquaredLength(ta.V[0], ta.V[1]), 4 * SquaredLength(tb.V[0], tb.V[1]));
      EXPECT_EQ(static_cast<int>(TypeOf(ta)), l % 3);
    }
  }
}

TEST(Diamond, MembersShareTheSplitEdgeAndCountsAreRight)
{
  for (int level = 0; level <= 9; ++level)
  {
    // Group the whole level by split edge, independently of DiamondMembers.
    std::map<DiamondId, std::set<TetId>> groups;
    for (const TetId id : AllAtLevel(level))
    {
      groups[DiamondOf(TetraOf(id))].insert(id);
    }
    std::map<int, int> interiorCounts;
    for (const auto& [diamond, group] : groups)
    {
      const TetId first = *group.begin();
      const Tetra t = TetraOf(first);
      const std::vector<TetId> members = DiamondMembers(first);
      EXPECT_EQ(std::set<TetId>(members.begin(), members.end()), group);
      for (const TetId m : members)
      {
        const Tetra mt = TetraOf(m);
        EXPECT_EQ(mt.V[0], t.V[0]);
        EXPECT_EQ(mt.V[1], t.V[1]);
        EXPECT_EQ(m.Level(), level);
        EXPECT_EQ(DiamondMembers(m), members);
      }
      EXPECT_EQ(DiamondCenter(diamond), t.SplitPoint());
      const DiamondType type = TypeOf(t);
      EXPECT_EQ(static_cast<int>(type), level % 3);
      ASSERT_LE(int(members.size()), FullMemberCount(type));
      // Away from the cube's faces a diamond is complete.
      const LatticePoint c = t.SplitPoint();
      const std::int64_t reach = std::max({ std::abs(t.V[1][0] - t.V[0][0]),
        std::abs(t.V[1][1] - t.V[0][1]), std::abs(t.V[1][2] - t.V[0][2]) });
      bool interior = true;
      for (int k = 0; k < 3; ++k)
      {
        interior = interior && c[k] - reach >= 0 && c[k] + reach <= LatticeSize;
      }
      if (interior)
      {
        EXPECT_EQ(int(members.size()), FullMemberCount(type));
        ++interiorCounts[int(members.size())];
      }
    }
    if (level == 0)
    {
      EXPECT_EQ(groups.size(), 1u); // one diamond: the six roots
    }
  }
}

TEST(Diamond, DeepMembersExist)
{
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 200; ++trial)
  {
    const TetId id = RandomPath(rng, int(rng() % (MaxLevel + 1)));
    const auto members = DiamondMembers(id);
    EXPECT_NE(std::find(members.begin(), members.end(), id), members.end());
    const Tetra t = TetraOf(id);
    for (const TetId m : members)
    {
      EXPECT_EQ(DiamondOf(TetraOf(m)), DiamondOf(t));
    }
  }
}

TEST(Locate, FindsTheTetrahedronHoldingAPoint)
{
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> coordinate(0, LatticeSize);
  for (int trial = 0; trial < 2000; ++trial)
  {
    const double p[3] = { coordinate(rng), coordinate(rng), coordinate(rng) };
    const int level = int(rng() % (MaxLevel + 1));
    const TetId id = Locate(p, level);
    EXPECT_EQ(id.Level(), level);
    EXPECT_TRUE(TetraOf(id).Contains(p));
    if (level > 0)
    {
      EXPECT_EQ(Locate(p, level - 1), id.Parent());
    }
  }
  // Corners and the center are located too (ties go to a deterministic side).
  const double corner[3] = { double(LatticeSize), 0, double(LatticeSize) };
  EXPECT_TRUE(TetraOf(Locate(corner, 30)).Contains(corner));
}

TEST(Morton, OrdersCentroidsAlongTheZCurve)
{
  const std::vector<TetId> level6 = AllAtLevel(6);
  std::set<std::uint64_t> codes;
  for (const TetId id : level6)
  {
    codes.insert(CentroidMorton(TetraOf(id)));
  }
  EXPECT_EQ(codes.size(), level6.size()); // distinct centroids, distinct codes
  Tetra lowCorner = RootTetra(0), highCorner = RootTetra(0);
  for (auto& v : lowCorner.V)
  {
    v = { v[0] / 4, v[1] / 4, v[2] / 4 };
  }
  for (auto& v : highCorner.V)
  {
    v = { LatticeSize - v[0] / 4, LatticeSize - v[1] / 4, LatticeSize - v[2] / 4 };
  }
  EXPECT_LT(CentroidMorton(lowCorner), CentroidMorton(highCorner));
}

TEST(LatticeFrame, MapsTheBoxIntoTheCube)
{
  const double lo[3] = { -1, 2, 10 }, hi[3] = { 3, 2.5, 10.25 };
  const LatticeFrame frame(lo, hi);
  const float corners[2][3] = { { -1, 2, 10 }, { 3, 2.5f, 10.25f } };
  double q[3];
  frame.ToLattice(corners[0], q);
  EXPECT_EQ(q[0], 0);
  frame.ToLattice(corners[1], q);
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_LE(q[k], LatticeSize);
  }
  EXPECT_NEAR(q[0], LatticeSize, 1);
  // A flat or single-point box still maps.
  const LatticeFrame flat(lo, lo);
  flat.ToLattice(corners[0], q);
  EXPECT_EQ(q[2], 0);
}
