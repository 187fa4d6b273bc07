// The constrained simplifier, its quadrics, its collapse queues, the patch merge and the nearest
// point of a triangle: locked and original boundaries, topology, quotas, triangle quality, exact
// vertices, determinism, error.
#include "atpClosestPoint.h"
#include "atpCollapseQueues.h"
#include "atpMergePatches.h"
#include "atpQuadric.h"
#include "atpSimplifier.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <thread>

using namespace atp;

namespace
{

using Edge = std::pair<std::uint32_t, std::uint32_t>; // directed: corner i -> corner i+1
using PositionKey = std::array<std::uint32_t, 3>;

PositionKey KeyOf(const PatchMesh& mesh, std::uint32_t v)
{
  PositionKey key;
  std::memcpy(key.data(), &mesh.Positions[3 * std::size_t(v)], sizeof(key));
  return key;
}

/// The positions of a mesh's vertices, to find which input vertices an output kept.
std::set<PositionKey> PositionsOf(const PatchMesh& mesh)
{
  std::set<PositionKey> positions;
  for (std::uint32_t v = 0; v < mesh.VertexCount(); ++v)
  {
    positions.insert(KeyOf(mesh, v));
  }
  return positions;
}

/// Triangle t of a mesh in double: its corners, and its normal scaled by twice its area.
struct FaceGeometry
{
  double P[3][3];
  double N[3];
};

FaceGeometry FaceOf(const PatchMesh& mesh, std::size_t t)
{
  FaceGeometry f;
  for (int k = 0; k < 3; ++k)
  {
    for (int c = 0; c < 3; ++c)
    {
      f.P[k][c] = mesh.Positions[3 * std::size_t(mesh.Indices[3 * t + std::size_t(k)]) + std::size_t(c)];
    }
  }
  const double a[3] = { f.P[1][0] - f.P[0][0], f.P[1][1] - f.P[0][1], f.P[1][2] - f.P[0][2] };
  const double b[3] = { f.P[2][0] - f.P[0][0], f.P[2][1] - f.P[0][1], f.P[2][2] - f.P[0][2] };
  f.N[0] = a[1] * b[2] - a[2] * b[1];
  f.N[1] = a[2] * b[0] - a[0] * b[2];
  f.N[2] = a[0] * b[1] - a[1] * b[0];
  return f;
}

/// Area-weighted vertex normals.
void ComputeNormals(PatchMesh& mesh)
{
  std::vector<double> sum(mesh.Positions.size(), 0.0);
  for (std::size_t t = 0; t < mesh.TriangleCount(); ++t)
  {
    const float* p[3];
    for (int k = 0; k < 3; ++k)
    {
      p[k] = &mesh.Positions[3 * std::size_t(mesh.Indices[3 * t + std::size_t(k)])];
    }
    const double a[3] = { p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2] };
    const double b[3] = { p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2] };
    const double n[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
    for (int k = 0; k < 3; ++k)
    {
      for (int c = 0; c < 3; ++c)
      {
        sum[3 * std::size_t(mesh.Indices[3 * t + std::size_t(k)]) + std::size_t(c)] += n[c];
      }
    }
  }
  mesh.Normals.resize(mesh.Positions.size());
  for (std::size_t v = 0; v < mesh.VertexCount(); ++v)
  {
    const double l = std::sqrt(sum[3 * v] * sum[3 * v] + sum[3 * v + 1] * sum[3 * v + 1] + sum[3 * v + 2] * sum[3 * v + 2]);
    for (int c = 0; c < 3; ++c)
    {
      mesh.Normals[3 * v + std::size_t(c)] = l > 0 ? float(sum[3 * v + std::size_t(c)] / l) : 0.f;
    }
  }
}

/// Sets the BoundaryEdges bit of every open edge when `original`, clears all otherwise
/// (then every open edge is diamond-external).
void MarkOpenEdges(PatchMesh& mesh, bool original)
{
  std::map<Edge, int> uses;
  for (std::size_t t = 0; t < mesh.TriangleCount(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t a = mesh.Indices[3 * t + std::size_t(k)];
      const std::uint32_t b = mesh.Indices[3 * t + std::size_t((k + 1) % 3)];
      ++uses[{ std::min(a, b), std::max(a, b) }];
    }
  }
  mesh.BoundaryEdges.assign(mesh.TriangleCount(), 0);
  for (std::size_t t = 0; t < mesh.TriangleCount() && original; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t a = mesh.Indices[3 * t + std::size_t(k)];
      const std::uint32_t b = mesh.Indices[3 * t + std::size_t((k + 1) % 3)];
      if (uses[{ std::min(a, b), std::max(a, b) }] == 1)
      {
        mesh.BoundaryEdges[t] |= std::uint8_t(1u << k);
      }
    }
  }
}

/// An n x n grid over [0, 1]^2, z = height(x, y), open edges marked original or external.
template <typename Height>
PatchMesh Grid(int n, Height height, bool originalBoundary)
{
  PatchMesh mesh;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      const double x = double(i) / n, y = double(j) / n;
      mesh.Positions.insert(mesh.Positions.end(), { float(x), float(y), float(height(x, y)) });
    }
  }
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const std::uint32_t a = std::uint32_t(j * (n + 1) + i), b = a + 1, c = a + std::uint32_t(n) + 1, d = c + 1;
      mesh.Indices.insert(mesh.Indices.end(), { a, b, d, a, d, c });
    }
  }
  ComputeNormals(mesh);
  MarkOpenEdges(mesh, originalBoundary);
  return mesh;
}

double Bumps(double x, double y)
{
  return 0.05 * std::sin(9 * x) * std::cos(7 * y) + 0.02 * std::sin(23 * x + 5 * y);
}

/// A closed torus with bumps and per-vertex colors; genus 1 (Euler characteristic 0).
PatchMesh BumpyTorus(int nu, int nv)
{
  PatchMesh mesh;
  for (int j = 0; j < nv; ++j)
  {
    for (int i = 0; i < nu; ++i)
    {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      const double r = 0.35 + 0.04 * std::sin(5 * u) * std::sin(3 * v);
      mesh.Positions.insert(mesh.Positions.end(),
        { float((1 + r * std::cos(v)) * std::cos(u)), float((1 + r * std::cos(v)) * std::sin(u)), float(r * std::sin(v)) });
      mesh.Colors.insert(mesh.Colors.end(), { std::uint8_t(i * 7), std::uint8_t(j * 13), 128, 255 });
    }
  }
  for (int j = 0; j < nv; ++j)
  {
    for (int i = 0; i < nu; ++i)
    {
      const auto at = [&](int a, int b) { return std::uint32_t((b % nv) * nu + (a % nu)); };
      mesh.Indices.insert(mesh.Indices.end(),
        { at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1) });
    }
  }
  ComputeNormals(mesh);
  MarkOpenEdges(mesh, true);
  return mesh;
}

RegionFunction OneRegion()
{
  return [](const double*, int) { return 0; };
}

/// All regions of a result welded back into one mesh.
PatchMesh Joined(const SimplifyResult& result)
{
  std::vector<const PatchMesh*> parts;
  for (const PatchMesh& region : result.Regions)
  {
    parts.push_back(&region);
  }
  return MergePatches(parts);
}

/// Directed edges with their BoundaryEdges bit.
std::map<Edge, bool> DirectedEdges(const PatchMesh& mesh)
{
  std::map<Edge, bool> edges;
  for (std::size_t t = 0; t < mesh.TriangleCount(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const Edge e{ mesh.Indices[3 * t + std::size_t(k)], mesh.Indices[3 * t + std::size_t((k + 1) % 3)] };
      EXPECT_TRUE(edges.emplace(e, (mesh.BoundaryEdges[t] >> k) & 1).second) << "edge used twice in one direction";
    }
  }
  return edges;
}

/// Directed edges whose reverse is absent: the open edges of an oriented mesh.
std::map<Edge, bool> OpenEdges(const PatchMesh& mesh)
{
  std::map<Edge, bool> open;
  const std::map<Edge, bool> edges = DirectedEdges(mesh);
  for (const auto& e : edges)
  {
    if (!edges.count({ e.first.second, e.first.first }))
    {
      open.insert(e);
    }
  }
  return open;
}

std::size_t TriangleTotal(const SimplifyResult& result)
{
  std::size_t n = 0;
  for (const PatchMesh& region : result.Regions)
  {
    n += region.TriangleCount();
  }
  return n;
}

/// Turns triangle t the other way round, its edge bits (0-2, and 3-5 for edges of many
/// sheets) with it, as the input would mark them.
void Turn(PatchMesh& mesh, std::size_t t)
{
  std::swap(mesh.Indices[3 * t + 1], mesh.Indices[3 * t + 2]);
  std::uint8_t& bits = mesh.BoundaryEdges[t];
  bits = std::uint8_t((bits & 0xD2) | ((bits & 0x01) << 2) | ((bits & 0x04) >> 2) | ((bits & 0x08) << 2) |
    ((bits & 0x20) >> 2));
}

long EulerCharacteristic(const PatchMesh& mesh)
{
  std::set<Edge> edges;
  for (std::size_t t = 0; t < mesh.TriangleCount(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t a = mesh.Indices[3 * t + std::size_t(k)], b = mesh.Indices[3 * t + std::size_t((k + 1) % 3)];
      edges.insert({ std::min(a, b), std::max(a, b) });
    }
  }
  return long(mesh.VertexCount()) - long(edges.size()) + long(mesh.TriangleCount());
}

} // namespace

TEST(Simplifier, ExternalBoundaryIsLockedBitExact)
{
  const PatchMesh mesh = Grid(40, Bumps, false);
  const std::map<Edge, bool> inputOpen = OpenEdges(mesh);
  const SimplifyResult result = Simplify(mesh, 1, OneRegion(), { 800 });
  EXPECT_TRUE(result.QuotasMet());
  EXPECT_LE(TriangleTotal(result), 800u);
  const PatchMesh out = Joined(result);
  std::map<PositionKey, std::uint32_t> outVertex;
  for (std::uint32_t v = 0; v < out.VertexCount(); ++v)
  {
    outVertex[KeyOf(out, v)] = v;
  }
  const std::map<Edge, bool> outOpen = OpenEdges(out);
  EXPECT_EQ(outOpen.size(), inputOpen.size());
  for (const auto& e : inputOpen)
  {
    const auto a = outVertex.find(KeyOf(mesh, e.first.first));
    const auto b = outVertex.find(KeyOf(mesh, e.first.second));
    ASSERT_TRUE(a != outVertex.end() && b != outVertex.end()) << "a locked vertex moved";
    const auto kept = outOpen.find({ a->second, b->second });
    ASSERT_TRUE(kept != outOpen.end()) << "an external boundary edge is gone";
    EXPECT_FALSE(kept->second);
  }
}

