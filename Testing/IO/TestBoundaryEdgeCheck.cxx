// BoundaryEdgeCheck: edges counted by position in either direction, -0 as +0, only edges used
// once keep their boundary bits, and a table past its size keeps none.
#include "atpBoundaryEdgeCheck.h"

#include <gtest/gtest.h>

#include <cstring>

namespace
{
atp::SoupTriangle Triangle(const float a[3], const float b[3], const float c[3], std::uint8_t bits)
{
  atp::SoupTriangle t;
  std::memset(&t, 0, sizeof(t));
  std::memcpy(t.V[0], a, sizeof(float) * 3);
  std::memcpy(t.V[1], b, sizeof(float) * 3);
  std::memcpy(t.V[2], c, sizeof(float) * 3);
  t.BoundaryEdges = std::uint8_t(bits | atp::BoundaryEdgeCheck::CountedBit); // as reading marks it
  return t;
}

const float P[3] = { 0, 0, 0 }, Q[3] = { 1, 0, 0 }, R[3] = { 0, 1, 0 }, S[3] = { 1, 1, 0 };
const float NegativeZeroP[3] = { -0.0f, 0, -0.0f };
} // namespace

TEST(BoundaryEdgeCheck, OnlyEdgesUsedOnceByPositionStayBoundary)
{
  atp::BoundaryEdgeCheck check;
  // Two triangles of unwelded vertices sharing the edge Q-R, flagged open by vertex index on
  // every edge; the second one counted R to Q, the other way round.
  check.Count(P, Q, true);
  check.Count(Q, R, true);
  check.Count(R, P, true);
  check.Count(R, Q, true);
  check.Count(Q, S, true);
  check.Count(S, R, true);
  EXPECT_EQ(check.EdgesUsedOnce(), 4u);
  EXPECT_EQ(check.EdgesShared(), 1u);
  EXPECT_FALSE(check.Overflowed());

  atp::SoupTriangle triangles[2] = { Triangle(P, Q, R, 0b111), Triangle(R, Q, S, 0b111) };
  check.Apply(triangles, 2);
  EXPECT_EQ(triangles[0].BoundaryEdges, 0b101); // Q-R (corner 1 to 2) is shared
  EXPECT_EQ(triangles[1].BoundaryEdges, 0b110); // R-Q (corner 0 to 1) is shared

  // A bit the sketch did not set stays clear, and an edge never counted is no boundary edge.
  atp::SoupTriangle unflagged = Triangle(P, Q, S, 0b001);
  check.Apply(&unflagged, 1);
  EXPECT_EQ(unflagged.BoundaryEdges, 0b001);
  atp::SoupTriangle uncounted = Triangle(P, S, R, 0b001);
  check.Apply(&uncounted, 1);
  EXPECT_EQ(uncounted.BoundaryEdges, 0);
}

TEST(BoundaryEdgeCheck, AnEdgeUsedThreeTimesIsNotBoundaryAndStays)
{
  atp::BoundaryEdgeCheck check;
  for (int use = 0; use < 3; ++use)
  {
    check.Count(P, Q, true);
  }
  check.Count(Q, R, true);
  check.Count(Q, R, true);
  EXPECT_EQ(check.EdgesUsedOnce(), 0u);
  EXPECT_EQ(check.EdgesShared(), 2u);
  // P-Q (corner 0 to 1), used three times, is marked to stay; Q-R, used twice, is not.
  atp::SoupTriangle t = Triangle(P, Q, R, 0b011);
  check.Apply(&t, 1);
  EXPECT_EQ(t.BoundaryEdges, 0b1000);
}

// A vertex where the boundary pinches fails the sketch's test, so an edge of three sheets that
// ends there is not flagged: counted all the same, it is marked to stay. An inner chord between
// two boundary vertices is counted twice but was never open: not "shared".
TEST(BoundaryEdgeCheck, UnflaggedEdgesOfThreeSheetsAreMarkedAndChordsAreNotShared)
{
  atp::BoundaryEdgeCheck check;
  for (int use = 0; use < 3; ++use)
  {
    check.Count(P, Q, false);
  }
  check.Count(Q, R, false);
  check.Count(R, Q, false);
  EXPECT_EQ(check.EdgesShared(), 0u);
  atp::SoupTriangle t = Triangle(P, Q, R, 0);
  check.Apply(&t, 1);
  EXPECT_EQ(t.BoundaryEdges, 0b1000);
  // A triangle reading did not mark has no counted edge: left as it is.
  atp::SoupTriangle unmarked = Triangle(P, Q, R, 0b001);
  unmarked.BoundaryEdges = 0b001;
  check.Apply(&unmarked, 1);
  EXPECT_EQ(unmarked.BoundaryEdges, 0b001);
}

TEST(BoundaryEdgeCheck, NegativeZeroIsTheSamePoint)
{
  atp::BoundaryEdgeCheck check;
  check.Count(P, Q, true);
  check.Count(Q, NegativeZeroP, true);
  EXPECT_EQ(check.EdgesShared(), 1u);
  EXPECT_EQ(check.EdgesUsedOnce(), 0u);
}

TEST(BoundaryEdgeCheck, PastItsSizeNoEdgeStaysBoundary)
{
  atp::BoundaryEdgeCheck check(2);
  check.Count(P, Q, true);
  check.Count(Q, R, true);
  atp::SoupTriangle t = Triangle(P, Q, R, 0b011);
  check.Apply(&t, 1);
  EXPECT_EQ(t.BoundaryEdges, 0b011) << "within its size the table answers";
  check.Count(R, P, true);
  EXPECT_TRUE(check.Overflowed());
  EXPECT_EQ(check.EdgesUsedOnce(), 0u);
  check.Apply(&t, 1);
  EXPECT_EQ(t.BoundaryEdges, 0) << "past its size every edge is locked: no crack";
}

TEST(BoundaryEdgeCheck, ManyEdgesGrowTheTable)
{
  atp::BoundaryEdgeCheck check;
  for (int i = 0; i < 5000; ++i)
  {
    const float a[3] = { float(i), 0, 0 }, b[3] = { float(i), 1, 0 };
    check.Count(a, b, true);
    if (i % 3 == 0)
    {
      check.Count(b, a, true);
    }
  }
  EXPECT_EQ(check.EdgesShared(), 1667u);
  EXPECT_EQ(check.EdgesUsedOnce(), 5000u - 1667u);
}

TEST(BoundaryEdgeCheck, EndPositionsAreFoundByPosition)
{
  atp::BoundaryEdgeCheck check;
  EXPECT_FALSE(check.HasEndPositions());
  check.AddEndPosition(NegativeZeroP);
  check.AddEndPosition(Q);
  EXPECT_TRUE(check.HasEndPositions());
  EXPECT_TRUE(check.IsEndPosition(P)) << "-0 and +0 are one point";
  EXPECT_TRUE(check.IsEndPosition(Q));
  EXPECT_FALSE(check.IsEndPosition(R));

  atp::BoundaryEdgeCheck small(1);
  small.AddEndPosition(P);
  EXPECT_FALSE(small.Overflowed());
  small.AddEndPosition(Q);
  EXPECT_TRUE(small.Overflowed()) << "end positions count against the size too";
  EXPECT_FALSE(small.HasEndPositions());
}
