// The scratch store of full-precision patches: what the parent diamond reads back is exactly
// what was put, in a record much smaller than the mesh in memory.
#include "atpNormalEncoding.h"
#include "atpPatchStore.h"

#include "FileTestFixture.h"

#include <cmath>
#include <random>

namespace
{

/// A patch whose normals, like every normal construction holds, were decoded from
/// EncodeNormal's 2 x int16; random connectivity is enough for a store.
atp::PatchMesh RandomPatch(std::size_t vertices, std::size_t triangles, bool colors, unsigned seed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> coordinate(-1000, 1000);
  std::uniform_int_distribution<int> octahedral(-32767, 32767);
  std::uniform_int_distribution<std::uint32_t> vertex(0, std::uint32_t(vertices - 1));
  atp::PatchMesh patch;
  for (std::size_t v = 0; v < vertices; ++v)
  {
    for (int a = 0; a < 3; ++a)
    {
      patch.Positions.push_back(coordinate(random));
    }
    const std::int16_t encoded[2] = { std::int16_t(octahedral(random)), std::int16_t(octahedral(random)) };
    float n[3];
    atp::DecodeNormal(encoded, n);
    patch.Normals.insert(patch.Normals.end(), n, n + 3);
    for (int c = 0; colors && c < 4; ++c)
    {
      patch.Colors.push_back(std::uint8_t(random()));
    }
  }
  for (std::size_t t = 0; t < triangles; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      patch.Indices.push_back(vertex(random));
    }
    patch.BoundaryEdges.push_back(std::uint8_t(random() % 8));
  }
  return patch;
}

void ExpectSame(const atp::PatchMesh& a, const atp::PatchMesh& b)
{
  EXPECT_EQ(a.Positions, b.Positions);
  EXPECT_EQ(a.Normals, b.Normals); // bit-exact floats
  EXPECT_EQ(a.Colors, b.Colors);
  EXPECT_EQ(a.Indices, b.Indices);
  EXPECT_EQ(a.BoundaryEdges, b.BoundaryEdges);
}

class PatchStore : public FileTestFixture
{
};

} // namespace

TEST_F(PatchStore, PatchesComeBackBitExact)
{
  atp::PatchStore store(Dir.string());
  // 16-bit indices, a patch just at their limit, 32-bit indices, colors, an empty patch.
  const std::vector<atp::PatchMesh> patches = { RandomPatch(300, 500, false, 1),
    RandomPatch(65536, 2000, false, 2), RandomPatch(70000, 3000, true, 3), atp::PatchMesh(),
    RandomPatch(10, 4, true, 4) };
  std::vector<atp::PatchStore::Handle> handles;
  for (const atp::PatchMesh& p : patches)
  {
    handles.push_back(store.Put(p));
  }
  for (std::size_t i = patches.size(); i-- > 0;)
  {
    atp::PatchMesh back = RandomPatch(5, 5, true, 9); // stale contents must go
    store.Get(handles[i], back);
    ExpectSame(back, patches[i]);
  }
}

TEST_F(PatchStore, RecordIsCompact)
{
  atp::PatchStore store(Dir.string());
  const atp::PatchMesh patch = RandomPatch(1000, 2000, false, 5);
  const atp::PatchStore::Handle handle = store.Put(patch);
  // Per vertex 12 bytes of position and 4 of normal; per triangle 3 x 2 bytes of index and one
  // of boundary bits (the mesh in memory takes 24 and 13).
  EXPECT_LE(handle.Bytes, 16 + 1000 * 16 + 2000 * 7u);
  EXPECT_EQ(store.PeakBytes(), handle.Bytes);
  store.Release(handle);
  const atp::PatchStore::Handle second = store.Put(patch);
  EXPECT_EQ(store.PeakBytes(), second.Bytes) << "released bytes count no more";
  EXPECT_EQ(store.BytesWritten(), 2 * handle.Bytes);
}

// Construction gives a whole level back at once: a handle spanning consecutive patches.
TEST_F(PatchStore, ARangeOfPatchesIsReleasedAtOnce)
{
  atp::PatchStore store(Dir.string());
  const atp::PatchMesh patch = RandomPatch(100, 150, true, 6);
  const std::uint64_t start = store.BytesWritten();
  for (int i = 0; i < 3; ++i)
  {
    store.Put(patch);
  }
  const std::uint64_t level = store.BytesWritten() - start;
  EXPECT_EQ(store.PeakBytes(), level);
  store.Release({ start, level });
  const atp::PatchStore::Handle next = store.Put(patch);
  EXPECT_EQ(store.PeakBytes(), level) << "the released range no longer counts";
  atp::PatchMesh back;
  store.Get(next, back);
  ExpectSame(back, patch);
}
