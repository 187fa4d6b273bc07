// Patch codec and quantization grid: round trips keep the triangle set, positions on the one
// global grid (bit-identical across patches), normals and colors; hostile bytes only ever give
// PatchFormatError or a valid patch.
#include "MeshTriangles.h"
#include "atpNormalEncoding.h"
#include "atpPatchCodec.h"
#include "atpQuantizationGrid.h"

#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace
{
using atp::test::Bits;
using atp::test::TriangleSet;
using Corner = atp::test::CornerBits;

/// A bumpy height field over [x0, x0 + size]^2 with unit normals, n x n quads, optional colors,
/// and its vertices shuffled so the encoder has reordering to do.
atp::PatchMesh Terrain(float x0, float y0, float size, int n, bool colors, unsigned seed)
{
  atp::PatchMesh mesh;
  const int side = n + 1;
  std::vector<std::uint32_t> order(side * side);
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    order[i] = static_cast<std::uint32_t>(i);
  }
  std::mt19937 random(seed);
  std::shuffle(order.begin(), order.end(), random);
  mesh.Positions.resize(3 * order.size());
  mesh.Normals.resize(3 * order.size());
  for (int j = 0; j < side; ++j)
  {
    for (int i = 0; i < side; ++i)
    {
      const std::uint32_t v = order[j * side + i];
      const float x = x0 + size * i / n;
      const float y = y0 + size * j / n;
      // Heights depend on x and y only: terrains that overlap share their vertices exactly.
      mesh.Positions[3 * v] = x;
      mesh.Positions[3 * v + 1] = y;
      mesh.Positions[3 * v + 2] = 0.1f * std::sin(3 * x) * std::cos(2 * y);
      const float dx = 0.3f * std::cos(3 * x) * std::cos(2 * y);
      const float dy = -0.2f * std::sin(3 * x) * std::sin(2 * y);
      const float length = std::sqrt(dx * dx + dy * dy + 1);
      mesh.Normals[3 * v] = -dx / length;
      mesh.Normals[3 * v + 1] = -dy / length;
      mesh.Normals[3 * v + 2] = 1 / length;
    }
  }
  if (colors)
  {
    mesh.Colors.resize(4 * order.size());
    for (std::size_t k = 0; k < mesh.Colors.size(); ++k)
    {
      mesh.Colors[k] = static_cast<std::uint8_t>(random());
    }
  }
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      const std::uint32_t a = order[j * side + i], b = order[j * side + i + 1];
      const std::uint32_t c = order[(j + 1) * side + i], d = order[(j + 1) * side + i + 1];
      mesh.Indices.insert(mesh.Indices.end(), { a, b, d, a, d, c });
    }
  }
  return mesh;
}

atp::QuantizationGrid GridFor(float lo, float hi, int extraBitsDropped = 0)
{
  const double min[3] = { lo, lo, lo };
  const double max[3] = { hi, hi, hi };
  return atp::QuantizationGrid::ForBounds(min, max, extraBitsDropped);
}

atp::PatchMesh RoundTrip(const atp::PatchMesh& mesh, const atp::QuantizationGrid& grid)
{
  const std::vector<std::uint8_t> bytes = atp::EncodePatch(mesh, grid);
  atp::PatchMesh decoded;
  atp::DecodePatch(bytes.data(), bytes.size(), grid, decoded);
  return decoded;
}

/// What the codec promises for any decoded patch, hostile input or not.
void ExpectValid(const atp::PatchMesh& mesh)
{
  const std::size_t vertices = mesh.VertexCount();
  ASSERT_EQ(mesh.Positions.size(), 3 * vertices);
  ASSERT_EQ(mesh.Normals.size(), 3 * vertices);
  ASSERT_TRUE(mesh.Colors.empty() || mesh.Colors.size() == 4 * vertices);
  ASSERT_EQ(mesh.Indices.size() % 3, 0u);
  ASSERT_TRUE(mesh.BoundaryEdges.empty());
  for (const std::uint32_t i : mesh.Indices)
  {
    ASSERT_LT(i, vertices);
  }
  for (std::size_t v = 0; v < vertices; ++v)
  {
    const float* n = &mesh.Normals[3 * v];
    ASSERT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0f, 1e-5f);
  }
}

/// What atpPatchCodec.h states for its NormalBits-bit normals.
constexpr double StatedNormalErrorDegrees = 0.12;

double AngleDegrees(const float* a, const float* b)
{
  const double cross[3] = { double(a[1]) * b[2] - double(a[2]) * b[1],
    double(a[2]) * b[0] - double(a[0]) * b[2], double(a[0]) * b[1] - double(a[1]) * b[0] };
  const double dot = double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
  return std::atan2(std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]),
           dot) * 180 / std::acos(-1.0);
}

TEST(QuantizationGrid, StepIsTheUlpOfTheLargestCoordinate)
{
  const double min[3] = { -3.0, 0.5, 1.0 };
  const double max[3] = { 1.0, 6.0, 2.0 }; // largest |coordinate| 6, binade [4, 8)
  const atp::QuantizationGrid grid = atp::QuantizationGrid::ForBounds(min, max);
  EXPECT_EQ(grid.Step, std::ldexp(1.0, 2 - 23));
  EXPECT_EQ(grid.MaxError(), grid.Step / 2);
  EXPECT_EQ(atp::QuantizationGrid::ForBounds(min, max, 3).Step, 8 * grid.Step);
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_LE(grid.Origin[a], min[a]);
    EXPECT_EQ(std::fmod(grid.Origin[a], grid.Step), 0.0);
    const float corner[3] = { float(max[0]), float(max[1]), float(max[2]) };
    EXPECT_LT(grid.Quantize(corner)[a], atp::QuantizationGrid::MaxInteger);
  }
}

