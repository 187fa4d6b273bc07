// Normal prediction from a patch's own geometry: integer octahedral coordinates that agree with
// the stored encoding, area-weighted sums that reproduce construction's normals, and sums that
// overflow 64 bits still giving a valid prediction without undefined behaviour.
#include "atpNormalEncoding.h"
#include "atpNormalPrediction.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace
{
constexpr std::int32_t Scale = 1024; // the patch codec's 11-bit normals

/// What the patch codec stores for a float normal (docs/atp-format.md): EncodeNormal's
/// coordinates divided by 32, rounded half away from zero.
std::array<int, 2> Stored(const float normal[3])
{
  std::int16_t octahedral[2];
  atp::EncodeNormal(normal, octahedral);
  std::array<int, 2> stored;
  for (int k = 0; k < 2; ++k)
  {
    const int magnitude = (std::abs(int(octahedral[k])) + 16) >> 5;
    stored[k] = octahedral[k] < 0 ? -magnitude : magnitude;
  }
  return stored;
}
} // namespace

TEST(NormalPrediction, OctahedralCoordinatesAgreeWithTheStoredEncoding)
{
  std::mt19937_64 random(7);
  for (int i = 0; i < 200000; ++i)
  {
    // Components of every magnitude up to 2^62, either sign, some zero.
    const int bits = 1 + int(random() % 62);
    std::int64_t direction[3];
    for (std::int64_t& d : direction)
    {
      d = random() % 7 == 0 ? 0 : std::int64_t(random() >> (64 - bits)) * (random() % 2 ? 1 : -1);
    }
    std::int32_t predicted[2];
    atp::OctahedralOfDirection(direction, Scale, predicted);
    const float normal[3] = { float(direction[0]), float(direction[1]), float(direction[2]) };
    const std::array<int, 2> stored = Stored(normal);
    for (int k = 0; k < 2; ++k)
    {
      ASSERT_LE(std::abs(predicted[k] - stored[k]), 1)
        << direction[0] << " " << direction[1] << " " << direction[2] << " coordinate " << k;
      ASSERT_LE(std::abs(predicted[k]), Scale); // inside the octahedral square
    }
  }
  const std::int64_t zero[3] = { 0, 0, 0 };
  std::int32_t out[2] = { 5, 5 };
  atp::OctahedralOfDirection(zero, Scale, out);
  EXPECT_EQ(out[0], 0);
  EXPECT_EQ(out[1], 0);
  // The extremes of 64 bits: no overflow (the sanitizer builds check), a valid coordinate.
  const std::int64_t extreme[3] = { std::numeric_limits<std::int64_t>::min(),
    std::numeric_limits<std::int64_t>::max(), std::numeric_limits<std::int64_t>::min() };
  atp::OctahedralOfDirection(extreme, Scale, out);
  EXPECT_LE(std::abs(out[0]), Scale);
  EXPECT_LE(std::abs(out[1]), Scale);
  // Scales past 2^10 would overflow the 32-bit rounding: refused.
  for (const std::int32_t scale : { 0, -1, atp::MaxOctahedralScale + 1 })
  {
    EXPECT_THROW(atp::OctahedralOfDirection(extreme, scale, out), std::invalid_argument);
    EXPECT_THROW(atp::PredictNormals({}, nullptr, 0, scale, out), std::invalid_argument);
  }
}

// Construction gives each vertex the area-weighted sum of its faces' normals: on the same
// triangles, the prediction is that normal to within a unit of the stored coordinates.
TEST(NormalPrediction, PredictsAreaWeightedNormalsOfTheSameTriangles)
{
  // A bumpy closed surface (a torus) on a grid of 2^20 steps per unit.
  const int around = 48, across = 24;
  std::vector<std::int64_t> points;
  for (int i = 0; i < around; ++i)
  {
    for (int j = 0; j < across; ++j)
    {
      const double u = 2 * M_PI * i / around, v = 2 * M_PI * j / across;
      const double r = 0.3 + 0.02 * std::sin(5 * u + 3 * v);
      const double p[3] = { (1 + r * std::cos(v)) * std::cos(u), (1 + r * std::cos(v)) * std::sin(u),
        r * std::sin(v) };
      for (const double c : p)
      {
        points.push_back(std::llround((c + 2) * (1 << 20)));
      }
    }
  }
  std::vector<std::uint32_t> indices;
  const auto at = [&](int i, int j) { return std::uint32_t((i % around) * across + j % across); };
  for (int i = 0; i < around; ++i)
  {
    for (int j = 0; j < across; ++j)
    {
      for (const std::uint32_t v : { at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1) })
      {
        indices.push_back(v);
      }
    }
  }
  const std::size_t vertices = points.size() / 3;
  std::vector<double> sums(3 * vertices, 0);
  for (std::size_t t = 0; t < indices.size(); t += 3)
  {
    const std::int64_t* a = &points[3 * indices[t]];
    const std::int64_t* b = &points[3 * indices[t + 1]];
    const std::int64_t* c = &points[3 * indices[t + 2]];
    const double u[3] = { double(b[0] - a[0]), double(b[1] - a[1]), double(b[2] - a[2]) };
    const double w[3] = { double(c[0] - a[0]), double(c[1] - a[1]), double(c[2] - a[2]) };
    const double n[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0] };
    for (int k = 0; k < 3; ++k)
    {
      for (int x = 0; x < 3; ++x)
      {
        sums[3 * indices[t + k] + x] += n[x];
      }
    }
  }
  std::vector<std::int32_t> predicted(2 * vertices);
  atp::PredictNormals(indices, points.data(), vertices, Scale, predicted.data());
  for (std::size_t v = 0; v < vertices; ++v)
  {
    const float normal[3] = { float(sums[3 * v]), float(sums[3 * v + 1]), float(sums[3 * v + 2]) };
    const std::array<int, 2> stored = Stored(normal);
    for (int k = 0; k < 2; ++k)
    {
      ASSERT_LE(std::abs(predicted[2 * v + k] - stored[k]), 1) << "vertex " << v;
    }
  }
}

// Sums past 64 bits (one big triangle on the full grid, used 20,000 times: 2^66) wrap around:
// the same on every run and every platform, coordinates inside the octahedral square, and no
// undefined behaviour.
TEST(NormalPrediction, OverflowingSumsWrapDeterministically)
{
  const std::int64_t top = (std::int64_t(1) << 26) - 1;
  const std::vector<std::int64_t> points = { 0, 0, 0, top, 0, top / 3, 0, top, top / 5 };
  std::vector<std::uint32_t> indices;
  for (int i = 0; i < 20000; ++i)
  {
    indices.insert(indices.end(), { 0u, 1u, 2u });
  }
  std::int32_t first[6], second[6], once[6];
  atp::PredictNormals(indices, points.data(), 3, Scale, first);
  atp::PredictNormals(indices, points.data(), 3, Scale, second);
  atp::PredictNormals({ 0u, 1u, 2u }, points.data(), 3, Scale, once);
  EXPECT_TRUE(std::equal(first, first + 6, second));
  EXPECT_FALSE(std::equal(first, first + 6, once)) << "the sums did not wrap";
  for (const std::int32_t coordinate : first)
  {
    EXPECT_LE(std::abs(coordinate), Scale);
  }
}