TEST(Simplifier, OriginalBoundaryOnlyLosesVertices)
{
  const int n = 40;
  const PatchMesh mesh = Grid(n, Bumps, true);
  // Input boundary vertices by their place along the counterclockwise perimeter.
  std::map<PositionKey, int> perimeter;
  for (int s = 0; s < 4 * n; ++s)
  {
    const int side = s / n, o = s % n;
    const int i = side == 0 ? o : side == 1 ? n : side == 2 ? n - o : 0;
    const int j = side == 0 ? 0 : side == 1 ? o : side == 2 ? n : n - o;
    perimeter[KeyOf(mesh, std::uint32_t(j * (n + 1) + i))] = s;
  }
  const SimplifyResult result = Simplify(mesh, 1, OneRegion(), { 200 });
  EXPECT_TRUE(result.QuotasMet());
  const PatchMesh out = Joined(result);
  const std::map<Edge, bool> outOpen = OpenEdges(out);
  // Bits mark exactly the open edges.
  for (const auto& e : DirectedEdges(out))
  {
    EXPECT_EQ(e.second, outOpen.count(e.first) == 1);
  }
  std::set<int> kept;
  for (const auto& e : outOpen)
  {
    const auto a = perimeter.find(KeyOf(out, e.first.first));
    ASSERT_TRUE(a != perimeter.end()) << "an interior vertex reached the boundary";
    kept.insert(a->second);
  }
  EXPECT_LT(kept.size(), std::size_t(4 * n)) << "the boundary should lose vertices";
  EXPECT_EQ(outOpen.size(), kept.size()) << "one boundary loop";
  for (const auto& e : outOpen)
  {
    // Each edge joins a kept vertex to the next kept one counterclockwise.
    const int a = perimeter.at(KeyOf(out, e.first.first));
    const int b = perimeter.at(KeyOf(out, e.first.second));
    auto next = kept.upper_bound(a);
    EXPECT_EQ(next == kept.end() ? *kept.begin() : *next, b);
  }
}

// Where the original boundary meets the diamond-external border, the vertex joins an edge that
// may shorten along the original boundary to one that is locked: it must stay, or the external
// border would end somewhere else than the neighbor patch's.
TEST(Simplifier, WhereTheOriginalBoundaryMeetsTheExternalBorderItStays)
{
  const int n = 40;
  PatchMesh mesh = Grid(n, Bumps, true);
  // The first half of side j = 0 (vertices i = 0..n/2; edge i -> i + 1 is corner 0 -> 1 of
  // triangle 2i) becomes external: vertex n/2 joins it to the original rest of the side.
  for (int i = 0; i < n / 2; ++i)
  {
    mesh.BoundaryEdges[2 * std::size_t(i)] &= std::uint8_t(~1u);
  }
  // A quota out of reach: every vertex that may move does.
  const SimplifyResult result = Simplify(mesh, 1, OneRegion(), { 1 });
  ASSERT_GT(result.Collapses, mesh.TriangleCount() / 4);
  const std::set<PositionKey> kept = PositionsOf(Joined(result));
  for (std::uint32_t i = 0; i <= std::uint32_t(n / 2); ++i)
  {
    EXPECT_TRUE(kept.count(KeyOf(mesh, i))) << "vertex " << i << " of the side moved";
  }
  int keptBeyond = 0; // the original part of the side, which may lose vertices
  for (std::uint32_t i = std::uint32_t(n / 2) + 1; i < std::uint32_t(n); ++i)
  {
    keptBeyond += int(kept.count(KeyOf(mesh, i)));
  }
  EXPECT_LT(keptBeyond, n / 2 - 1) << "the original boundary next to it should simplify";
}

// A grid of bumps, free to simplify, with three defects whose vertices must all stay: a fin
// standing on a row of its vertices (edges of three triangles), a small sheet touching it at one
// vertex only (a fan of a disk and a wedge), and one triangle turned against its neighbors.
// The pinch is what the classification's walk around a fan guards: without it the pinch passes
// for a boundary vertex and collapses along the sheet's side.
TEST(Simplifier, NonManifoldVerticesNeverMove)
{
  const int n = 40;
  PatchMesh mesh = Grid(n, Bumps, true);
  const auto at = [&](int i, int j) { return std::uint32_t(j * (n + 1) + i); };
  const auto position = [&](std::uint32_t v) { return &mesh.Positions[3 * std::size_t(v)]; };
  const auto addVertex = [&](double x, double y, double z) {
    mesh.Positions.insert(mesh.Positions.end(), { float(x), float(y), float(z) });
    return std::uint32_t(mesh.VertexCount() - 1);
  };
  std::set<std::uint32_t> mustStay;

  // The fin: rows above the grid's row j = 20, its bottom row being that row's own vertices.
  const int finRows = 10;
  std::vector<std::uint32_t> below;
  for (int i = 0; i <= n; ++i)
  {
    below.push_back(at(i, 20));
    mustStay.insert(at(i, 20));
  }
  for (int r = 1; r <= finRows; ++r)
  {
    std::vector<std::uint32_t> row;
    for (int i = 0; i <= n; ++i)
    {
      const float* base = position(at(i, 20));
      row.push_back(addVertex(base[0], base[1], base[2] + 0.3 * r / finRows));
    }
    for (int i = 0; i < n; ++i)
    {
      mesh.Indices.insert(mesh.Indices.end(), { below[i], below[i + 1], row[i + 1], below[i], row[i + 1], row[i] });
    }
    below = row;
  }

  // The sheet: a wedge of triangles just above the grid, facing up, touching it only at (10, 10).
  const std::uint32_t pinch = at(10, 10);
  mustStay.insert(pinch);
  // Copied: adding the rim's vertices may move the positions.
  const std::array<float, 3> p = { position(pinch)[0], position(pinch)[1], position(pinch)[2] };
  std::vector<std::uint32_t> rim;
  for (int k = 0; k <= 6; ++k)
  {
    const double angle = 0.2 * k;
    rim.push_back(addVertex(p[0] - 0.005 * std::cos(angle), p[1] + 0.005 * std::sin(angle), p[2] + 0.001));
  }
  const std::size_t firstOfSheet = mesh.TriangleCount();
  for (int k = 0; k < 6; ++k)
  {
    mesh.Indices.insert(mesh.Indices.end(), { pinch, rim[k + 1], rim[k] });
  }

  ComputeNormals(mesh);
  MarkOpenEdges(mesh, true);
  // The sheet's rim is diamond-external, so the sheet keeps its triangles and the pinch has a
  // legal collapse along the sheet's sides if it were taken for a boundary vertex.
  for (std::size_t t = firstOfSheet; t < firstOfSheet + 6; ++t)
  {
    mesh.BoundaryEdges[t] &= std::uint8_t(~2u);
  }
  // A quota out of reach: the simplifier goes on while any collapse is legal, so a vertex that
  // may move does.
  const SimplifyResult result = Simplify(mesh, 1, OneRegion(), { 1 });
  ASSERT_GT(result.Collapses, mesh.TriangleCount() / 4) << "the grid around the defects simplifies";
  const std::set<PositionKey> kept = PositionsOf(Joined(result));
  for (std::uint32_t v : mustStay)
  {
    EXPECT_TRUE(kept.count(KeyOf(mesh, v))) << "vertex " << v << " moved";
  }
}

// Two triangles back to back with no other neighbors (a closed component of no volume, which a
// coarse level can leave behind): collapsing one of its corners would take both triangles and
// leave the vertex it collapsed into with none, its error measured against nothing.
// An input edge of three or more triangles (bit 3 + k) looks inner in a patch holding two of
// them: its ends never move, and every triangle that holds it in the output keeps the mark,
// also where a collapse into one of its ends removed the triangle that had it.
TEST(Simplifier, EdgesOfManySheetsStayAndKeepTheirMark)
{
  // Also with every other triangle turned: the marks must turn with the triangles, both ways.
  for (const bool turned : { false, true })
  {
  SCOPED_TRACE(turned ? "every other triangle turned" : "all facing one way");
  const int n = 24, line = n / 2;
  PatchMesh mesh = Grid(n, Bumps, false);
  const auto onLine = [&](std::uint32_t v) { return int(v % std::uint32_t(n + 1)) == line; };
  std::set<std::uint32_t> lineVertices;
  for (std::size_t t = 0; t < mesh.TriangleCount(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t a = mesh.Indices[3 * t + std::size_t(k)], b = mesh.Indices[3 * t + std::size_t(k + 1) % 3];
      if (onLine(a) && onLine(b))
      {
        mesh.BoundaryEdges[t] |= std::uint8_t(8u << k);
        lineVertices.insert(a);
        lineVertices.insert(b);
      }
    }
  }
  for (std::size_t t = 0; turned && t < mesh.TriangleCount(); t += 2)
  {
    Turn(mesh, t);
  }
  const SimplifyResult result = Simplify(mesh, 1, OneRegion(), { 200 });
  const PatchMesh out = Joined(result);
  std::map<PositionKey, std::uint32_t> outVertex;
  for (std::uint32_t v = 0; v < out.VertexCount(); ++v)
  {
    outVertex[KeyOf(out, v)] = v;
  }
  std::map<std::uint32_t, std::uint32_t> rankOnLine; // output vertex -> its place along the line
  for (const std::uint32_t v : lineVertices)
  {
    const auto found = outVertex.find(KeyOf(mesh, v));
    ASSERT_TRUE(found != outVertex.end()) << "a vertex of the line moved";
    rankOnLine[found->second] = v / std::uint32_t(n + 1);
  }
  // Each edge of the line, on each side, in a triangle that keeps its mark; a chord between
  // two of its vertices (a sliver along the line, which collapses into its ends can leave) is
  // no edge of the line.
  std::size_t lineEdges = 0;
  for (std::size_t t = 0; t < out.TriangleCount(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const auto a = rankOnLine.find(out.Indices[3 * t + std::size_t(k)]);
      const auto b = rankOnLine.find(out.Indices[3 * t + std::size_t(k + 1) % 3]);
      if (a != rankOnLine.end() && b != rankOnLine.end() && (a->second + 1 == b->second || b->second + 1 == a->second))
      {
        ++lineEdges;
        EXPECT_TRUE(out.BoundaryEdges[t] & (8u << k)) << "an edge of the line lost its mark";
      }
    }
  }
  EXPECT_EQ(lineEdges, 2u * n) << "each edge of the line, once on each side";
  EXPECT_LT(TriangleTotal(result), mesh.TriangleCount() / 3);
  }
}