TEST(QuantizationGrid, DegenerateBoxes)
{
  const double origin[3] = { 0, 0, 0 };
  const atp::QuantizationGrid point = atp::QuantizationGrid::ForBounds(origin, origin);
  EXPECT_GT(point.Step, 0.0);
  const float zero[3] = { 0, 0, 0 };
  float back[3];
  point.Dequantize(point.Quantize(zero).data(), back);
  EXPECT_EQ(Bits(back), Bits(zero));

  const double flatMin[3] = { -2, 5, 1 };
  const double flatMax[3] = { 3, 5, 4 }; // flat in y
  const atp::QuantizationGrid flat = atp::QuantizationGrid::ForBounds(flatMin, flatMax);
  const float p[3] = { 0.25f, 5, 3.5f };
  flat.Dequantize(flat.Quantize(p).data(), back);
  EXPECT_EQ(Bits(back), Bits(p));

  const double nan[3] = { 0, std::nan(""), 0 };
  EXPECT_THROW(atp::QuantizationGrid::ForBounds(origin, nan), std::invalid_argument);
  EXPECT_THROW(atp::QuantizationGrid::ForBounds(flatMax, flatMin), std::invalid_argument);
}

TEST(QuantizationGrid, ClampsOutsideTheBox)
{
  const atp::QuantizationGrid grid = GridFor(-1, 1);
  const float far[3] = { -1e30f, 1e30f, std::nanf("") };
  const std::array<std::uint32_t, 3> q = grid.Quantize(far);
  EXPECT_EQ(q[0], 0u);
  EXPECT_EQ(q[1], atp::QuantizationGrid::MaxInteger);
  EXPECT_EQ(q[2], 0u);
}

TEST(PatchCodec, RoundTripKeepsTrianglesPositionsNormalsColors)
{
  const atp::PatchMesh mesh = Terrain(-1.5f, 0.25f, 1.0f, 40, true, 1);
  const atp::QuantizationGrid grid = GridFor(-2, 2);
  const atp::PatchMesh decoded = RoundTrip(mesh, grid);
  ExpectValid(decoded);
  ASSERT_EQ(decoded.VertexCount(), mesh.VertexCount());
  ASSERT_EQ(decoded.TriangleCount(), mesh.TriangleCount());

  // The expected decoded position of each input vertex is its grid point.
  std::vector<float> snapped(mesh.Positions.size());
  for (std::size_t v = 0; v < mesh.VertexCount(); ++v)
  {
    grid.Dequantize(grid.Quantize(&mesh.Positions[3 * v]).data(), &snapped[3 * v]);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_LE(std::fabs(snapped[3 * v + a] - mesh.Positions[3 * v + a]), grid.MaxError());
    }
  }
  EXPECT_EQ(TriangleSet(decoded.Positions, decoded.Indices),
    TriangleSet(snapped, mesh.Indices));

  // Match vertices by snapped position (all distinct here) to compare normals and colors.
  std::vector<std::pair<Corner, std::size_t>> byPosition;
  for (std::size_t v = 0; v < mesh.VertexCount(); ++v)
  {
    byPosition.emplace_back(Bits(&snapped[3 * v]), v);
  }
  std::sort(byPosition.begin(), byPosition.end());
  double worstDegrees = 0;
  for (std::size_t v = 0; v < decoded.VertexCount(); ++v)
  {
    const auto found = std::lower_bound(byPosition.begin(), byPosition.end(),
      std::make_pair(Bits(&decoded.Positions[3 * v]), std::size_t(0)));
    ASSERT_NE(found, byPosition.end());
    ASSERT_EQ(found->first, Bits(&decoded.Positions[3 * v]));
    const std::size_t original = found->second;
    worstDegrees = std::max(
      worstDegrees, AngleDegrees(&decoded.Normals[3 * v], &mesh.Normals[3 * original]));
    for (int k = 0; k < 4; ++k)
    {
      EXPECT_EQ(decoded.Colors[4 * v + k], mesh.Colors[4 * original + k]);
    }
  }
  EXPECT_LT(worstDegrees, StatedNormalErrorDegrees);
}

TEST(PatchCodec, NormalsWithinStatedAngularError)
{
  // One triangle per normal would be wasteful: a fan over many vertices at one point.
  atp::PatchMesh mesh;
  std::mt19937 random(7);
  std::normal_distribution<float> gaussian;
  const int count = 20000;
  for (int v = 0; v < count; ++v)
  {
    float n[3] = { gaussian(random), gaussian(random), gaussian(random) };
    if (v < 6) // the axes, where octahedral folding has its corners
    {
      n[0] = n[1] = n[2] = 0;
      n[v / 2] = v % 2 ? -1.0f : 1.0f;
    }
    const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int a = 0; a < 3; ++a)
    {
      mesh.Normals.push_back(n[a] / length);
      mesh.Positions.push_back(float(v));
    }
  }
  for (std::uint32_t v = 0; v + 2 < count; v += 3)
  {
    mesh.Indices.insert(mesh.Indices.end(), { v, v + 1, v + 2 });
  }
  const atp::QuantizationGrid grid = GridFor(0, count);
  const atp::PatchMesh decoded = RoundTrip(mesh, grid);
  ExpectValid(decoded);
  double worstDegrees = 0;
  for (std::size_t v = 0; v < decoded.VertexCount(); ++v)
  {
    // Positions are v, v, v: exact on this grid, so they name the original vertex.
    const std::size_t original = static_cast<std::size_t>(decoded.Positions[3 * v]);
    worstDegrees = std::max(
      worstDegrees, AngleDegrees(&decoded.Normals[3 * v], &mesh.Normals[3 * original]));
  }
  EXPECT_LT(worstDegrees, StatedNormalErrorDegrees);
  // Not far below it either: the stream really holds NormalBits bits, not 16.
  EXPECT_GT(worstDegrees, StatedNormalErrorDegrees / 2);
  std::printf("octahedral normals of %d bits: max angular error %.5f degrees\n", atp::NormalBits,
    worstDegrees);
}

