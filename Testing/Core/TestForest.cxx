// Conformity of diamond refinement, proven by an exact face-matching check and by TetGen, and
// the same checks rejecting cuts that break a diamond; locating points in a diamond's members.
#include "ConformityCheck.h"
#include "ProcessMemory.h"
#include "atpMemberLocator.h"
#include "atpTetraForest.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include <random>
#include <vector>

using namespace atp;
using atp::testing::FaceMatchingProblem;
using atp::testing::TetGenProblem;

namespace
{
std::vector<Tetra> LeafGeometry(const TetraForest& forest)
{
  std::vector<Tetra> tets;
  for (const auto leaf : forest.Leaves())
  {
    tets.push_back(forest.Geometry(leaf));
  }
  return tets;
}

/// Refines random leaves (biased to a random spot so depth varies a lot across the cube).
TetraForest RandomRefinement(unsigned seed, int splits)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> coordinate(0, LatticeSize);
  const double focus[3] = { coordinate(rng), coordinate(rng), coordinate(rng) };
  TetraForest forest;
  for (int s = 0; s < splits; ++s)
  {
    double p[3];
    const bool nearFocus = rng() % 2 == 0;
    for (int k = 0; k < 3; ++k)
    {
      p[k] = nearFocus ? std::min<double>(LatticeSize, std::abs(focus[k] + coordinate(rng) / 64 -
                                                            LatticeSize / 128.0))
                       : coordinate(rng);
    }
    forest.SplitDiamond(forest.LeafContaining(p), [](TetraForest::NodeIndex) {});
  }
  return forest;
}
} // namespace

// A billion-triangle forest has millions of nodes: their pages leave the process when it says
// so, and come back unchanged.
TEST(Forest, ReleasedNodesLeaveMemoryAndReadBackTheSame)
{
  const TetraForest forest = RandomRefinement(21, 20000);
  ASSERT_GT(forest.Size(), 200000u); // several MiB of nodes
  std::vector<std::uint64_t> ids(forest.Size());
  for (std::size_t n = 0; n < forest.Size(); ++n)
  {
    ids[n] = forest[TetraForest::NodeIndex(n)].Id.Bits;
  }
  const std::vector<TetraForest::NodeIndex> leaves = forest.Leaves();
  const long before = atp::testing::MappedFileKiB();
  forest.ReleaseResident();
  const long after = atp::testing::MappedFileKiB();
  // Nearly all of it: other mapped files (code) may come in meanwhile.
  EXPECT_GE(before - after, long(forest.Size() * sizeof(TetraForest::Node) / 1024) * 9 / 10)
    << before << " -> " << after << " KiB";
  EXPECT_EQ(forest.Leaves(), leaves);
  for (std::size_t n = 0; n < forest.Size(); ++n)
  {
    ASSERT_EQ(forest[TetraForest::NodeIndex(n)].Id.Bits, ids[n]) << n;
  }
}

TEST(Forest, StartsWithSixRootsThatConform)
{
  TetraForest forest;
  EXPECT_EQ(forest.Size(), 6u);
  EXPECT_EQ(forest.Leaves().size(), 6u);
  EXPECT_EQ(FaceMatchingProblem(LeafGeometry(forest)), "");
  EXPECT_EQ(TetGenProblem(LeafGeometry(forest)), "");
}

TEST(Forest, RandomDiamondRefinementsConform)
{
  for (unsigned seed = 1; seed <= 8; ++seed)
  {
    const TetraForest forest = RandomRefinement(seed, 40 + 25 * int(seed));
    const auto tets = LeafGeometry(forest);
    EXPECT_GE(forest.Depth(), 6) << "seed " << seed;
    EXPECT_EQ(FaceMatchingProblem(tets), "") << "seed " << seed;
    EXPECT_EQ(TetGenProblem(tets), "") << "seed " << seed;
  }
}