TEST(Simplifier, TwoTrianglesBackToBackStay)
{
  PatchMesh mesh = Grid(20, Bumps, true);
  const std::uint32_t first = std::uint32_t(mesh.VertexCount());
  mesh.Positions.insert(mesh.Positions.end(), { 2.0f, 0.0f, 0.0f, 2.1f, 0.0f, 0.0f, 2.0f, 0.1f, 0.0f });
  mesh.Indices.insert(mesh.Indices.end(), { first, first + 1, first + 2, first + 2, first + 1, first });
  ComputeNormals(mesh);
  MarkOpenEdges(mesh, true);
  // Collapsing the pair would cost nothing: both corners lie in the planes of both triangles.
  const SimplifyResult result = Simplify(mesh, 1, OneRegion(), { 200 });
  EXPECT_TRUE(result.QuotasMet());
  EXPECT_LT(result.Error, 0.05);
  const std::set<PositionKey> kept = PositionsOf(Joined(result));
  for (std::uint32_t v = first; v < first + 3; ++v)
  {
    EXPECT_TRUE(kept.count(KeyOf(mesh, v))) << "vertex " << v << " of the pair is gone";
  }
}

TEST(Simplifier, ClosedMeshStaysClosed)
{
  const PatchMesh mesh = BumpyTorus(96, 48);
  ASSERT_EQ(EulerCharacteristic(mesh), 0);
  const SimplifyResult result = Simplify(mesh, 1, OneRegion(), { 900 });
  EXPECT_TRUE(result.QuotasMet());
  EXPECT_LE(TriangleTotal(result), 900u);
  const PatchMesh out = Joined(result);
  EXPECT_TRUE(OpenEdges(out).empty());
  EXPECT_EQ(EulerCharacteristic(out), 0);
}

/// Where the edges used by one triangle (in either direction) of `mesh` are, and whether the
/// triangles using them mark them as the input's boundary.
void ExpectBoundaryBitsOnOpenEdgesOnly(const PatchMesh& mesh)
{
  std::map<Edge, int> uses;
  const auto undirected = [&](std::size_t t, int k) {
    const std::uint32_t a = mesh.Indices[3 * t + std::size_t(k)], b = mesh.Indices[3 * t + std::size_t((k + 1) % 3)];
    return Edge{ std::min(a, b), std::max(a, b) };
  };
  for (std::size_t t = 0; t < mesh.TriangleCount(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      ++uses[undirected(t, k)];
    }
  }
  for (std::size_t t = 0; t < mesh.TriangleCount(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_EQ((mesh.BoundaryEdges[t] >> k) & 1, uses[undirected(t, k)] == 1 ? 1 : 0)
        << "triangle " << t << " edge " << k;
    }
  }
}

// A mesh whose triangles face either way (stripes of the torus turned inside out) is simplified
// as if they all faced one way, and every triangle comes out facing as it came in: at each of
// the stripes' seams two triangles run their shared edge the same way, which would otherwise
// lock both of its ends, and the input's normals, summed over faces of both facings, no longer
// order the collapses.
TEST(Simplifier, MisorientedTrianglesAreTurnedWhileSimplifyingAndBackAfter)
{
  const int nu = 96, nv = 48, stripe = 12;
  PatchMesh consistent = BumpyTorus(nu, nv);
  PatchMesh turned = consistent;
  // Triangles come two per quad, quad (i, j) at 2 (j nu + i).
  const auto inStripe = [&](std::size_t t) { return int(t / 2 % nu) / stripe % 2 == 1; };
  for (std::size_t t = 0; t < turned.TriangleCount(); ++t)
  {
    if (inStripe(t))
    {
      Turn(turned, t);
    }
  }
  ComputeNormals(turned);
  const SimplifyResult reference = Simplify(consistent, 1, OneRegion(), { 900 });
  const SimplifyResult result = Simplify(turned, 1, OneRegion(), { 900 });
  EXPECT_TRUE(result.QuotasMet()) << TriangleTotal(result) << " triangles";
  EXPECT_LE(result.Error, 1.5 * reference.Error);
  EXPECT_FALSE(reference.FacingAtRandom);
  EXPECT_FALSE(result.FacingAtRandom) << "seams between stripes are no random facing";
  const PatchMesh out = Joined(result);
  ExpectBoundaryBitsOnOpenEdgesOnly(out);
  EXPECT_EQ(EulerCharacteristic(out), 0);

  // Every triangle as it came in: with nothing to collapse, the output is the input.
  const PatchMesh same = Joined(Simplify(turned, 1, OneRegion(), { std::uint32_t(turned.TriangleCount()) }));
  ASSERT_EQ(same.TriangleCount(), turned.TriangleCount());
  for (std::size_t t = 0; t < turned.TriangleCount(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      ASSERT_EQ(KeyOf(same, same.Indices[3 * t + std::size_t(k)]), KeyOf(turned, turned.Indices[3 * t + std::size_t(k)]))
        << "triangle " << t << " corner " << k;
    }
  }

  // Facing after the collapses: outward (from the tube's center circle) outside the stripes,
  // inward in them, judged where all three corners lie in one stripe's or gap's angles, three
  // quads or more from its edges (a triangle's corners move a few quads' way at most here).
  std::size_t judged = 0, wrong = 0;
  for (std::size_t t = 0; t < out.TriangleCount(); ++t)
  {
    const float* p[3];
    int band[3];
    double centroid[3] = { 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      p[k] = &out.Positions[3 * std::size_t(out.Indices[3 * t + std::size_t(k)])];
      double u = std::atan2(p[k][1], p[k][0]);
      u = (u < 0 ? u + 2 * M_PI : u) / (2 * M_PI) * nu; // in quads around the torus
      const double within = std::fmod(u, stripe);
      band[k] = within < 3 || within > stripe - 3 ? -1 : int(u) / stripe % 2;
      for (int a = 0; a < 3; ++a)
      {
        centroid[a] += p[k][a] / 3;
      }
    }
    if (band[0] < 0 || band[0] != band[1] || band[1] != band[2])
    {
      continue;
    }
    const double ring = std::hypot(centroid[0], centroid[1]);
    const double outward[3] = { centroid[0] - centroid[0] / ring, centroid[1] - centroid[1] / ring, centroid[2] };
    const double a[3] = { p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2] };
    const double b[3] = { p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2] };
    const double n[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
    const bool facesOut = n[0] * outward[0] + n[1] * outward[1] + n[2] * outward[2] > 0;
    ++judged;
    wrong += facesOut == (band[0] == 1);
  }
  EXPECT_GT(judged, 50u);
  EXPECT_EQ(wrong, 0u) << "of " << judged << " triangles face the other way than they came in";
}

// The input triangles a vertex's corners stand for (PatchMesh::CornerUses) stay with it through
// the collapses, whichever region its triangles end in: on a closed torus every vertex left
// stands for all of its own. A vertex whose counts fall short (as if a sheet on one of its edges
// lay in another patch) never moves.
TEST(Simplifier, InputUsesStayWithTheirVerticesAndShortOnesStay)
{
  const int nu = 64, nv = 32;
  PatchMesh mesh = BumpyTorus(nu, nv);
  mesh.InputUses.assign(mesh.VertexCount(), 0);
  for (const std::uint32_t v : mesh.Indices)
  {
    ++mesh.InputUses[v];
  }
  mesh.CornerUses.assign(mesh.Indices.size(), 1);
  const std::uint32_t shortVertex = 9 * nu + 17;
  ++mesh.InputUses[shortVertex];
  const RegionFunction side = [](const double p[3], int) { return p[0] < 0 ? 0 : 1; };
  const SimplifyResult result = Simplify(mesh, 2, side, { 500, 500 });
  EXPECT_TRUE(result.QuotasMet());
  const PatchMesh joined = Joined(result);
  ASSERT_TRUE(joined.UsesSized());
  const std::vector<std::uint8_t> elsewhere = VerticesUsedElsewhere(joined);
  std::size_t found = joined.VertexCount();
  for (std::uint32_t v = 0; v < joined.VertexCount(); ++v)
  {
    found = KeyOf(joined, v) == KeyOf(mesh, shortVertex) ? v : found;
  }
  ASSERT_LT(found, joined.VertexCount()) << "the vertex short of its input triangles moved";
  for (std::size_t v = 0; v < elsewhere.size(); ++v)
  {
    ASSERT_EQ(elsewhere[v], v == found ? 1 : 0) << "vertex " << v << " of " << elsewhere.size();
  }
}

// A Moebius strip cannot face one way: turning its triangles leaves one seam of edges run the
// same way by both of their triangles, whose ends stay. Reached breadth first, that seam crosses
// the strip where the two fronts meet; depth first, it ran along the strip (1,600 triangles with
// half turned at random kept 812 for a quota of 200, with an error of 0.3 of the strip's size).
TEST(Simplifier, AMoebiusStripSimplifiesWithItsTrianglesTurnedAtRandom)
{
  const int n = 200, w = 4;
  PatchMesh mesh;
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j <= w; ++j)
    {
      const double u = 2 * M_PI * i / n, s = (double(j) / w - 0.5) * 0.6;
      mesh.Positions.insert(mesh.Positions.end(), { float((1 + s * std::cos(u / 2)) * std::cos(u)),
        float((1 + s * std::cos(u / 2)) * std::sin(u)), float(s * std::sin(u / 2)) });
    }
  }
  const auto at = [&](int i, int j) { return std::uint32_t((i % n) * (w + 1) + j); };
  std::mt19937 random(1);
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < w; ++j)
    {
      std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (i == n - 1) // the half twist joins the last column to the first upside down
      {
        b = at(0, w - j);
        c = at(0, w - j - 1);
      }
      for (std::array<std::uint32_t, 3> t : { std::array<std::uint32_t, 3>{ a, b, c }, std::array<std::uint32_t, 3>{ a, c, d } })
      {
        if (random() % 2)
        {
          std::swap(t[1], t[2]);
        }
        mesh.Indices.insert(mesh.Indices.end(), t.begin(), t.end());
      }
    }
  }
  ComputeNormals(mesh);
  MarkOpenEdges(mesh, true);
  const SimplifyResult result = Simplify(mesh, 1, OneRegion(), { std::uint32_t(n) });
  EXPECT_TRUE(result.QuotasMet()) << TriangleTotal(result) << " triangles";
  EXPECT_LT(result.Error, 0.02);
  EXPECT_TRUE(result.FacingAtRandom);
  ExpectBoundaryBitsOnOpenEdgesOnly(Joined(result));
}