// Vertex normals are sums of area-weighted face normals: a mesh with huge coordinates overflows
// them (the mesh fuzzer found NaN reaching the int16 conversion). Every float vector encodes to
// a unit normal, in the direction that is left of it.
TEST(NormalEncoding, OverflowedAndNaNVectorsEncodeToUnitNormals)
{
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float half = std::sqrt(0.5f);
  const struct
  {
    float Given[3];
    float Expected[3];
  } cases[] = {
    { { inf, 5, 0 }, { 1, 0, 0 } },
    { { inf, -inf, 7 }, { half, -half, 0 } },
    { { 0, 0, -inf }, { 0, 0, -1 } },
    { { nan, nan, nan }, { 0, 0, 1 } },
    { { nan, 1, 0 }, { 0, 1, 0 } },
    { { 3e38f, 3e38f, 0 }, { half, half, 0 } },
    { { -3e38f, 0, -3e38f }, { -half, 0, -half } },
  };
  for (const auto& c : cases)
  {
    std::int16_t encoded[2];
    atp::EncodeNormal(c.Given, encoded);
    float decoded[3];
    atp::DecodeNormal(encoded, decoded);
    EXPECT_LT(AngleDegrees(decoded, c.Expected), 0.01)
      << c.Given[0] << " " << c.Given[1] << " " << c.Given[2];
  }
}

TEST(PatchCodec, SharedVertexIsBitIdenticalAcrossPatches)
{
  // Two patches of different extents and vertex orders meeting at x = 0.5, y in [0, 1].
  const atp::QuantizationGrid grid = GridFor(-4, 4);
  const atp::PatchMesh small = RoundTrip(Terrain(0.0f, 0.0f, 0.5f, 8, false, 2), grid);
  const atp::PatchMesh large = RoundTrip(Terrain(0.5f, 0.0f, 2.0f, 32, false, 3), grid);
  ExpectValid(small);
  ExpectValid(large);
  std::vector<Corner> seam;
  for (std::size_t v = 0; v < small.VertexCount(); ++v)
  {
    if (small.Positions[3 * v] == 0.5f)
    {
      seam.push_back(Bits(&small.Positions[3 * v]));
    }
  }
  std::vector<Corner> largeCorners;
  for (std::size_t v = 0; v < large.VertexCount(); ++v)
  {
    largeCorners.push_back(Bits(&large.Positions[3 * v]));
  }
  std::sort(largeCorners.begin(), largeCorners.end());
  int shared = 0;
  for (const Corner& c : seam)
  {
    shared += std::binary_search(largeCorners.begin(), largeCorners.end(), c);
  }
  // Both tessellations have y = j / 16 on the seam: the small patch's 9 seam vertices.
  EXPECT_EQ(seam.size(), 9u);
  EXPECT_EQ(shared, 9);
}

TEST(PatchCodec, TopBinadeCoordinatesAreBitExact)
{
  // Box up to 6: every float with magnitude in [4, 8) lies on the grid.
  const atp::QuantizationGrid grid = GridFor(-7.5f, 6.0f);
  atp::PatchMesh mesh;
  std::mt19937 random(11);
  std::uniform_real_distribution<float> magnitude(4.0f, 7.5f);
  for (std::uint32_t v = 0; v < 3000; ++v)
  {
    for (int a = 0; a < 3; ++a)
    {
      const float m = magnitude(random);
      mesh.Positions.push_back(random() % 2 && m <= 6.0f ? m : -m);
      mesh.Normals.push_back(a == 2 ? 1.0f : 0.0f);
    }
  }
  for (std::uint32_t v = 0; v + 2 < 3000; v += 3)
  {
    mesh.Indices.insert(mesh.Indices.end(), { v, v + 1, v + 2 });
  }
  const atp::PatchMesh decoded = RoundTrip(mesh, grid);
  ExpectValid(decoded);
  EXPECT_EQ(TriangleSet(decoded.Positions, decoded.Indices),
    TriangleSet(mesh.Positions, mesh.Indices));
}

/// Scanner-like noise on the heights, a function of x and y only (like Terrain's heights).
void Roughen(atp::PatchMesh& mesh, float amplitude)
{
  for (std::size_t v = 0; v < mesh.VertexCount(); ++v)
  {
    const float x = mesh.Positions[3 * v], y = mesh.Positions[3 * v + 1];
    mesh.Positions[3 * v + 2] += amplitude * std::sin(12345.0f * x) * std::cos(23456.0f * y);
  }
}

/// Bytes of the position stream (the second of the four stream sizes that end the header).
std::size_t PositionStreamBytes(const std::vector<std::uint8_t>& bytes)
{
  std::uint32_t size;
  std::memcpy(&size, &bytes[atp::PatchHeaderBytes - 12], sizeof(size));
  return size;
}

/// Bytes of the normal stream (the third).
std::size_t NormalStreamBytes(const std::vector<std::uint8_t>& bytes)
{
  std::uint32_t size;
  std::memcpy(&size, &bytes[atp::PatchHeaderBytes - 8], sizeof(size));
  return size;
}