TEST(Forest, SplitsWholeDiamondsParentsFirst)
{
  TetraForest forest;
  std::vector<TetraForest::NodeIndex> order;
  const double p[3] = { 1000.5, 2000.25, 3000.125 };
  for (int s = 0; s < 60; ++s)
  {
    forest.SplitDiamond(
      forest.LeafContaining(p), [&](TetraForest::NodeIndex n) { order.push_back(n); });
  }
  std::vector<bool> seen(forest.Size(), false);
  for (const auto n : order)
  {
    // A node is split only after its parent.
    const auto parent = forest[n].Parent;
    EXPECT_TRUE(parent == TetraForest::None || seen[std::size_t(parent)]);
    seen[std::size_t(n)] = true;
    // All of its diamond is split too.
    for (const TetId member : DiamondMembers(forest[n].Id))
    {
      const auto m = forest.Find(member);
      ASSERT_NE(m, TetraForest::None);
      EXPECT_FALSE(forest[m].IsLeaf());
    }
  }
  EXPECT_EQ(forest.Depth(), 60);
  EXPECT_EQ(forest[forest.LeafContaining(p)].Id.Level(), 60);
  EXPECT_FALSE(forest.SplitDiamond(forest.LeafContaining(p), [](TetraForest::NodeIndex) {}))
    << "the deepest level cannot split";
  EXPECT_EQ(FaceMatchingProblem(LeafGeometry(forest)), "");
}

TEST(Forest, FindAndLocateAgree)
{
  const TetraForest forest = RandomRefinement(11, 120);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> coordinate(0, LatticeSize);
  for (int trial = 0; trial < 500; ++trial)
  {
    const double p[3] = { coordinate(rng), coordinate(rng), coordinate(rng) };
    const auto leaf = forest.LeafContaining(p);
    ASSERT_TRUE(forest[leaf].IsLeaf());
    EXPECT_TRUE(forest.Geometry(leaf).Contains(p));
    EXPECT_EQ(forest.Find(forest[leaf].Id), leaf);
    EXPECT_EQ(Locate(p, forest[leaf].Id.Level()), forest[leaf].Id);
  }
  // The batch location agrees with one descent at a time: on random points (interleaved
  // descents, an odd count: a tail too), on a random walk (mostly the hint's leaf) and on the
  // leaves' own corners and face centers, where the hint must step back for the descent's rule,
  // each followed by its leaf's centroid (a hit right after a miss).
  std::vector<std::array<double, 3>> points(1001);
  for (auto& p : points)
  {
    p = { coordinate(rng), coordinate(rng), coordinate(rng) };
  }
  std::array<double, 3> walker = points[0];
  std::normal_distribution<double> step(0, LatticeSize / 4000.0);
  for (int i = 0; i < 3000; ++i)
  {
    for (double& x : walker)
    {
      x = std::min(double(LatticeSize), std::max(0.0, x + step(rng)));
    }
    points.push_back(walker);
  }
  for (const auto leaf : forest.Leaves())
  {
    const Tetra t = forest.Geometry(leaf);
    for (int v = 0; v < 4; ++v)
    {
      const std::array<double, 3> corner = { double(t.V[std::size_t(v)][0]), double(t.V[std::size_t(v)][1]), double(t.V[std::size_t(v)][2]) };
      points.push_back(corner);
      std::array<double, 3> face{};
      for (int w = 0; w < 4; ++w)
      {
        for (int a = 0; a < 3 && w != v; ++a)
        {
          face[std::size_t(a)] += t.V[std::size_t(w)][std::size_t(a)] / 3.0;
        }
      }
      points.push_back(forest.Geometry(leaf).Centroid());
      points.push_back(face);
    }
  }
  std::vector<TetraForest::NodeIndex> leaves(points.size());
  TetraForest::LeafHint hint;
  forest.LeavesContaining(
    reinterpret_cast<const double(*)[3]>(points.data()), leaves.data(), points.size(), hint);
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    EXPECT_EQ(leaves[i], forest.LeafContaining(points[i].data())) << "point " << i;
  }
}