// Turned triangles on the input's boundary: their boundary bits turn with them, there and back.
TEST(Simplifier, TurnedTrianglesKeepTheirBoundaryEdges)
{
  PatchMesh mesh = Grid(30, Bumps, true);
  for (std::size_t t = 0; t < mesh.TriangleCount(); t += 2)
  {
    Turn(mesh, t); // every other triangle: every inner edge of the grid's quads runs one way
  }
  ComputeNormals(mesh);
  const SimplifyResult result = Simplify(mesh, 1, OneRegion(), { std::uint32_t(mesh.TriangleCount() / 4) });
  EXPECT_TRUE(result.QuotasMet()) << TriangleTotal(result) << " triangles";
  ExpectBoundaryBitsOnOpenEdgesOnly(Joined(result));
}

TEST(Simplifier, BordersBetweenRegionsAreFree)
{
  // A diamond's members meet inside its mesh: their border is no boundary of the mesh, and its
  // vertices simplify like any other (only the diamond's external border is locked).
  const int n = 40;
  const PatchMesh mesh = Grid(n, Bumps, false); // every open edge external: locked
  const RegionFunction side = [](const double p[3], int) { return p[0] < 0.5 ? 0 : 1; };
  const SimplifyResult result = Simplify(mesh, 2, side, { 300, 300 });
  EXPECT_TRUE(result.QuotasMet());
  const std::set<PositionKey> kept = PositionsOf(Joined(result));
  int onBorder = 0; // interior vertices on the line x = 0.5 between the regions
  for (int j = 1; j < n; ++j)
  {
    onBorder += int(kept.count(KeyOf(mesh, std::uint32_t(j * (n + 1) + n / 2))));
  }
  EXPECT_LT(onBorder, (n - 1) / 2) << "the border between the regions should lose vertices";
  for (int i = 0; i <= n; ++i)
  {
    EXPECT_TRUE(kept.count(KeyOf(mesh, std::uint32_t(i)))) << "a locked vertex moved";
  }
}

TEST(Simplifier, QuotasPerRegion)
{
  const PatchMesh mesh = Grid(60, Bumps, true);
  const RegionFunction side = [](const double p[3], int) { return p[0] < 0.4 ? 0 : 1; };
  const std::vector<std::uint32_t> quotas{ 1000, 300 };
  const SimplifyResult result = Simplify(mesh, 2, side, quotas);
  EXPECT_TRUE(result.QuotasMet());
  for (int r = 0; r < 2; ++r)
  {
    const PatchMesh& region = result.Regions[std::size_t(r)];
    EXPECT_LE(region.TriangleCount(), quotas[std::size_t(r)]);
    // Each member gets its budget: not simplified far below it.
    EXPECT_GE(region.TriangleCount() + 8, quotas[std::size_t(r)]);
    for (std::size_t t = 0; t < region.TriangleCount(); ++t)
    {
      double centroid[3] = { 0, 0, 0 };
      for (int k = 0; k < 3; ++k)
      {
        for (int c = 0; c < 3; ++c)
        {
          centroid[c] += region.Positions[3 * std::size_t(region.Indices[3 * t + std::size_t(k)]) + std::size_t(c)] / 3.0;
        }
      }
      EXPECT_EQ(side(centroid, 0), r);
    }
  }
}

// With a total quota the regions share the halving: a flat region gives up more than half, a
// bumpy one keeps more, and the surface is closer to the input than with half each. Each region
// is still held to its own quota.
TEST(Simplifier, RegionsShareATotalQuota)
{
  const PatchMesh mesh = Grid(60, [](double x, double y) { return x < 0.5 ? 0.0 : Bumps(x, y); }, true);
  const RegionFunction side = [](const double p[3], int) { return p[0] < 0.5 ? 0 : 1; };
  const std::uint32_t half = std::uint32_t(mesh.TriangleCount() / 2);

  const SimplifyResult apart = Simplify(mesh, 2, side, { half / 2, half / 2 });
  ASSERT_TRUE(apart.QuotasMet());

  SimplifyOptions pooled;
  pooled.TotalQuota = half;
  const SimplifyResult shared = Simplify(mesh, 2, side, { half, half }, pooled);
  EXPECT_TRUE(shared.QuotasMet());
  EXPECT_LE(TriangleTotal(shared), half);
  EXPECT_GE(TriangleTotal(shared) + 4, half);
  EXPECT_LT(shared.Regions[0].TriangleCount(), half / 4) << "the flat region gives up most";
  EXPECT_GT(shared.Regions[1].TriangleCount(), half * 3 / 4);
  EXPECT_LT(shared.Error, 0.8 * apart.Error);

  // The bumpy region's own quota still holds: the flat one gives up the rest.
  const SimplifyResult capped = Simplify(mesh, 2, side, { half, half / 2 }, pooled);
  EXPECT_TRUE(capped.QuotasMet());
  EXPECT_LE(capped.Regions[1].TriangleCount(), half / 2);
  EXPECT_LE(TriangleTotal(capped), half);
}

/// A strip one triangle pair wide along x (100 triangles, 102 vertices): once its open edges
/// are marked diamond-external, every vertex is on them.
PatchMesh Strip()
{
  PatchMesh mesh;
  for (int i = 0; i <= 50; ++i)
  {
    mesh.Positions.insert(mesh.Positions.end(), { float(i), 0.f, 0.f, float(i), 1.f, 0.f });
  }
  for (std::uint32_t i = 0; i < 50; ++i)
  {
    mesh.Indices.insert(mesh.Indices.end(), { 2 * i, 2 * i + 2, 2 * i + 3, 2 * i, 2 * i + 3, 2 * i + 1 });
  }
  return mesh;
}

TEST(Simplifier, UnreachableQuotaWhenEverythingIsLocked)
{
  PatchMesh mesh = Strip();
  ComputeNormals(mesh);
  MarkOpenEdges(mesh, false);
  const SimplifyResult result = Simplify(mesh, 1, OneRegion(), { 10 });
  EXPECT_FALSE(result.QuotasMet());
  EXPECT_EQ(result.TrianglesOverQuotas, 100u - 10u);
  EXPECT_EQ(result.Collapses, 0u);
  EXPECT_EQ(TriangleTotal(result), mesh.TriangleCount());
  EXPECT_EQ(result.Error, 0.0);

  // Split in two at x = 20: the 40 triangles left of it over a quota of 10, the 60 right of it
  // under one of 1000. What is over counts whole: the room on the right does not offset it.
  const RegionFunction halves = [](const double p[3], int) { return p[0] < 20 ? 0 : 1; };
  const SimplifyResult split = Simplify(mesh, 2, halves, { 10, 1000 });
  ASSERT_EQ(split.Regions.size(), 2u);
  EXPECT_EQ(split.Regions[0].TriangleCount(), 40u);
  EXPECT_EQ(split.Regions[1].TriangleCount(), 60u);
  EXPECT_EQ(split.TrianglesOverQuotas, 40u - 10u);

  // Over a total quota as well: both excesses count.
  SimplifyOptions pooled;
  pooled.TotalQuota = 70;
  EXPECT_EQ(Simplify(mesh, 2, halves, { 10, 1000 }, pooled).TrianglesOverQuotas, (40u - 10u) + (100u - 70u));
}

/// A flat disk of `rings` rings of `spokes` vertices around a center (vertex 0), its rim
/// diamond-external.
PatchMesh Web(int spokes, int rings)
{
  PatchMesh mesh;
  mesh.Positions = { 0.f, 0.f, 0.f };
  for (int r = 1; r <= rings; ++r)
  {
    for (int i = 0; i < spokes; ++i)
    {
      const double angle = 2 * M_PI * i / spokes;
      mesh.Positions.insert(mesh.Positions.end(), { float(r * std::cos(angle)), float(r * std::sin(angle)), 0.f });
    }
  }
  const auto at = [spokes](int r, int i) { return r == 0 ? 0u : std::uint32_t(1 + (r - 1) * spokes + i % spokes); };
  for (int i = 0; i < spokes; ++i)
  {
    mesh.Indices.insert(mesh.Indices.end(), { 0u, at(1, i), at(1, i + 1) });
  }
  for (int r = 1; r < rings; ++r)
  {
    for (int i = 0; i < spokes; ++i)
    {
      mesh.Indices.insert(mesh.Indices.end(), { at(r, i), at(r + 1, i), at(r + 1, i + 1) });
      mesh.Indices.insert(mesh.Indices.end(), { at(r, i), at(r + 1, i + 1), at(r, i + 1) });
    }
  }
  ComputeNormals(mesh);
  MarkOpenEdges(mesh, false);
  return mesh;
}

// Down to an eighth: every collapse writes its target's fan anew at the end of the fan pool,
// which is compacted several times along the way (about 18 corners written per collapse here).
TEST(Simplifier, DeepSimplificationKeepsADiskAndItsRim)
{
  const PatchMesh mesh = Web(256, 24);
  const std::uint32_t quota = std::uint32_t(mesh.TriangleCount() / 8);
  const SimplifyResult result = Simplify(mesh, 1, OneRegion(), { quota });
  EXPECT_TRUE(result.QuotasMet());
  EXPECT_LE(TriangleTotal(result), quota);
  EXPECT_GT(result.Collapses, 4u * 256u);
  const PatchMesh out = Joined(result);
  // Still one disk (Euler characteristic 1) whose only open edges are the whole locked rim.
  EXPECT_EQ(EulerCharacteristic(out), 1);
  EXPECT_EQ(OpenEdges(out).size(), 256u);
  const SimplifyResult again = Simplify(mesh, 1, OneRegion(), { quota });
  EXPECT_EQ(again.Regions[0].Indices, result.Regions[0].Indices);
}