// Construction takes a patch's sphere and cone from what a reader decodes, which the encoder
// hands out without decoding: it must be exactly that.
TEST(PatchCodec, EncodersDecodedMeshIsTheDecodersBitForBit)
{
  const atp::QuantizationGrid grid = GridFor(-2, 2);
  atp::PatchPrecision coarse;
  coarse.InteriorPositionShift = 9;
  atp::PatchMesh rough = Terrain(-1.5f, 0.25f, 1.0f, 30, true, 5);
  Roughen(rough, 1e-3f);
  for (const atp::PatchPrecision& precision : { atp::PatchPrecision(), coarse })
  {
    for (const atp::PatchMesh& mesh : { rough, Terrain(0, 0, 0.5f, 7, false, 2), atp::PatchMesh() })
    {
      for (const atp::CacheOrder order : { atp::CacheOrder::Best, atp::CacheOrder::Fast })
      {
        atp::PatchMesh fromEncoder, fromBytes;
        const std::vector<std::uint8_t> bytes =
          atp::EncodePatch(mesh, grid, precision, &fromEncoder, order);
        atp::DecodePatch(bytes.data(), bytes.size(), grid, fromBytes);
        EXPECT_EQ(fromEncoder.Indices, fromBytes.Indices);
        EXPECT_EQ(fromEncoder.Positions, fromBytes.Positions);
        EXPECT_EQ(fromEncoder.Normals, fromBytes.Normals);
        EXPECT_EQ(fromEncoder.Colors, fromBytes.Colors);
        EXPECT_TRUE(fromEncoder.BoundaryEdges.empty());
      }
    }
  }
}

// The fast order is another order of the same triangles, still one a vertex cache likes: close
// to the best order's misses, far below the input's shuffled order.
TEST(PatchCodec, FastCacheOrderKeepsTheTrianglesInAnotherGoodOrder)
{
  const atp::QuantizationGrid grid = GridFor(-2, 2);
  atp::PatchMesh mesh = Terrain(-1.5f, 0.25f, 1.0f, 40, true, 3);
  std::vector<std::size_t> order(mesh.TriangleCount());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::shuffle(order.begin(), order.end(), std::mt19937(3));
  const std::vector<std::uint32_t> rows = mesh.Indices;
  for (std::size_t t = 0; t < order.size(); ++t)
  {
    std::copy_n(&rows[3 * order[t]], 3, &mesh.Indices[3 * t]);
  }
  std::map<atp::CacheOrder, atp::PatchMesh> decoded;
  for (const atp::CacheOrder order : { atp::CacheOrder::Best, atp::CacheOrder::Fast })
  {
    const std::vector<std::uint8_t> bytes = atp::EncodePatch(mesh, grid, {}, nullptr, order);
    atp::DecodePatch(bytes.data(), bytes.size(), grid, decoded[order]);
    ExpectValid(decoded[order]);
  }
  const atp::PatchMesh& best = decoded[atp::CacheOrder::Best];
  const atp::PatchMesh& fast = decoded[atp::CacheOrder::Fast];
  EXPECT_EQ(TriangleSet(fast.Positions, fast.Indices), TriangleSet(best.Positions, best.Indices));
  EXPECT_NE(fast.Indices, best.Indices);
  const auto missesPerTriangle = [](const atp::PatchMesh& m) {
    return meshopt_analyzeVertexCache(m.Indices.data(), m.Indices.size(), m.VertexCount(), 16, 0, 0)
      .acmr;
  };
  const float input = missesPerTriangle(mesh);
  const float bestMisses = missesPerTriangle(best);
  const float fastMisses = missesPerTriangle(fast);
  EXPECT_LT(fastMisses, 1.1f * bestMisses);
  EXPECT_LT(fastMisses, 0.6f * input);
}

// A vertex whose input triangles are not all in the patch (PatchMesh::InputUses over its
// corners' CornerUses: a sheet elsewhere on one of its edges) is shared with another patch, so
// it keeps the full grid where the interior is stored coarser.
TEST(PatchCodec, VerticesUsedElsewhereAreStoredExactly)
{
  const atp::QuantizationGrid grid = GridFor(-2, 2);
  atp::PatchMesh mesh = Terrain(-1.5f, 0.25f, 1.0f, 30, false, 5);
  Roughen(mesh, 1e-3f);
  mesh.InputUses.assign(mesh.VertexCount(), 0);
  for (const std::uint32_t v : mesh.Indices)
  {
    ++mesh.InputUses[v];
  }
  mesh.CornerUses.assign(mesh.Indices.size(), 1);
  const std::uint32_t shared = 15 * 31 + 15; // in the middle of the 31 x 31 vertices
  ++mesh.InputUses[shared];
  atp::PatchPrecision coarse;
  coarse.InteriorPositionShift = 9;
  atp::PatchMesh exact, rounded;
  atp::EncodePatch(mesh, grid, {}, &exact);
  atp::EncodePatch(mesh, grid, coarse, &rounded);
  ASSERT_EQ(exact.Positions.size(), rounded.Positions.size());
  // Vertices come out in the same order at both precisions: count those that moved, and find
  // the shared one by its exact position.
  const std::array<std::uint32_t, 3> key = grid.Quantize(&mesh.Positions[3 * shared]);
  std::size_t moved = 0, sharedFound = 0;
  for (std::size_t v = 0; v < exact.VertexCount(); ++v)
  {
    const bool same = std::equal(&exact.Positions[3 * v], &exact.Positions[3 * v + 3], &rounded.Positions[3 * v]);
    moved += !same;
    if (grid.Quantize(&exact.Positions[3 * v]) == key)
    {
      ++sharedFound;
      EXPECT_TRUE(same) << "the shared vertex was rounded to the interior's grid";
    }
  }
  EXPECT_EQ(sharedFound, 1u);
  EXPECT_GT(moved, 100u) << "the interior is stored coarser";
}