TEST(TetraForest, LeafHintHoldsOnlyPointsWellInsideALeafThatIsStillALeaf)
{
  TetraForest forest;
  const TetraForest::NodeIndex root = 2;
  TetraForest::LeafHint hint;
  const std::array<double, 3> centroid = forest.Geometry(root).Centroid();
  EXPECT_FALSE(hint.Holds(forest, centroid.data())) << "no leaf yet";
  hint.Set(forest, root);
  EXPECT_TRUE(hint.Holds(forest, centroid.data()));
  const Tetra t = forest.Geometry(root);
  for (int v = 0; v < 4; ++v)
  {
    const std::array<double, 3> corner = { double(t.V[std::size_t(v)][0]), double(t.V[std::size_t(v)][1]), double(t.V[std::size_t(v)][2]) };
    EXPECT_FALSE(hint.Holds(forest, corner.data())) << "corner " << v;
    // Halfway between the centroid and the corner: inside. 1e-7 lattice units from the
    // corner toward the centroid: inside too, but within the margin of three faces.
    std::array<double, 3> half, nearCorner;
    double length = 0;
    for (int a = 0; a < 3; ++a)
    {
      length += (centroid[std::size_t(a)] - corner[std::size_t(a)]) * (centroid[std::size_t(a)] - corner[std::size_t(a)]);
    }
    length = std::sqrt(length);
    for (int a = 0; a < 3; ++a)
    {
      half[std::size_t(a)] = 0.5 * (centroid[std::size_t(a)] + corner[std::size_t(a)]);
      nearCorner[std::size_t(a)] = corner[std::size_t(a)] + 1e-7 / length * (centroid[std::size_t(a)] - corner[std::size_t(a)]);
    }
    ASSERT_TRUE(forest.Geometry(root).Contains(nearCorner.data()));
    EXPECT_TRUE(hint.Holds(forest, half.data()));
    EXPECT_FALSE(hint.Holds(forest, nearCorner.data()));
  }
  const std::array<double, 3> outside = { -1, -1, -1 };
  EXPECT_FALSE(hint.Holds(forest, outside.data()));
  forest.SplitDiamond(root, [](TetraForest::NodeIndex) {});
  EXPECT_FALSE(hint.Holds(forest, centroid.data())) << "the leaf was split";
}

// The hint keeps the face planes of recent leaves by node number: leaves whose numbers agree in
// their low bits, set in turn, must each be held by their own planes.
TEST(TetraForest, LeafHintTellsApartLeavesItRemembersInOneSlot)
{
  const TetraForest forest = RandomRefinement(4, 600);
  const std::vector<TetraForest::NodeIndex> leaves = forest.Leaves();
  constexpr TetraForest::NodeIndex Apart = 1024; // a multiple of any slot count up to it
  TetraForest::NodeIndex a = TetraForest::None, b = TetraForest::None;
  for (std::size_t i = 0; i < leaves.size() && b == TetraForest::None; ++i)
  {
    for (std::size_t j = i + 1; j < leaves.size() && b == TetraForest::None; ++j)
    {
      if ((leaves[j] - leaves[i]) % Apart == 0)
      {
        a = leaves[i];
        b = leaves[j];
      }
    }
  }
  ASSERT_NE(b, TetraForest::None) << "the forest is too small for the test";
  const std::array<double, 3> inA = forest.Geometry(a).Centroid(), inB = forest.Geometry(b).Centroid();
  TetraForest::LeafHint hint;
  for (int round = 0; round < 2; ++round)
  {
    hint.Set(forest, a);
    EXPECT_TRUE(hint.Holds(forest, inA.data()));
    EXPECT_FALSE(hint.Holds(forest, inB.data()));
    hint.Set(forest, b);
    EXPECT_TRUE(hint.Holds(forest, inB.data()));
    EXPECT_FALSE(hint.Holds(forest, inA.data()));
  }
}