TEST(Simplifier, NoFlippedOrDegenerateTrianglesAndExactVertices)
{
  const PatchMesh mesh = BumpyTorus(96, 48);
  std::map<PositionKey, std::uint32_t> inputVertex;
  for (std::uint32_t v = 0; v < mesh.VertexCount(); ++v)
  {
    inputVertex[KeyOf(mesh, v)] = v;
  }
  const SimplifyResult result = Simplify(mesh, 1, OneRegion(), { 600 });
  const PatchMesh& out = result.Regions[0];
  ASSERT_GT(out.TriangleCount(), 0u);
  for (std::uint32_t v = 0; v < out.VertexCount(); ++v)
  {
    const auto in = inputVertex.find(KeyOf(out, v));
    ASSERT_TRUE(in != inputVertex.end());
    EXPECT_EQ(std::memcmp(&out.Normals[3 * v], &mesh.Normals[3 * std::size_t(in->second)], 12), 0);
    EXPECT_EQ(std::memcmp(&out.Colors[4 * v], &mesh.Colors[4 * std::size_t(in->second)], 4), 0);
  }
  for (std::size_t t = 0; t < out.TriangleCount(); ++t)
  {
    const std::uint32_t* tri = &out.Indices[3 * t];
    ASSERT_TRUE(tri[0] != tri[1] && tri[1] != tri[2] && tri[2] != tri[0]);
    const FaceGeometry face = FaceOf(out, t);
    const auto& p = face.P;
    const double* n = face.N;
    const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    EXPECT_GT(area, 1e-8);
    // Outward: away from the tube's center circle.
    const double c[3] = { (p[0][0] + p[1][0] + p[2][0]) / 3, (p[0][1] + p[1][1] + p[2][1]) / 3, (p[0][2] + p[1][2] + p[2][2]) / 3 };
    const double ring = std::sqrt(c[0] * c[0] + c[1] * c[1]);
    const double out3[3] = { c[0] - c[0] / ring, c[1] - c[1] / ring, c[2] };
    EXPECT_GT(n[0] * out3[0] + n[1] * out3[1] + n[2] * out3[2], 0.0) << "flipped triangle " << t;
  }
}

TEST(Simplifier, DeterministicAcrossRunsAndThreads)
{
  const PatchMesh mesh = BumpyTorus(80, 40);
  const RegionFunction regions = [](const double p[3], int) { return p[0] < 0 ? 0 : (p[1] < 0 ? 1 : 2); };
  const std::vector<std::uint32_t> quotas{ 600, 500, 400 };
  const SimplifyResult first = Simplify(mesh, 3, regions, quotas);
  SimplifyResult concurrent[2];
  std::thread a([&] { concurrent[0] = Simplify(mesh, 3, regions, quotas); });
  std::thread b([&] { concurrent[1] = Simplify(mesh, 3, regions, quotas); });
  a.join();
  b.join();
  for (const SimplifyResult& other : concurrent)
  {
    EXPECT_EQ(other.Error, first.Error);
    EXPECT_EQ(other.Collapses, first.Collapses);
    for (int r = 0; r < 3; ++r)
    {
      const PatchMesh& x = first.Regions[std::size_t(r)];
      const PatchMesh& y = other.Regions[std::size_t(r)];
      EXPECT_EQ(x.Positions, y.Positions);
      EXPECT_EQ(x.Normals, y.Normals);
      EXPECT_EQ(x.Colors, y.Colors);
      EXPECT_EQ(x.Indices, y.Indices);
      EXPECT_EQ(x.BoundaryEdges, y.BoundaryEdges);
    }
  }
}

// With DeepRegionOf, a triangle whose corners lie deep in one region takes that region without
// a call of regionOf: far fewer calls, the same result. An answer out of range is refused.
TEST(Simplifier, DeepRegionsSpareLookupsAndChangeNothing)
{
  const PatchMesh mesh = BumpyTorus(80, 40);
  std::size_t calls = 0;
  const RegionFunction regions = [&calls](const double p[3], int) {
    ++calls;
    return p[0] < 0 ? 0 : (p[1] < 0 ? 1 : 2);
  };
  // The regions are convex (quarter and half spaces): a point clear of their borders vouches for
  // every convex combination of such points.
  const RegionFunction deep = [](const double p[3], int) {
    constexpr double margin = 1e-3;
    if (p[0] < -margin)
    {
      return 0;
    }
    if (p[0] > margin && std::abs(p[1]) > margin)
    {
      return p[1] < 0 ? 1 : 2;
    }
    return -1;
  };
  const std::vector<std::uint32_t> quotas{ 600, 500, 400 };
  const SimplifyResult plain = Simplify(mesh, 3, regions, quotas);
  const std::size_t plainCalls = calls;
  calls = 0;
  SimplifyOptions options;
  options.DeepRegionOf = deep;
  const SimplifyResult spared = Simplify(mesh, 3, regions, quotas, options);
  EXPECT_LT(calls * 5, plainCalls) << calls << " calls with deep regions, " << plainCalls << " without";
  EXPECT_EQ(spared.Error, plain.Error);
  EXPECT_EQ(spared.Collapses, plain.Collapses);
  for (int r = 0; r < 3; ++r)
  {
    EXPECT_EQ(spared.Regions[std::size_t(r)].Indices, plain.Regions[std::size_t(r)].Indices);
    EXPECT_EQ(spared.Regions[std::size_t(r)].Positions, plain.Regions[std::size_t(r)].Positions);
  }

  options.DeepRegionOf = [](const double*, int) { return 3; };
  EXPECT_THROW(Simplify(mesh, 3, regions, quotas, options), std::invalid_argument);
}

TEST(MergePatches, WelderNumbersPositionsInOrderOfFirstSightBitForBit)
{
  const float points[][3] = { { 1, 2, 3 }, { 4, 5, 6 }, { 1, 2, 3 }, { 0.0f, 0, 0 }, { -0.0f, 0, 0 },
    { 4, 5, 6 } };
  std::vector<float> positions(3 * std::size(points), -1);
  PositionWelder welder(std::size(points), positions.data());
  const std::uint32_t expected[] = { 0, 1, 0, 2, 3, 1 };
  const bool expectedAdded[] = { true, true, false, true, true, false };
  for (std::size_t i = 0; i < std::size(points); ++i)
  {
    bool added = !expectedAdded[i];
    EXPECT_EQ(welder.Weld(points[i], added), expected[i]) << "point " << i;
    EXPECT_EQ(added, expectedAdded[i]) << "point " << i;
  }
  // -0 and +0 differ in their bits: a position is welded only to the very same one.
  EXPECT_EQ(welder.Count(), 4u);
  const float stored[] = { 1, 2, 3, 4, 5, 6, 0, 0, 0, -0.0f, 0, 0 };
  for (std::size_t i = 0; i < std::size(stored); ++i)
  {
    EXPECT_EQ(std::signbit(positions[i]), std::signbit(stored[i])) << "float " << i;
    EXPECT_EQ(positions[i], stored[i]) << "float " << i;
  }
  EXPECT_EQ(positions[12], -1.0f) << "nothing is written past the positions seen";

  // Made for 2: a third distinct position is refused, not written past the room.
  float room[6] = { -1, -1, -1, -1, -1, -1 };
  PositionWelder small(2, room);
  bool added = false;
  small.Weld(points[0], added);
  small.Weld(points[1], added);
  EXPECT_EQ(small.Weld(points[2], added), 0u) << "a position seen before still welds";
  EXPECT_THROW(small.Weld(points[3], added), std::logic_error);
  EXPECT_EQ(small.Count(), 2u);
}

TEST(MergePatches, WeldsTwoHalvesIntoOneManifold)
{
  const PatchMesh grid = Grid(20, Bumps, true);
  // Split by triangle centroid; each half gets its own compact copy of the vertices it uses.
  PatchMesh halves[2];
  std::vector<std::uint32_t> local[2];
  for (auto& l : local)
  {
    l.assign(grid.VertexCount(), ~0u);
  }
  for (std::size_t t = 0; t < grid.TriangleCount(); ++t)
  {
    double x = 0;
    for (int k = 0; k < 3; ++k)
    {
      x += grid.Positions[3 * std::size_t(grid.Indices[3 * t + std::size_t(k)])] / 3.0;
    }
    const int h = x < 0.5 ? 0 : 1;
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t v = grid.Indices[3 * t + std::size_t(k)];
      if (local[h][v] == ~0u)
      {
        local[h][v] = std::uint32_t(halves[h].VertexCount());
        halves[h].Positions.insert(halves[h].Positions.end(), &grid.Positions[3 * v], &grid.Positions[3 * v] + 3);
        halves[h].Normals.insert(halves[h].Normals.end(), &grid.Normals[3 * v], &grid.Normals[3 * v] + 3);
      }
      halves[h].Indices.push_back(local[h][v]);
    }
    halves[h].BoundaryEdges.push_back(grid.BoundaryEdges[t]);
  }
  ASSERT_EQ(OpenEdges(halves[0]).size() + OpenEdges(halves[1]).size(), OpenEdges(grid).size() + 2 * 20);
  const PatchMesh merged = MergePatches({ &halves[0], &halves[1] });
  EXPECT_EQ(merged.VertexCount(), grid.VertexCount());
  EXPECT_EQ(merged.TriangleCount(), grid.TriangleCount());
  EXPECT_EQ(OpenEdges(merged).size(), OpenEdges(grid).size());
  EXPECT_EQ(EulerCharacteristic(merged), 1);
  for (const auto& e : OpenEdges(merged))
  {
    EXPECT_TRUE(e.second) << "an open edge of the merged mesh is the input's boundary";
  }
}

TEST(Simplifier, ErrorGrowsAsQuotaFalls)
{
  const PatchMesh mesh = Grid(50, Bumps, true);
  double previous = 0;
  for (std::uint32_t quota : { 4000u, 2000u, 800u, 300u })
  {
    const SimplifyResult result = Simplify(mesh, 1, OneRegion(), { quota });
    EXPECT_TRUE(result.QuotasMet());
    EXPECT_GT(result.Error, previous) << quota;
    previous = result.Error;
  }
  EXPECT_LT(previous, 0.1);
}