/// `mesh` with a disk of `triangles` triangles around one new vertex beside it.
atp::PatchMesh WithFan(atp::PatchMesh mesh, std::uint32_t triangles)
{
  const auto center = std::uint32_t(mesh.VertexCount());
  const auto add = [&mesh](float x, float y) {
    mesh.Positions.insert(mesh.Positions.end(), { x, y, 0.0f });
    mesh.Normals.insert(mesh.Normals.end(), { 0.0f, 0.0f, 1.0f });
  };
  add(3, 0);
  for (std::uint32_t i = 0; i < triangles; ++i)
  {
    const double angle = 2 * 3.141592653589793 * i / triangles;
    add(3 + 0.5f * float(std::cos(angle)), 0.5f * float(std::sin(angle)));
  }
  for (std::uint32_t i = 0; i < triangles; ++i)
  {
    mesh.Indices.insert(mesh.Indices.end(), { center, center + 1 + i, center + 1 + (i + 1) % triangles });
  }
  return mesh;
}

// The best order's time per triangle grows with the valence of the vertices in its cache: a
// triangle repeated thousands of times (which no partition splits) made it quadratic. Above
// the limit a patch takes the fast order, at the limit it keeps the best.
TEST(PatchCodec, VerticesOfGreatValenceTakeTheFastOrder)
{
  const atp::QuantizationGrid grid = GridFor(-2, 4);
  const atp::PatchMesh terrain = Terrain(-1.5f, 0.25f, 1.0f, 12, false, 4);
  const auto encode = [&grid](const atp::PatchMesh& mesh, atp::CacheOrder order) {
    return atp::EncodePatch(mesh, grid, {}, nullptr, order);
  };
  const atp::PatchMesh atLimit = WithFan(terrain, atp::MaxBestOrderValence);
  EXPECT_NE(encode(atLimit, atp::CacheOrder::Best), encode(atLimit, atp::CacheOrder::Fast));
  const atp::PatchMesh overLimit = WithFan(terrain, atp::MaxBestOrderValence + 1);
  EXPECT_EQ(encode(overLimit, atp::CacheOrder::Best), encode(overLimit, atp::CacheOrder::Fast));

  atp::PatchMesh repeated = terrain;
  for (int i = 0; i < 20000; ++i)
  {
    repeated.Indices.insert(repeated.Indices.end(), terrain.Indices.begin(), terrain.Indices.begin() + 3);
  }
  const std::vector<std::uint8_t> bytes = encode(repeated, atp::CacheOrder::Best);
  EXPECT_EQ(bytes, encode(repeated, atp::CacheOrder::Fast));
  atp::PatchMesh back;
  atp::DecodePatch(bytes.data(), bytes.size(), grid, back);
  EXPECT_EQ(back.TriangleCount(), repeated.TriangleCount());
}

TEST(PatchCodec, SmoothSurfacesArePredicted)
{
  // A smooth height field: its grid points follow their parallelograms to within the
  // curvature, so the lossless positions take a fraction of the 26 x 3 bits a point has (the
  // grid's neighbors are 2^16 steps apart here: deltas alone would cost 5 to 6 bytes), and less
  // than the same points with noise.
  const atp::QuantizationGrid grid = GridFor(0, 1);
  atp::PatchMesh mesh = Terrain(0.25f, 0.5f, 0.25f, 40, false, 3);
  const std::vector<std::uint8_t> smooth = atp::EncodePatch(mesh, grid);
  Roughen(mesh, 1e-3f);
  const std::vector<std::uint8_t> rough = atp::EncodePatch(mesh, grid);
  const double smoothPerVertex = double(PositionStreamBytes(smooth)) / double(mesh.VertexCount());
  const double roughPerVertex = double(PositionStreamBytes(rough)) / double(mesh.VertexCount());
  std::printf("positions: %.2f bytes per vertex smooth, %.2f rough\n", smoothPerVertex, roughPerVertex);
  EXPECT_LT(smoothPerVertex, 2.0);
  EXPECT_LT(smoothPerVertex, roughPerVertex);
}

TEST(PatchCodec, CoarserInteriorKeepsTheBorderExactAndShrinks)
{
  atp::PatchMesh mesh = Terrain(0.25f, 0.5f, 0.25f, 40, false, 3);
  Roughen(mesh, 1e-4f); // below the coarse grid's step: rounded away inside
  const atp::QuantizationGrid grid = GridFor(0, 1);
  atp::PatchPrecision coarse;
  coarse.InteriorPositionShift = 12;
  const std::vector<std::uint8_t> exact = atp::EncodePatch(mesh, grid);
  const std::vector<std::uint8_t> bytes = atp::EncodePatch(mesh, grid, coarse);
  // Positions only: normals are predicted from the geometry, which the rounding changes.
  EXPECT_LT(PositionStreamBytes(bytes), PositionStreamBytes(exact) * 9 / 10);
  atp::PatchMesh decoded, lossless;
  atp::DecodePatch(bytes.data(), bytes.size(), grid, decoded);
  atp::DecodePatch(exact.data(), exact.size(), grid, lossless);
  ASSERT_EQ(decoded.Indices, lossless.Indices) << "precision must not change the order";
  // The grid's outer ring of vertices is the patch border: bit-exact. Inside, every vertex is
  // within the stated error, and some really moved.
  std::size_t moved = 0;
  for (std::size_t v = 0; v < decoded.VertexCount(); ++v)
  {
    const float* a = &decoded.Positions[3 * v];
    const float* b = &lossless.Positions[3 * v];
    const double d = std::sqrt(double(a[0] - b[0]) * (a[0] - b[0]) +
      double(a[1] - b[1]) * (a[1] - b[1]) + double(a[2] - b[2]) * (a[2] - b[2]));
    const bool border = b[0] == 0.25f || b[0] == 0.5f || b[1] == 0.5f || b[1] == 0.75f;
    if (border)
    {
      EXPECT_EQ(d, 0.0) << "border vertex " << v;
    }
    EXPECT_LE(d, coarse.PositionError(grid));
    moved += d > 0;
    EXPECT_LE(AngleDegrees(&decoded.Normals[3 * v], &lossless.Normals[3 * v]), 0.1);
  }
  EXPECT_GT(moved, decoded.VertexCount() / 2);
  coarse.InteriorPositionShift = -1;
  EXPECT_THROW(atp::EncodePatch(mesh, grid, coarse), std::invalid_argument);
}