// The checks must be able to fail: break a diamond on purpose.
TEST(ConformityCheck, RejectsOneMemberOfADiamondSplitAlone)
{
  const TetraForest forest = RandomRefinement(3, 60);
  std::vector<Tetra> tets;
  bool broken = false;
  for (const auto leaf : forest.Leaves())
  {
    const Tetra t = forest.Geometry(leaf);
    if (!broken && DiamondMembers(forest[leaf].Id).size() > 1)
    {
      const auto children = t.Children();
      tets.insert(tets.end(), children.begin(), children.end());
      broken = true;
      continue;
    }
    tets.push_back(t);
  }
  ASSERT_TRUE(broken);
  EXPECT_NE(FaceMatchingProblem(tets), "");
  EXPECT_NE(TetGenProblem(tets), "");
}

TEST(ConformityCheck, RejectsAChildSplitWithoutItsDiamond)
{
  // Split a whole diamond properly, then one of the new children alone.
  TetraForest forest;
  forest.SplitDiamond(0, [](TetraForest::NodeIndex) {});
  forest.SplitDiamond(forest.LeafContaining(std::array<double, 3>{ 9e5, 1e5, 2e5 }.data()),
    [](TetraForest::NodeIndex) {});
  auto tets = LeafGeometry(forest);
  ASSERT_EQ(FaceMatchingProblem(tets), "");
  ASSERT_EQ(TetGenProblem(tets), "");
  const Tetra victim = tets.back();
  tets.pop_back();
  const auto children = victim.Children();
  tets.insert(tets.end(), children.begin(), children.end());
  EXPECT_NE(FaceMatchingProblem(tets), "");
  EXPECT_NE(TetGenProblem(tets), "");
}

TEST(ConformityCheck, RejectsAMissingTetrahedron)
{
  auto tets = LeafGeometry(RandomRefinement(4, 30));
  tets.erase(tets.begin() + 3);
  EXPECT_NE(FaceMatchingProblem(tets), "");
}

/// Calls test(locator, members, world) for 40 diamonds of a random refinement, world(t, b, p)
/// giving the point p of barycentric coordinates b in member t.
template <typename Test>
int ForEachTestDiamond(Test test)
{
  const TetraForest forest = RandomRefinement(11, 60);
  const double boxMin[3] = { -2, 0, 1 }, boxMax[3] = { 3, 4, 2 };
  const LatticeFrame frame(boxMin, boxMax);
  int diamonds = 0;
  for (const auto leaf : forest.Leaves())
  {
    const std::vector<TetId> ids = DiamondMembers(forest[leaf].Id);
    if (ids.size() < 2 || diamonds == 40)
    {
      continue;
    }
    ++diamonds;
    std::vector<Tetra> members;
    for (const TetId id : ids)
    {
      members.push_back(TetraOf(id));
    }
    const MemberLocator locator(members, frame);
    const auto world = [&](const Tetra& t, const double b[4], double out[3]) {
      double lattice[3] = { 0, 0, 0 };
      for (int k = 0; k < 4; ++k)
      {
        for (int a = 0; a < 3; ++a)
        {
          lattice[a] += b[k] * t.V[std::size_t(k)][std::size_t(a)];
        }
      }
      for (int a = 0; a < 3; ++a)
      {
        out[a] = frame.Origin()[std::size_t(a)] + lattice[a] / frame.Scale();
      }
    };
    test(locator, members, world);
  }
  return diamonds;
}