/// The distance from p to the triangle (a, b, c): to its plane when p projects inside, else to
/// its nearest edge (independent of the simplifier's closest-point code).
double PointTriangleDistance(const double* p, const double* a, const double* b, const double* c)
{
  const auto sub = [](const double* x, const double* y, double* o) {
    for (int i = 0; i < 3; ++i)
    {
      o[i] = x[i] - y[i];
    }
  };
  const auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
  const auto segment = [&](const double* x, const double* y) {
    double d[3], e[3];
    sub(y, x, d);
    sub(p, x, e);
    const double t = std::clamp(dot(d, e) / std::max(dot(d, d), 1e-300), 0.0, 1.0);
    for (int i = 0; i < 3; ++i)
    {
      e[i] -= t * d[i];
    }
    return std::sqrt(dot(e, e));
  };
  double ab[3], ac[3], ap[3];
  sub(b, a, ab);
  sub(c, a, ac);
  sub(p, a, ap);
  const double n[3] = { ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0] };
  const double corners[3][3] = { { a[0], a[1], a[2] }, { b[0], b[1], b[2] }, { c[0], c[1], c[2] } };
  bool inside = dot(n, n) > 0;
  for (int k = 0; k < 3 && inside; ++k)
  {
    double e[3], q[3], m[3];
    sub(corners[(k + 1) % 3], corners[k], e);
    sub(p, corners[k], q);
    m[0] = e[1] * q[2] - e[2] * q[1];
    m[1] = e[2] * q[0] - e[0] * q[2];
    m[2] = e[0] * q[1] - e[1] * q[0];
    inside = dot(m, n) >= 0;
  }
  if (inside)
  {
    return std::abs(dot(ap, n)) / std::sqrt(dot(n, n));
  }
  return std::min({ segment(a, b), segment(b, c), segment(c, a) });
}

/// The largest distance from a vertex of `in` to the triangles of `out`, by brute force.
double LargestDistance(const PatchMesh& in, const PatchMesh& out)
{
  double largest = 0;
  for (std::size_t v = 0; v < in.VertexCount(); ++v)
  {
    const double p[3] = { in.Positions[3 * v], in.Positions[3 * v + 1], in.Positions[3 * v + 2] };
    double nearest = 1e300;
    for (std::size_t t = 0; t < out.TriangleCount(); ++t)
    {
      double c[3][3];
      for (int k = 0; k < 3; ++k)
      {
        for (int i = 0; i < 3; ++i)
        {
          c[k][i] = out.Positions[3 * std::size_t(out.Indices[3 * t + std::size_t(k)]) + std::size_t(i)];
        }
      }
      nearest = std::min(nearest, PointTriangleDistance(p, c[0], c[1], c[2]));
    }
    largest = std::max(largest, nearest);
  }
  return largest;
}

// The reported error bounds the true one and is tight. On the bumpy grid, a walk that stopped
// where a removed vertex's closest point is interior to a face (on a tilted face, no nearest
// point of the surface) reported 0.0126 for a true 0.0033 at 800 triangles.
TEST(Simplifier, ErrorIsTheLargestVertexDistanceToTheOutput)
{
  const PatchMesh torus = BumpyTorus(60, 30);
  const PatchMesh grid = Grid(50, Bumps, true);
  const std::pair<const PatchMesh*, std::uint32_t> cases[] = { { &torus, 600 }, { &grid, 800 }, { &grid, 300 } };
  for (const auto& [mesh, quota] : cases)
  {
    const SimplifyResult result = Simplify(*mesh, 1, OneRegion(), { quota });
    const double largest = LargestDistance(*mesh, Joined(result));
    EXPECT_GT(largest, 0);
    EXPECT_GE(result.Error, largest * (1 - 1e-9)) << "an upper bound, quota " << quota;
    EXPECT_LE(result.Error, largest * 1.01) << "and a tight one, quota " << quota;
  }
}

TEST(Simplifier, PlanarGridHasNoError)
{
  const PatchMesh mesh = Grid(40, [](double, double) { return 0.25; }, false);
  const SimplifyResult result = Simplify(mesh, 1, OneRegion(), { 300 });
  EXPECT_TRUE(result.QuotasMet());
  EXPECT_GT(result.Collapses, 1000u);
  EXPECT_LT(result.Error, 1e-6);
}

/// On a flat mesh over the xy square: the mean, over the input's vertices, of the difference
/// between attribute(input, v) and the output's attribute interpolated at the vertex.
template <typename Attribute>
double MeanInterpolationError(const PatchMesh& input, const PatchMesh& output, Attribute attribute)
{
  double sum = 0;
  for (std::uint32_t v = 0; v < input.VertexCount(); ++v)
  {
    const double x = input.Positions[3 * v], y = input.Positions[3 * v + 1];
    double best = 1e300;
    for (std::size_t t = 0; t < output.TriangleCount(); ++t)
    {
      const std::uint32_t* c = &output.Indices[3 * t];
      const auto at = [&](int k, int a) { return double(output.Positions[3 * std::size_t(c[k]) + std::size_t(a)]); };
      const double det = (at(1, 0) - at(0, 0)) * (at(2, 1) - at(0, 1)) - (at(2, 0) - at(0, 0)) * (at(1, 1) - at(0, 1));
      const double s = ((x - at(0, 0)) * (at(2, 1) - at(0, 1)) - (at(2, 0) - at(0, 0)) * (y - at(0, 1))) / det;
      const double u = ((at(1, 0) - at(0, 0)) * (y - at(0, 1)) - (x - at(0, 0)) * (at(1, 1) - at(0, 1))) / det;
      if (s < -1e-9 || u < -1e-9 || s + u > 1 + 1e-9)
      {
        continue;
      }
      const double value = (1 - s - u) * attribute(output, c[0]) + s * attribute(output, c[1]) + u * attribute(output, c[2]);
      best = std::min(best, std::abs(value - attribute(input, v)));
    }
    EXPECT_LT(best, 1e300) << "vertex " << v << " is not covered";
    sum += best;
  }
  return sum / double(input.VertexCount());
}

TEST(Simplifier, NormalsAndColorsSteerTheCollapses)
{
  // A flat grid whose colors and normals change across a slanted line: positions alone give
  // every collapse the same cost, so only the attributes' quadrics keep the line.
  PatchMesh mesh = Grid(40, [](double, double) { return 0.0; }, false);
  mesh.Colors.clear();
  for (std::uint32_t v = 0; v < mesh.VertexCount(); ++v)
  {
    const bool left = mesh.Positions[3 * v] + 0.3f * mesh.Positions[3 * v + 1] < 0.6f;
    mesh.Colors.insert(mesh.Colors.end(), { std::uint8_t(left ? 255 : 0), 0, std::uint8_t(left ? 0 : 255), 255 });
    const float normal[3] = { left ? 0.f : 0.6f, 0.f, left ? 1.f : 0.8f };
    std::copy(normal, normal + 3, &mesh.Normals[3 * std::size_t(v)]);
  }
  const auto red = [](const PatchMesh& m, std::uint32_t v) { return double(m.Colors[4 * std::size_t(v)]) / 255; };
  const auto normalX = [](const PatchMesh& m, std::uint32_t v) { return double(m.Normals[3 * std::size_t(v)]); };
  const auto errors = [&](double normalWeight, double colorWeight) {
    SimplifyOptions options;
    options.NormalWeight = normalWeight;
    options.ColorWeight = colorWeight;
    const PatchMesh out = Joined(Simplify(mesh, 1, OneRegion(), { 400 }, options));
    EXPECT_LE(out.TriangleCount(), 400u);
    return std::array<double, 2>{ { MeanInterpolationError(mesh, out, red), MeanInterpolationError(mesh, out, normalX) } };
  };
  const std::array<double, 2> neither = errors(0, 0), colors = errors(0, 0.005), normals = errors(0.002, 0);
  std::printf("mean interpolation error of red / normal x: positions only %.4f / %.4f, with colors "
              "%.4f, with normals %.4f\n", neither[0], neither[1], colors[0], normals[1]);
  EXPECT_LT(colors[0], 0.5 * neither[0]);
  EXPECT_LT(normals[1], 0.5 * neither[1]);
}

/// A star: one movable center inside a ring of four locked vertices (the ring's edges are the
/// diamond's external boundary), so that every collapse is the center's onto a ring corner and
/// leaves two of its four triangles, the ring split along a diagonal. The normal of a closed fan
/// is its ring's vector area, so the angle between the faces a collapse leaves and the center's
/// fan normal depends on the ring alone, whatever the star's size; the cost grows with the
/// square of the size.
struct StarShape
{
  std::array<float, 4> RingHeights; ///< of the ring's corners at (1, 0), (0, 1), (-1, 0), (0, -1)
  float CenterHeight;
};
/// Every collapse flattens it: the faces left lie along the fan normal.
constexpr StarShape Cone{ { 0, 0, 0, 0 }, 0.5f };
/// A saddle: every collapse leaves faces 76 degrees from the fan normal, steep but no fin.
constexpr StarShape Steep{ { 2, -2, 2, -2 }, 0 };
/// A steeper saddle: 82 degrees, fins.
constexpr StarShape Finned{ { 3.5f, -3.5f, 3.5f, -3.5f }, 0 };
/// A skewed ring: every collapse leaves a face 96 degrees from the fan normal, against it.
constexpr StarShape Against{ { -4, 0, -3, 1 }, -1 };

/// Appends `count` stars of `shape` scaled by `size`, side by side, their ring edges marked
/// diamond-external; returns their centers.
std::vector<std::uint32_t> AddStars(PatchMesh& mesh, const StarShape& shape, float size, int count)
{
  const float ring[4][2] = { { 1, 0 }, { 0, 1 }, { -1, 0 }, { 0, -1 } };
  std::vector<std::uint32_t> centers;
  for (int i = 0; i < count; ++i)
  {
    const std::uint32_t center = std::uint32_t(mesh.VertexCount());
    const float x = 30.f * float(center); // 150 or more apart: stars are at most 20 across
    mesh.Positions.insert(mesh.Positions.end(), { x, 0.f, size * shape.CenterHeight });
    for (int k = 0; k < 4; ++k)
    {
      mesh.Positions.insert(
        mesh.Positions.end(), { x + size * ring[k][0], size * ring[k][1], size * shape.RingHeights[k] });
    }
    for (std::uint32_t k = 0; k < 4; ++k)
    {
      mesh.Indices.insert(mesh.Indices.end(), { center, center + 1 + k, center + 1 + (k + 1) % 4 });
    }
    centers.push_back(center);
  }
  mesh.BoundaryEdges.resize(mesh.TriangleCount(), 0);
  return centers;
}