/// The border vertex count a patch's header holds (docs/atp-format.md: bytes 22 to 25).
std::uint32_t BorderCount(const std::vector<std::uint8_t>& bytes)
{
  std::uint32_t count;
  std::memcpy(&count, &bytes[22], sizeof(count));
  return count;
}

TEST(PatchCodec, BorderVerticesAreThoseOfEdgesUsedOnce)
{
  // A rough grid, whose outer ring is its border, with the irregular cases of a real patch
  // inside: a triangle repeated and one reversed (edges used three times, or twice the same
  // way: not border), a degenerate triangle on an interior edge, and a triangle hanging off one
  // interior vertex by that vertex alone (its edges are used once: its corners are border).
  // A triangle on the ring is reversed too: two of the ring's vertices then only have border
  // edges that come in, or only ones that go out.
  const int n = 20;
  atp::PatchMesh mesh = Terrain(0.25f, 0.5f, 0.25f, n, false, 3);
  Roughen(mesh, 1e-4f);
  const auto triangle = [&](int i, int j, int half) { return 3 * std::size_t(2 * (j * n + i) + half); };
  const std::size_t repeated = triangle(5, 5, 0), reversed = triangle(10, 10, 1);
  const std::size_t degenerate = triangle(14, 6, 0), hanging = triangle(4, 15, 0);
  mesh.Indices.insert(mesh.Indices.end(), &mesh.Indices[repeated], &mesh.Indices[repeated] + 3);
  for (const std::size_t t : { reversed, triangle(0, 10, 1) })
  {
    std::swap(mesh.Indices[t + 1], mesh.Indices[t + 2]);
  }
  const std::uint32_t a = mesh.Indices[degenerate], b = mesh.Indices[degenerate + 1];
  mesh.Indices.insert(mesh.Indices.end(), { a, a, b });
  const std::uint32_t hub = mesh.Indices[hanging];
  const std::uint32_t first = std::uint32_t(mesh.VertexCount());
  for (const float dx : { 0.01f, 0.02f })
  {
    const float* p = &mesh.Positions[3 * std::size_t(hub)];
    mesh.Positions.insert(mesh.Positions.end(), { p[0] + dx, p[1] + 0.005f, p[2] + 0.05f });
    mesh.Normals.insert(mesh.Normals.end(), { 0.0f, 0.0f, 1.0f });
  }
  mesh.Indices.insert(mesh.Indices.end(), { hub, first, first + 1 });

  // The rule written down again: a vertex is border when an edge from it to another vertex is
  // used by one triangle in all, whichever way.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (std::size_t t = 0; t < mesh.TriangleCount(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t u = mesh.Indices[3 * t + k], v = mesh.Indices[3 * t + (k + 1) % 3];
      if (u != v)
      {
        ++uses[{ std::min(u, v), std::max(u, v) }];
      }
    }
  }
  std::vector<bool> border(mesh.VertexCount(), false);
  for (const auto& [edge, count] : uses)
  {
    if (count == 1)
    {
      border[edge.first] = border[edge.second] = true;
    }
  }
  const std::size_t expected = std::size_t(std::count(border.begin(), border.end(), true));
  ASSERT_EQ(expected, std::size_t(4 * n + 3)) << "the ring and the hanging triangle";
  ASSERT_FALSE(border[a] || border[b]);

  const atp::QuantizationGrid grid = GridFor(0, 1);
  atp::PatchPrecision coarse;
  coarse.InteriorPositionShift = 12;
  const std::vector<std::uint8_t> bytes = atp::EncodePatch(mesh, grid, coarse);
  EXPECT_EQ(BorderCount(bytes), expected);
  const std::vector<std::uint8_t> exact = atp::EncodePatch(mesh, grid);
  atp::PatchMesh decoded, lossless;
  atp::DecodePatch(bytes.data(), bytes.size(), grid, decoded);
  atp::DecodePatch(exact.data(), exact.size(), grid, lossless);
  ASSERT_EQ(decoded.Indices, lossless.Indices);
  // Each decoded vertex is the input vertex nearest its lossless position: border ones keep
  // their position exactly on the coarser grid, the others all move.
  for (std::size_t v = 0; v < lossless.VertexCount(); ++v)
  {
    const float* p = &lossless.Positions[3 * v];
    std::size_t input = 0;
    double nearest = INFINITY;
    for (std::size_t w = 0; w < mesh.VertexCount(); ++w)
    {
      const float* q = &mesh.Positions[3 * w];
      const double d = std::hypot(double(p[0] - q[0]), double(p[1] - q[1]), double(p[2] - q[2]));
      if (d < nearest)
      {
        nearest = d;
        input = w;
      }
    }
    const bool same = std::equal(p, p + 3, &decoded.Positions[3 * v]);
    EXPECT_EQ(same, bool(border[input])) << "vertex " << input;
  }
}