// The member a point is given to does not depend on the member tried first: points well inside
// a member, on the faces between members, and around the diamond (outside it too).
TEST(MemberLocator, AnswerDoesNotDependOnTheLikelyMember)
{
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  int points = 0, facePoints = 0;
  const int diamonds = ForEachTestDiamond([&](const MemberLocator& locator, const std::vector<Tetra>& members, auto world) {
    for (std::size_t m = 0; m < members.size(); ++m)
    {
      for (int sample = 0; sample < 30; ++sample)
      {
        // Kind 0: well inside m; 1: on one of its faces; 2: stretched up to twice its size
        // around its centroid, often outside the diamond.
        const int kind = sample % 3;
        double b[4], sum = 0;
        for (double& x : b)
        {
          x = 0.05 + unit(rng);
          sum += x;
        }
        for (double& x : b)
        {
          x /= sum;
        }
        if (kind == 1)
        {
          const int face = int(rng() % 4);
          const double rest = 1 - b[face];
          b[face] = 0;
          for (double& x : b)
          {
            x /= rest;
          }
          ++facePoints;
        }
        if (kind == 2)
        {
          for (double& x : b)
          {
            x = 0.25 + 2 * (x - 0.25) * (1 + unit(rng));
          }
        }
        double p[3];
        world(members[m], b, p);
        const int answer = locator.MemberOf(p);
        if (kind == 0)
        {
          ASSERT_EQ(answer, int(m));
        }
        for (int likely = 0; likely < int(members.size()); ++likely)
        {
          ASSERT_EQ(locator.MemberOf(p, likely), answer) << "kind " << kind << ", likely " << likely;
        }
        ++points;
      }
    }
  });
  EXPECT_EQ(diamonds, 40);
  EXPECT_GT(points, 2000);
  EXPECT_GT(facePoints, 700);
}

// A member DeepMemberOf names for three points is the member MemberOf gives their centroid,
// whatever member it tries first, even for points barely deep enough: the simplifier assigns
// most triangles on that guarantee. Points on a face, or only ClearlyInside of it, get -1.
TEST(MemberLocator, DeepPointsVouchForTheirCentroids)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  int triples = 0, nearFace = 0, deep = 0;
  const int diamonds = ForEachTestDiamond([&](const MemberLocator& locator, const std::vector<Tetra>& members, auto world) {
    for (std::size_t m = 0; m < members.size(); ++m)
    {
      std::vector<std::array<double, 3>> deepPoints;
      for (int sample = 0; sample < 60; ++sample)
      {
        // Random barycentrics, with one coordinate often pushed to within a few times the
        // margin of a face (2e-6), or onto it.
        double b[4], sum = 0;
        for (double& x : b)
        {
          x = unit(rng);
          sum += x;
        }
        for (double& x : b)
        {
          x /= sum;
        }
        const int face = int(rng() % 4);
        const int kind = sample % 4;
        const double nearness[4] = { -1, 0, 1e-6, 2e-6 * (1 + 4 * unit(rng)) };
        if (kind > 0)
        {
          const double rest = (1 - nearness[kind]) / (1 - b[face]);
          for (double& x : b)
          {
            x *= rest;
          }
          b[face] = nearness[kind];
        }
        double p[3];
        world(members[m], b, p);
        const int answer = locator.DeepMemberOf(p);
        for (int likely = 0; likely < int(members.size()); ++likely)
        {
          ASSERT_EQ(locator.DeepMemberOf(p, likely), answer);
        }
        if (kind == 1 || kind == 2)
        {
          ASSERT_EQ(answer, -1) << "a point within MemberOf's own margin of a face";
          ++nearFace;
          continue;
        }
        if (answer < 0)
        {
          continue;
        }
        ASSERT_EQ(answer, int(m));
        ASSERT_EQ(locator.MemberOf(p), answer);
        deepPoints.push_back({ p[0], p[1], p[2] });
        ++deep;
      }
      for (std::size_t i = 0; i + 2 < deepPoints.size(); ++i)
      {
        double centroid[3];
        for (int a = 0; a < 3; ++a)
        {
          centroid[a] = (deepPoints[i][std::size_t(a)] + deepPoints[i + 1][std::size_t(a)] +
                          deepPoints[i + 2][std::size_t(a)]) / 3;
        }
        for (int likely = 0; likely < int(members.size()); ++likely)
        {
          ASSERT_EQ(locator.MemberOf(centroid, likely), int(m));
        }
        ++triples;
      }
    }
  });
  EXPECT_EQ(diamonds, 40);
  EXPECT_GT(deep, 1500);
  EXPECT_GT(nearFace, 1000);
  EXPECT_GT(triples, 1000);
}