/// How many of `vertices` of `in` are still in the result.
std::size_t Kept(const PatchMesh& in, const SimplifyResult& result, const std::vector<std::uint32_t>& vertices)
{
  const std::set<PositionKey> kept = PositionsOf(Joined(result));
  return std::size_t(std::count_if(
    vertices.begin(), vertices.end(), [&](std::uint32_t v) { return kept.count(KeyOf(in, v)) != 0; }));
}

// A collapse that leaves a face within 10 degrees of edge-on to the moved vertex's fan (a fin
// standing off the surface) waits until nothing else is left, however cheap; one that leaves
// faces steep but short of that does not wait.
TEST(Simplifier, FinsOnlyWhenAQuotaNeedsThem)
{
  PatchMesh mesh;
  const std::vector<std::uint32_t> cones = AddStars(mesh, Cone, 10, 3);
  const std::vector<std::uint32_t> steep = AddStars(mesh, Steep, 1.5f, 3);
  const std::vector<std::uint32_t> finned = AddStars(mesh, Finned, 1, 3);
  ASSERT_EQ(mesh.TriangleCount(), 36u);
  // Six collapses: the steep saddles and the cones, though they cost 2 and 30 times as much as
  // the finned saddles.
  const SimplifyResult six = Simplify(mesh, 1, OneRegion(), { 24 });
  EXPECT_TRUE(six.QuotasMet());
  EXPECT_EQ(six.Collapses, 6u);
  EXPECT_EQ(Kept(mesh, six, steep), 0u) << "steep faces are no fins";
  EXPECT_EQ(Kept(mesh, six, cones), 0u);
  EXPECT_EQ(Kept(mesh, six, finned), 3u) << "a fin where other collapses were left";
  // A seventh: only a fin is left.
  const SimplifyResult seven = Simplify(mesh, 1, OneRegion(), { 22 });
  EXPECT_TRUE(seven.QuotasMet());
  EXPECT_EQ(Kept(mesh, seven, cones), 0u);
  EXPECT_EQ(Kept(mesh, seven, finned), 2u);
}

// Faces against the fan's normal come last of all, after fins, however cheap.
TEST(Simplifier, FacesAgainstTheSurfaceOnlyAsALastResort)
{
  PatchMesh mesh;
  const std::vector<std::uint32_t> cones = AddStars(mesh, Cone, 10, 2);
  const std::vector<std::uint32_t> finned = AddStars(mesh, Finned, 1, 2);
  const std::vector<std::uint32_t> against = AddStars(mesh, Against, 1, 2);
  ASSERT_EQ(mesh.TriangleCount(), 24u);
  const SimplifyResult cheapest = Simplify(mesh, 1, OneRegion(), { 20 });
  EXPECT_EQ(Kept(mesh, cheapest, cones), 0u);
  EXPECT_EQ(Kept(mesh, cheapest, finned) + Kept(mesh, cheapest, against), 4u);
  const SimplifyResult fins = Simplify(mesh, 1, OneRegion(), { 16 });
  EXPECT_TRUE(fins.QuotasMet());
  EXPECT_EQ(Kept(mesh, fins, finned), 0u);
  EXPECT_EQ(Kept(mesh, fins, against), 2u) << "a face against the surface where fins were left";
  const SimplifyResult all = Simplify(mesh, 1, OneRegion(), { 12 });
  EXPECT_TRUE(all.QuotasMet());
  EXPECT_EQ(all.Collapses, 6u);
}

/// Appends a closed tetrahedron, its corner at `corner` and its edges along the axes `size` long,
/// oriented outward; its vertices are all `size` * sqrt(3) / 2 from the center of its box.
void AddTetrahedron(PatchMesh& mesh, float x, float y, float z, float size)
{
  const std::uint32_t first = std::uint32_t(mesh.VertexCount());
  mesh.Positions.insert(mesh.Positions.end(), { x, y, z, x + size, y, z, x, y + size, z, x, y, z + size });
  for (const std::uint32_t corner : { 0u, 2u, 1u, 0u, 1u, 3u, 0u, 3u, 2u, 1u, 2u, 3u })
  {
    mesh.Indices.push_back(first + corner);
  }
}

// Closed pieces (tetrahedra here, what an isosurface's specks end as) cannot shrink, and can
// hold most of a coarse patch: with nothing else left for the quota they go whole, smallest
// first, their vertices counted as moved to the centers of their boxes. Pieces with a locked
// vertex or an open edge stay.
TEST(Simplifier, ClosedPiecesGoWholeSmallestFirst)
{
  // A strip whose vertices are all on the external boundary: 100 triangles that cannot go.
  PatchMesh mesh = Strip();
  // Six tetrahedra, the smallest last, and one triangle alone, its edges the input's boundary.
  const float sizes[6] = { 0.6f, 0.5f, 0.4f, 0.3f, 0.2f, 0.1f };
  for (int i = 0; i < 6; ++i)
  {
    AddTetrahedron(mesh, 5.f * float(i), 5.f, 0.f, sizes[i]);
  }
  const std::uint32_t lone = std::uint32_t(mesh.VertexCount());
  mesh.Positions.insert(mesh.Positions.end(), { 0.f, 10.f, 0.f, 1.f, 10.f, 0.f, 0.f, 11.f, 0.f });
  mesh.Indices.insert(mesh.Indices.end(), { lone, lone + 1, lone + 2 });
  ComputeNormals(mesh);
  MarkOpenEdges(mesh, false);
  mesh.BoundaryEdges.back() = 7;
  ASSERT_EQ(mesh.TriangleCount(), 125u);

  // Two tetrahedra must go: the two smallest.
  const SimplifyResult two = Simplify(mesh, 1, OneRegion(), { 117 });
  EXPECT_TRUE(two.QuotasMet());
  EXPECT_EQ(TriangleTotal(two), 117u);
  EXPECT_EQ(two.PiecesRemoved, 2u);
  EXPECT_EQ(two.Collapses, 0u);
  EXPECT_NEAR(two.Error, 0.2 * std::sqrt(3.0) / 2, 1e-6) << "the larger of the two, moved to its center";
  const std::set<PositionKey> kept = PositionsOf(Joined(two));
  for (std::uint32_t v = 0; v < mesh.VertexCount(); ++v)
  {
    const bool inSmallest = v >= 102 + 4 * 4 && v < lone;
    EXPECT_EQ(kept.count(KeyOf(mesh, v)), inSmallest ? 0u : 1u) << "vertex " << v;
  }

  // Out of reach: every tetrahedron goes, then the lone triangle, open only along the input's
  // boundary (its box is the largest); the strip, on the external border, stays.
  const SimplifyResult all = Simplify(mesh, 1, OneRegion(), { 1 });
  EXPECT_EQ(all.PiecesRemoved, 7u);
  EXPECT_EQ(TriangleTotal(all), 100u);
  EXPECT_EQ(all.TrianglesOverQuotas, 99u);
  EXPECT_NEAR(all.Error, std::sqrt(2.0) / 2, 1e-6);

  // A piece with a vertex on the external border is no piece to remove: the lone triangle with
  // one edge not of the input's boundary (so locked) stays.
  mesh.BoundaryEdges.back() = 6;
  EXPECT_EQ(Simplify(mesh, 1, OneRegion(), { 1 }).PiecesRemoved, 6u);
}

// A piece no larger than the deviation the collapses already made goes before a face may turn
// nearly edge-on to the surface: it costs no error, where the fin shows. A larger one stays
// while fins can meet the quota: its removal would raise the error.
TEST(Simplifier, ClosedPiecesWithinTheErrorGoBeforeFins)
{
  for (const float size : { 1.f, 20.f })
  {
    // Flattening the cones moves their centers by 5; then 4 more triangles must go: the
    // tetrahedron (its corners 0.87 or 17 from its center) or two fins.
    PatchMesh mesh;
    AddStars(mesh, Cone, 10, 2);
    const std::vector<std::uint32_t> finned = AddStars(mesh, Finned, 1, 2);
    AddTetrahedron(mesh, 0.f, 50.f, 0.f, size);
    mesh.BoundaryEdges.resize(mesh.TriangleCount(), 0);
    const SimplifyResult result = Simplify(mesh, 1, OneRegion(), { 12 });
    EXPECT_TRUE(result.QuotasMet());
    const bool small = size < 5;
    EXPECT_EQ(result.PiecesRemoved, small ? 1u : 0u) << "tetrahedron of size " << size;
    EXPECT_EQ(Kept(mesh, result, finned), small ? 2u : 0u);
    if (small)
    {
      EXPECT_NEAR(result.Error, 5.0, 1e-5);
    }
  }
}

TEST(Simplifier, EmptyInput)
{
  const SimplifyResult result = Simplify(PatchMesh(), 2, OneRegion(), { 0, 5 });
  ASSERT_EQ(result.Regions.size(), 2u);
  EXPECT_TRUE(result.QuotasMet());
  EXPECT_EQ(result.Collapses, 0u);
  EXPECT_EQ(TriangleTotal(result), 0u);
  EXPECT_EQ(MergePatches({}).VertexCount(), 0u);
}