TEST(PatchCodec, EmptyPatch)
{
  const atp::QuantizationGrid grid = GridFor(0, 1);
  atp::PatchMesh empty;
  const std::vector<std::uint8_t> bytes = atp::EncodePatch(empty, grid);
  EXPECT_EQ(bytes.size(), atp::PatchHeaderBytes);
  atp::PatchMesh decoded = Terrain(0, 0, 1, 2, true, 4); // stale contents must go
  atp::DecodePatch(bytes.data(), bytes.size(), grid, decoded);
  EXPECT_EQ(decoded.VertexCount(), 0u);
  EXPECT_EQ(decoded.TriangleCount(), 0u);
  EXPECT_FALSE(decoded.HasColors());
  ExpectValid(decoded);
}

TEST(PatchCodec, DecodeReusesCapacity)
{
  const atp::QuantizationGrid grid = GridFor(-2, 2);
  const std::vector<std::uint8_t> big = atp::EncodePatch(Terrain(0, 0, 1, 30, false, 5), grid);
  const std::vector<std::uint8_t> small = atp::EncodePatch(Terrain(0, 0, 1, 10, false, 6), grid);
  atp::PatchMesh out;
  atp::DecodePatch(big.data(), big.size(), grid, out);
  const float* positions = out.Positions.data();
  const std::uint32_t* indices = out.Indices.data();
  atp::DecodePatch(small.data(), small.size(), grid, out);
  EXPECT_EQ(out.Positions.data(), positions);
  EXPECT_EQ(out.Indices.data(), indices);
  ExpectValid(out);
}

TEST(PatchCodec, InconsistentMeshIsRejected)
{
  const atp::QuantizationGrid grid = GridFor(0, 1);
  atp::PatchMesh mesh = Terrain(0, 0, 1, 2, false, 8);
  mesh.Indices.back() = 1000;
  EXPECT_THROW(atp::EncodePatch(mesh, grid), std::invalid_argument);
  mesh = Terrain(0, 0, 1, 2, false, 8);
  mesh.Normals.pop_back();
  EXPECT_THROW(atp::EncodePatch(mesh, grid), std::invalid_argument);
}

