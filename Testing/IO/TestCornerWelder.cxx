// CornerWelder: the same vertices, in the same order (first appearance), as welding in memory
// by exact position, -0 as +0, over many buckets and several gathering ranges.
#include "atpCornerWelder.h"
#include "atpPositionWelder.h"

#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <unordered_map>
#include <random>
#include <vector>

namespace
{
std::string Scratch()
{
  return std::filesystem::temp_directory_path().string();
}

using Key = std::array<std::uint32_t, 3>;
struct KeyHash
{
  std::size_t operator()(const Key& k) const { return (k[0] * 31u + k[1]) * 31u + k[2]; }
};

Key KeyOf(const float p[3])
{
  Key key;
  atp::PositionBits(p, key.data());
  return key;
}

/// Welds `corners` (3 floats each) both ways and compares.
void ExpectWeldedAsInMemory(const std::vector<float>& corners, std::uint64_t expectedCorners)
{
  atp::CornerWelder welder(Scratch(), expectedCorners);
  std::unordered_map<Key, std::uint32_t, KeyHash> index;
  std::vector<std::uint32_t> indices;
  std::vector<float> positions;
  for (std::size_t c = 0; c < corners.size() / 3; ++c)
  {
    const float* p = &corners[3 * c];
    welder.Add(p);
    const auto [it, added] = index.emplace(KeyOf(p), std::uint32_t(index.size()));
    if (added)
    {
      positions.insert(positions.end(), p, p + 3);
    }
    indices.push_back(it->second);
  }
  EXPECT_EQ(welder.Corners(), indices.size());
  const atp::CornerWelder::Mesh mesh = welder.Finish();
  ASSERT_EQ(mesh.VertexCount, index.size());
  ASSERT_EQ(mesh.Indices.Size(), indices.size());
  ASSERT_EQ(mesh.Positions.Size(), positions.size());
  for (std::size_t c = 0; c < indices.size(); ++c)
  {
    ASSERT_EQ(mesh.Indices[c], indices[c]) << "corner " << c;
  }
  for (std::size_t i = 0; i < positions.size(); ++i)
  {
    // +0 where the first corner at a zero position said -0: positions are compared as keys.
    ASSERT_EQ(positions[i] + 0.0f, mesh.Positions[i] + 0.0f) << "coordinate " << i;
  }
}
} // namespace

TEST(CornerWelder, NumbersPositionsInOrderOfFirstAppearance)
{
  // A strip of quads as a soup: each inner vertex met in six corners.
  std::vector<float> corners;
  const auto corner = [&](float x, float y) { corners.insert(corners.end(), { x, y, 0.0f }); };
  for (int i = 0; i < 50; ++i)
  {
    const float x = float(i);
    corner(x, 0), corner(x + 1, 0), corner(x + 1, 1);
    corner(x, 0), corner(x + 1, 1), corner(x, 1);
  }
  ExpectWeldedAsInMemory(corners, corners.size() / 3);
}

TEST(CornerWelder, NegativeZeroIsZero)
{
  const std::vector<float> corners = { -0.0f, 0, 1, 0, -0.0f, 1, 0, 0, 1, 0, 0, -0.0f, 0, 0, 0 };
  atp::CornerWelder welder(Scratch(), 5);
  for (std::size_t c = 0; c < corners.size() / 3; ++c)
  {
    welder.Add(&corners[3 * c]);
  }
  const atp::CornerWelder::Mesh mesh = welder.Finish();
  EXPECT_EQ(mesh.VertexCount, 2u);
  const std::uint32_t expected[5] = { 0, 0, 0, 1, 1 };
  for (int c = 0; c < 5; ++c)
  {
    EXPECT_EQ(mesh.Indices[std::size_t(c)], expected[c]);
  }
}

TEST(CornerWelder, ManyBucketsAndRanges)
{
  // 5M corners (two gathering ranges of 2^22) drawn from 300k positions, spread over 256
  // buckets by a large guess of the corner count; some positions recur millions of corners later.
  std::mt19937 random(7);
  std::uniform_int_distribution<int> pick(0, 299999);
  std::vector<float> corners;
  corners.reserve(3 * 5000000);
  for (int c = 0; c < 5000000; ++c)
  {
    const int p = pick(random);
    corners.insert(corners.end(), { float(p % 97) - 48, float(p / 97 % 61), float(p / 5917) });
  }
  ExpectWeldedAsInMemory(corners, std::uint64_t(1) << 28);
}

TEST(CornerWelder, NothingAddedIsAnEmptyMesh)
{
  atp::CornerWelder welder(Scratch(), 0);
  const atp::CornerWelder::Mesh mesh = welder.Finish();
  EXPECT_EQ(mesh.VertexCount, 0u);
  EXPECT_EQ(mesh.Indices.Size(), 0u);
}
