// BoundarySketch against exact edge counting: closed meshes, grids, holes, and random meshes.
#include "atpBoundarySketch.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace
{
using Triangle = std::array<std::uint32_t, 3>;
using Edge = std::pair<std::uint32_t, std::uint32_t>;

Edge Undirected(std::uint32_t a, std::uint32_t b)
{
  return a < b ? Edge(a, b) : Edge(b, a);
}

/// Edges used by an odd number of triangles, found the obvious way.
std::set<Edge> ExactBoundary(const std::vector<Triangle>& triangles)
{
  std::map<Edge, int> uses;
  for (const Triangle& t : triangles)
  {
    for (int c = 0; c < 3; ++c)
    {
      ++uses[Undirected(t[c], t[(c + 1) % 3])];
    }
  }
  std::set<Edge> boundary;
  for (const auto& entry : uses)
  {
    if (entry.second % 2 == 1)
    {
      boundary.insert(entry.first);
    }
  }
  return boundary;
}

std::set<Edge> SketchBoundary(const std::vector<Triangle>& triangles, std::uint32_t vertexCount)
{
  atp::BoundarySketch sketch(vertexCount, std::filesystem::temp_directory_path().string());
  for (const Triangle& t : triangles)
  {
    sketch.AddTriangle(t[0], t[1], t[2]);
  }
  std::set<Edge> boundary;
  for (const Triangle& t : triangles)
  {
    for (int c = 0; c < 3; ++c)
    {
      const std::uint32_t u = t[c];
      const std::uint32_t v = t[(c + 1) % 3];
      EXPECT_EQ(sketch.IsBoundaryEdge(u, v), sketch.IsBoundaryEdge(v, u));
      if (sketch.IsBoundaryEdge(u, v))
      {
        boundary.insert(Undirected(u, v));
      }
    }
  }
  return boundary;
}

/// An nx by ny grid of quads, two triangles each; `skip` quads are left out (holes).
std::vector<Triangle> Grid(
  std::uint32_t nx, std::uint32_t ny, const std::set<std::uint32_t>& skip = {})
{
  std::vector<Triangle> triangles;
  auto id = [&](std::uint32_t i, std::uint32_t j) { return j * (nx + 1) + i; };
  for (std::uint32_t j = 0; j < ny; ++j)
  {
    for (std::uint32_t i = 0; i < nx; ++i)
    {
      if (skip.count(j * nx + i))
      {
        continue;
      }
      triangles.push_back({ id(i, j), id(i + 1, j), id(i + 1, j + 1) });
      triangles.push_back({ id(i, j), id(i + 1, j + 1), id(i, j + 1) });
    }
  }
  return triangles;
}

TEST(BoundarySketch, ClosedMeshesHaveNoBoundary)
{
  const std::vector<Triangle> tetrahedron = { { 0, 2, 1 }, { 0, 1, 3 }, { 1, 2, 3 }, { 2, 0, 3 } };
  EXPECT_TRUE(SketchBoundary(tetrahedron, 4).empty());
  const std::vector<Triangle> octahedron = { { 0, 2, 4 }, { 2, 1, 4 }, { 1, 3, 4 }, { 3, 0, 4 },
    { 2, 0, 5 }, { 1, 2, 5 }, { 3, 1, 5 }, { 0, 3, 5 } };
  EXPECT_TRUE(SketchBoundary(octahedron, 6).empty());
}

TEST(BoundarySketch, GridBoundaryIsItsPerimeter)
{
  const std::vector<Triangle> grid = Grid(7, 4);
  const std::set<Edge> boundary = SketchBoundary(grid, 8 * 5);
  EXPECT_EQ(boundary.size(), 2u * (7 + 4));
  EXPECT_EQ(boundary, ExactBoundary(grid));
}

TEST(BoundarySketch, HoleEdgesAreBoundary)
{
  // Quad (2, 2) of a 5x5 grid removed: the perimeter plus the hole's 4 edges.
  const std::vector<Triangle> mesh = Grid(5, 5, { 2 * 5 + 2 });
  const std::set<Edge> boundary = SketchBoundary(mesh, 6 * 6);
  EXPECT_EQ(boundary.size(), 4u * 5 + 4);
  EXPECT_EQ(boundary, ExactBoundary(mesh));
}

TEST(BoundarySketch, SingleTriangle)
{
  EXPECT_EQ(SketchBoundary({ { 0, 1, 2 } }, 3).size(), 3u);
}

TEST(BoundarySketch, EdgeUsedTwiceWithTheSameOrientationIsInterior)
{
  // Inconsistently oriented neighbours still share their edge.
  const std::vector<Triangle> mesh = { { 0, 1, 2 }, { 0, 1, 3 } };
  const std::set<Edge> boundary = SketchBoundary(mesh, 4);
  EXPECT_EQ(boundary.count(Edge(0, 1)), 0u);
  EXPECT_EQ(boundary.size(), 4u);
}

TEST(BoundarySketch, PinchVertexErrsOnTheInteriorSide)
{
  // Two triangles touching at vertex 0 only: vertex 0 has four boundary neighbours, so its
  // edges read as interior; the edges away from it are found.
  const std::vector<Triangle> bowtie = { { 0, 1, 2 }, { 0, 3, 4 } };
  const std::set<Edge> boundary = SketchBoundary(bowtie, 5);
  EXPECT_EQ(boundary, (std::set<Edge>{ Edge(1, 2), Edge(3, 4) }));
}

TEST(BoundarySketch, MatchesExactCountingOnRandomHoles)
{
  // Scattered missing quads, no two touching (so every boundary vertex is manifold): the
  // sketch must agree exactly with counting.
  std::mt19937 random(7);
  for (int trial = 0; trial < 20; ++trial)
  {
    const std::uint32_t n = 20;
    std::set<std::uint32_t> skip;
    for (std::uint32_t j = 1; j + 1 < n; j += 3)
    {
      for (std::uint32_t i = 1; i + 1 < n; i += 3)
      {
        if (random() % 2)
        {
          skip.insert(j * n + i);
        }
      }
    }
    const std::vector<Triangle> mesh = Grid(n, n, skip);
    EXPECT_EQ(SketchBoundary(mesh, (n + 1) * (n + 1)), ExactBoundary(mesh));
  }
}

TEST(BoundarySketch, LargeVertexIndices)
{
  // Indices near 2^32 must not collide with small ones in the XOR sketch.
  const std::uint32_t big = 4000000000u;
  atp::BoundarySketch sketch(big + 4, std::filesystem::temp_directory_path().string());
  sketch.AddTriangle(big, big + 1, big + 2);
  sketch.AddTriangle(big, big + 2, big + 3);
  EXPECT_TRUE(sketch.IsBoundaryEdge(big, big + 1));
  EXPECT_TRUE(sketch.IsBoundaryEdge(big + 3, big));
  EXPECT_FALSE(sketch.IsBoundaryEdge(big, big + 2));
}
} // namespace