void PutU32(std::vector<std::uint8_t>& bytes, std::size_t at, std::uint32_t v)
{
  for (int i = 0; i < 4; ++i)
  {
    bytes[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
  }
}

TEST(PatchCodec, AbsurdCountsAreRejectedBeforeAllocating)
{
  const atp::QuantizationGrid grid = GridFor(-2, 2);
  const std::vector<std::uint8_t> valid = atp::EncodePatch(Terrain(0, 0, 1, 20, false, 9), grid);
  atp::PatchMesh out;
  for (const std::uint32_t vertices : { 1u << 31, atp::MaxPatchVertices, 1u << 20 })
  {
    std::vector<std::uint8_t> bytes = valid;
    PutU32(bytes, 2, vertices); // vertex count
    EXPECT_THROW(atp::DecodePatch(bytes.data(), bytes.size(), grid, out), atp::PatchFormatError);
    EXPECT_EQ(out.Positions.capacity(), 0u);
  }
  for (const std::uint32_t triangles : { 1u << 31, atp::MaxPatchTriangles, 1u << 20 })
  {
    std::vector<std::uint8_t> bytes = valid;
    PutU32(bytes, 6, triangles); // triangle count
    EXPECT_THROW(atp::DecodePatch(bytes.data(), bytes.size(), grid, out), atp::PatchFormatError);
    EXPECT_EQ(out.Indices.capacity(), 0u);
  }
  try
  {
    std::vector<std::uint8_t> bytes = valid;
    PutU32(bytes, 2, 1u << 31);
    atp::DecodePatch(bytes.data(), bytes.size(), grid, out);
  }
  catch (const atp::PatchFormatError& e)
  {
    EXPECT_NE(std::string(e.what()).find("2147483648 vertices"), std::string::npos) << e.what();
  }
}

// A normal stream whose records are all alike: after the byte-lane differences every vertex but
// the first has residual 0, and the first has the residual `first` on its x coordinate.
std::vector<std::uint8_t> NormalStreamWithFirstResidual(std::size_t vertices, std::int32_t first)
{
  const std::uint16_t zigzag = std::uint16_t(first < 0 ? -2 * first - 1 : 2 * first);
  // Each stored byte is the running sum of the un-zigzagged residual bytes.
  const auto unzigzag8 = [](std::uint8_t z) { return std::uint8_t((z >> 1) ^ (0u - (z & 1u))); };
  const std::uint8_t record[4] = { unzigzag8(std::uint8_t(zigzag)), unzigzag8(std::uint8_t(zigzag >> 8)), 0, 0 };
  std::vector<std::uint8_t> records;
  for (std::size_t v = 0; v < vertices; ++v)
  {
    records.insert(records.end(), record, record + 4);
  }
  std::vector<std::uint8_t> stream(meshopt_encodeVertexBufferBound(vertices, 4));
  stream.resize(meshopt_encodeVertexBuffer(stream.data(), stream.size(), records.data(), vertices, 4));
  return stream;
}

/// `patch` (without colors) with its normal stream replaced by `stream`.
std::vector<std::uint8_t> WithNormalStream(
  const std::vector<std::uint8_t>& patch, const std::vector<std::uint8_t>& stream)
{
  std::uint32_t sizes[4];
  std::memcpy(sizes, &patch[atp::PatchHeaderBytes - 16], sizeof(sizes));
  const std::size_t normalsStart = atp::PatchHeaderBytes + sizes[0] + sizes[1];
  std::vector<std::uint8_t> bytes(patch.begin(), patch.begin() + normalsStart);
  bytes.insert(bytes.end(), stream.begin(), stream.end());
  PutU32(bytes, atp::PatchHeaderBytes - 8, std::uint32_t(stream.size()));
  return bytes;
}

// Normals are stored as residuals of their prediction from the decoded geometry; a residual
// that lands outside the octahedral square is corruption, reported, not clamped into a normal.
TEST(PatchCodec, NormalOutsideTheOctahedralSquareIsRejected)
{
  const atp::QuantizationGrid grid = GridFor(-2, 2);
  const atp::PatchMesh mesh = Terrain(0, 0, 1, 12, false, 4);
  const std::vector<std::uint8_t> valid = atp::EncodePatch(mesh, grid);
  const std::size_t vertices = mesh.VertexCount();
  atp::PatchMesh out;
  // Within the square whatever the prediction (|prediction| <= 1024): decodes.
  for (const std::int32_t residual : { 0, 1, -1 })
  {
    const std::vector<std::uint8_t> bytes =
      WithNormalStream(valid, NormalStreamWithFirstResidual(vertices, residual));
    EXPECT_NO_THROW(atp::DecodePatch(bytes.data(), bytes.size(), grid, out)) << residual;
  }
  for (const std::int32_t residual : { 2049, -2049, 20000, -30000 })
  {
    const std::vector<std::uint8_t> bytes =
      WithNormalStream(valid, NormalStreamWithFirstResidual(vertices, residual));
    try
    {
      atp::DecodePatch(bytes.data(), bytes.size(), grid, out);
      ADD_FAILURE() << "residual " << residual << " accepted";
    }
    catch (const atp::PatchFormatError& e)
    {
      EXPECT_NE(std::string(e.what()).find("octahedral square"), std::string::npos) << e.what();
    }
  }
}

// Normals that follow the surface cost a fraction of their 22 bits: the decoder predicts them
// from the positions. The same normals shuffled among the vertices cost far more.
TEST(PatchCodec, NormalsOfTheSurfaceArePredicted)
{
  const atp::QuantizationGrid grid = GridFor(0, 1);
  atp::PatchMesh mesh = Terrain(0.25f, 0.5f, 0.25f, 40, false, 3);
  const std::vector<std::uint8_t> surface = atp::EncodePatch(mesh, grid);
  std::mt19937 random(8);
  for (std::size_t v = mesh.VertexCount() - 1; v > 0; --v)
  {
    const std::size_t other = random() % (v + 1);
    std::swap_ranges(&mesh.Normals[3 * v], &mesh.Normals[3 * v + 3], &mesh.Normals[3 * other]);
  }
  const std::vector<std::uint8_t> shuffled = atp::EncodePatch(mesh, grid);
  const double surfacePerVertex = double(NormalStreamBytes(surface)) / double(mesh.VertexCount());
  const double shuffledPerVertex = double(NormalStreamBytes(shuffled)) / double(mesh.VertexCount());
  std::printf("normals: %.2f bytes per vertex on the surface, %.2f shuffled\n", surfacePerVertex,
    shuffledPerVertex);
  EXPECT_LT(surfacePerVertex, 1.0);
  EXPECT_LT(surfacePerVertex * 2, shuffledPerVertex);
}

TEST(PatchCodec, HostileBytesThrowOrDecodeValid)
{
  const atp::QuantizationGrid grid = GridFor(-2, 2);
  const std::vector<std::uint8_t> valid = atp::EncodePatch(Terrain(-1, -1, 2, 24, true, 10), grid);
  std::mt19937 random(12345);
  atp::PatchMesh out;
  int rejected = 0;
  int decoded = 0;
  auto attempt = [&](const std::vector<std::uint8_t>& bytes)
  {
    try
    {
      atp::DecodePatch(bytes.data(), bytes.size(), grid, out);
      ++decoded;
      ExpectValid(out);
    }
    catch (const atp::PatchFormatError&)
    {
      ++rejected;
    }
  };
  for (int iteration = 0; iteration < 20000; ++iteration)
  {
    std::vector<std::uint8_t> bytes = valid;
    switch (iteration % 5)
    {
      case 0: // a few random bit flips anywhere
        for (int k = 1 + random() % 4; k > 0; --k)
        {
          bytes[random() % bytes.size()] ^= std::uint8_t(1u << (random() % 8));
        }
        break;
      case 1: // random bytes in the streams, header intact: exercises meshopt's decoders
        for (int k = 1 + random() % 16; k > 0; --k)
        {
          bytes[atp::PatchHeaderBytes + random() % (bytes.size() - atp::PatchHeaderBytes)] =
            std::uint8_t(random());
        }
        break;
      case 2: // truncated, or extended with garbage
        bytes.resize(random() % (bytes.size() + 64), std::uint8_t(random()));
        break;
      case 3: // one header field replaced
        PutU32(bytes, 2 + 4 * (random() % 9), std::uint32_t(random()) >> (random() % 32));
        break;
      default: // garbage behind a plausible header
        for (std::size_t k = atp::PatchHeaderBytes; k < bytes.size(); ++k)
        {
          bytes[k] = std::uint8_t(random());
        }
        break;
    }
    attempt(bytes);
    if (HasFatalFailure())
    {
      return;
    }
  }
  for (int iteration = 0; iteration < 2000; ++iteration) // pure garbage, including tiny sizes
  {
    std::vector<std::uint8_t> bytes(random() % 200);
    for (std::uint8_t& b : bytes)
    {
      b = std::uint8_t(random());
    }
    attempt(bytes);
  }
  attempt({});
  EXPECT_GT(rejected, 0);
  EXPECT_GT(decoded, 0); // stream bytes changed without breaking the codec: garbage, but valid
  std::printf("hostile inputs: %d rejected, %d decoded to valid patches\n", rejected, decoded);
}

} // namespace