// Random keys set, changed, moved between queues and removed, checked against ordered sets
// after every step: each queue's front is its least (cost, vertex), every vertex in one queue.
TEST(CollapseQueues, FrontsFollowChangingKeys)
{
  constexpr std::size_t QueueCount = 3, VertexCount = 200;
  CollapseQueues queues(QueueCount, VertexCount);
  std::vector<std::set<std::pair<double, std::uint32_t>>> expected(QueueCount);
  std::vector<int> queueOf(VertexCount, -1);
  std::vector<double> costOf(VertexCount, 0);
  std::mt19937 random(7);
  // Few distinct costs, so that ties (broken by vertex) are common.
  std::uniform_int_distribution<int> cost(0, 20), vertex(0, int(VertexCount) - 1),
    queue(0, int(QueueCount) - 1), action(0, 3);
  const auto set = [&](std::uint32_t v, int q, double c) {
    if (queueOf[std::size_t(v)] >= 0)
    {
      expected[std::size_t(queueOf[v])].erase({ costOf[v], v });
    }
    queues.Set(v, std::size_t(q), c);
    expected[std::size_t(q)].insert({ c, v });
    queueOf[v] = q;
    costOf[v] = c;
  };
  // Before Order(): appended only, then heaped at once.
  for (std::uint32_t v = 0; v < VertexCount; v += 2)
  {
    set(v, queue(random), cost(random));
  }
  set(4, 1, 0.5); // a second key before ordering replaces the first
  queues.Order();
  for (int step = 0; step < 20000; ++step)
  {
    const std::uint32_t v = std::uint32_t(vertex(random));
    const int a = action(random);
    if (a == 0 && queueOf[v] >= 0)
    {
      expected[std::size_t(queueOf[v])].erase({ costOf[v], v });
      queues.Remove(v);
      queueOf[v] = -1;
    }
    else if (a == 1 && queueOf[v] >= 0)
    {
      set(v, queueOf[v], cost(random)); // the same queue, a new key
    }
    else if (a == 2 && !expected[0].empty())
    {
      const std::uint32_t front = queues.Front(0).Vertex; // pop
      expected[0].erase({ costOf[front], front });
      queues.Remove(front);
      queueOf[front] = -1;
    }
    else
    {
      set(v, queue(random), cost(random));
    }
    for (std::size_t q = 0; q < QueueCount; ++q)
    {
      ASSERT_EQ(queues.Empty(q), expected[q].empty()) << "step " << step;
      if (!expected[q].empty())
      {
        ASSERT_EQ(queues.Front(q).Vertex, expected[q].begin()->second) << "step " << step;
        ASSERT_EQ(queues.Front(q).Cost, expected[q].begin()->first) << "step " << step;
      }
    }
    ASSERT_EQ(queues.Queued(v), queueOf[v] >= 0);
  }
  // Popped to the end, each queue gives its keys in order: a heap broken below its front shows.
  for (std::size_t q = 0; q < QueueCount; ++q)
  {
    for (const auto& [c, v] : expected[q])
    {
      ASSERT_FALSE(queues.Empty(q));
      ASSERT_EQ(queues.Front(q).Vertex, v);
      ASSERT_EQ(queues.Front(q).Cost, c);
      queues.Remove(v);
    }
    EXPECT_TRUE(queues.Empty(q));
  }
}

TEST(Simplifier, RejectsMismatchedQuotasAndRegionsOutOfRange)
{
  const PatchMesh mesh = Grid(10, [](double, double) { return 0.25; }, false);
  EXPECT_THROW(Simplify(mesh, 2, OneRegion(), { 10 }), std::invalid_argument);
  EXPECT_THROW(Simplify(mesh, 0, OneRegion(), {}), std::invalid_argument);
  EXPECT_THROW(Simplify(mesh, 1 << 30, OneRegion(), { 10 }), std::invalid_argument); // nothing sized first
  const RegionFunction outside = [](const double*, int) { return 2; };
  EXPECT_THROW(Simplify(mesh, 2, outside, { 10, 10 }), std::invalid_argument);
}

// Q(p, s) of one triangle is w times its squared plane distance plus, per attribute, w times
// the squared deviation of s from the attribute's linear field at p; for attribute counts the
// evaluation unrolls (0, 3, 4, 7) and for others.
TEST(Quadric, ATrianglesQuadricIsItsWeightedPlaneDistanceAndFieldDeviation)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> value(-1, 1);
  for (const int attributes : { 0, 2, 3, 4, 7 })
  {
    double n[3] = { value(random), value(random), value(random) };
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& x : n)
    {
      x /= length;
    }
    const double d = value(random);
    const double w = 0.5 + value(random) * value(random);
    const std::size_t count = static_cast<std::size_t>(attributes);
    std::vector<double> g(3 * count), offsets(count);
    for (double& x : g)
    {
      x = value(random);
    }
    for (double& x : offsets)
    {
      x = value(random);
    }
    std::vector<double> q(Quadric::Size(attributes), -1.0); // every entry is written
    Quadric::SetTriangle(q.data(), n, d, attributes, g.data(), offsets.data(), w);
    for (int trial = 0; trial < 20; ++trial)
    {
      const double p[3] = { value(random), value(random), value(random) };
      std::vector<double> s(count);
      double expected = n[0] * p[0] + n[1] * p[1] + n[2] * p[2] + d;
      expected = w * expected * expected;
      for (int j = 0; j < attributes; ++j)
      {
        s[std::size_t(j)] = value(random);
        const double* gj = &g[3 * std::size_t(j)];
        const double deviation = gj[0] * p[0] + gj[1] * p[1] + gj[2] * p[2] +
          offsets[std::size_t(j)] - s[std::size_t(j)];
        expected += w * deviation * deviation;
      }
      EXPECT_NEAR(Quadric::Evaluate(q.data(), attributes, p, s.data()), expected, 1e-12)
        << attributes << " attributes";
    }
  }
}

TEST(Quadric, AddingToCornersAddsToEachRecord)
{
  const std::size_t n = Quadric::Size(3) + 1;
  std::vector<double> r(n), a(n), b(n), c(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    r[i] = 0.5 * double(i) + 1;
    a[i] = double(i);
    b[i] = -double(i);
    c[i] = 3;
  }
  Quadric::AddToCorners(a.data(), b.data(), c.data(), r.data(), n);
  for (std::size_t i = 0; i < n; ++i)
  {
    EXPECT_EQ(a[i], double(i) + r[i]);
    EXPECT_EQ(b[i], -double(i) + r[i]);
    EXPECT_EQ(c[i], 3 + r[i]);
  }
}

// A triangle without area (collinear corners, or all but: slivers reach the simplifier): the
// point found is finite and no point of its sides is nearer. Without a case for it the face's
// barycentric weights divided by zero.
TEST(ClosestPoint, ATriangleWithoutAreaGivesTheNearestPointOfItsSides)
{
  std::mt19937 random(11);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  for (int trial = 0; trial < 200; ++trial)
  {
    // Corners at a, a + d and a + k d: with d of few bits exactly collinear (even trials), else
    // as nearly as doubles round.
    const bool exact = trial % 2 == 0;
    double d[3];
    for (double& x : d)
    {
      x = exact ? std::ldexp(std::round(8 * coordinate(random)), -3) : coordinate(random);
    }
    const double k = trial % 3 == 0 ? 0.37 : (trial % 3 == 1 ? -1.3 : 2.1); // c between, before, after
    double corner[3][3], p[3];
    for (int i = 0; i < 3; ++i)
    {
      corner[0][i] = exact ? std::round(8 * coordinate(random)) / 8 : coordinate(random);
      corner[1][i] = corner[0][i] + d[i];
      corner[2][i] = corner[0][i] + k * d[i];
      p[i] = coordinate(random);
    }
    const TrianglePoint found = ClosestOnTriangle(p, corner[0], corner[1], corner[2]);
    double found2 = 0;
    for (int i = 0; i < 3; ++i)
    {
      ASSERT_TRUE(std::isfinite(found.Point[i])) << "trial " << trial;
      found2 += (found.Point[i] - p[i]) * (found.Point[i] - p[i]);
    }
    for (int side = 0; side < 3; ++side)
    {
      const double* from = corner[side];
      const double* to = corner[(side + 1) % 3];
      for (int s = 0; s <= 400; ++s)
      {
        double q2 = 0;
        for (int i = 0; i < 3; ++i)
        {
          const double q = from[i] + (to[i] - from[i]) * s / 400;
          q2 += (q - p[i]) * (q - p[i]);
        }
        ASSERT_GE(q2, found2 - 1e-12) << "trial " << trial << " side " << side;
      }
    }
  }
}

// Against a dense sampling of each triangle: nothing sampled is nearer than the point found,
// which lies on the triangle, inside it exactly when it says so. Points near corners, edges and
// the face, of thin and obtuse triangles as well.
TEST(ClosestPoint, NoSampleOfTheTriangleIsNearer)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  int interiors = 0, borders = 0;
  for (int trial = 0; trial < 300; ++trial)
  {
    double corner[3][3], p[3];
    for (auto& c : corner)
    {
      for (double& x : c)
      {
        x = coordinate(random);
      }
    }
    if (trial % 3 == 0) // a sliver: c almost on the line through a and b
    {
      for (int i = 0; i < 3; ++i)
      {
        corner[2][i] = 0.3 * corner[0][i] + 0.7 * corner[1][i] + 0.01 * coordinate(random);
      }
    }
    for (double& x : p)
    {
      x = coordinate(random);
    }
    const TrianglePoint found = ClosestOnTriangle(p, corner[0], corner[1], corner[2]);
    ASSERT_GE(found.S, 0.0);
    ASSERT_GE(found.T, 0.0);
    ASSERT_LE(found.S + found.T, 1.0 + 1e-12);
    const auto at = [&](double s, double t, double q[3]) {
      for (int i = 0; i < 3; ++i)
      {
        q[i] = corner[0][i] + s * (corner[1][i] - corner[0][i]) + t * (corner[2][i] - corner[0][i]);
      }
    };
    const auto distance2 = [&](const double q[3]) {
      return (q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) + (q[2] - p[2]) * (q[2] - p[2]);
    };
    double q[3];
    at(found.S, found.T, q);
    for (int i = 0; i < 3; ++i)
    {
      ASSERT_NEAR(found.Point[i], q[i], 1e-12) << "trial " << trial;
    }
    const double foundDistance2 = distance2(found.Point);
    const int n = 200;
    for (int i = 0; i <= n; ++i)
    {
      for (int j = 0; i + j <= n; ++j)
      {
        at(double(i) / n, double(j) / n, q);
        ASSERT_GE(distance2(q), foundDistance2 - 1e-12) << "trial " << trial;
      }
    }
    const bool onBorder = found.S == 0 || found.T == 0 || std::abs(found.S + found.T - 1) < 1e-12;
    (onBorder ? borders : interiors) += 1;
  }
  EXPECT_GT(interiors, 10);
  EXPECT_GT(borders, 10);
}
