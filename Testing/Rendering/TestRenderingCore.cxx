// The renderer's plain C++ parts, without a GPU: the cache policy, background decoding and
// speculative prefetching. Run under ThreadSanitizer too (ATP_SANITIZE=thread).
#include "TestModel.h"

#include "atpBufferArena.h"
#include "atpCut.h"
#include "atpModelFile.h"
#include "atpPatchCache.h"
#include "atpPatchFetcher.h"
#include "atpPrefetcher.h"
#include "atpRenderPatch.h"

#include "vtkNew.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <set>
#include <thread>
#include <unistd.h>

namespace
{
using namespace atp::test;

TEST(PatchCache, EvictsLeastRecentlyUsedButNeverThisFramesPatches)
{
  std::vector<int> released;
  atp::PatchCache<int> cache([&](int& v) { released.push_back(v); });
  const auto fits = [] { return true; }; // storage that never fragments: the budget decides
  cache.SetBudget(300);
  for (std::uint32_t key = 0; key < 3; ++key)
  {
    ASSERT_TRUE(cache.MakeRoom(100, fits));
    cache.Insert(key, int(key), 100);
  }
  // Full, and everything is pinned by this frame: no room.
  EXPECT_FALSE(cache.MakeRoom(100, fits));
  EXPECT_TRUE(released.empty());
  cache.NewFrame();
  cache.Use(0); // 1 is now the least recently used
  ASSERT_TRUE(cache.MakeRoom(100, fits));
  cache.Insert(3, 3, 100);
  EXPECT_EQ(released, std::vector<int>{ 1 });
  EXPECT_FALSE(cache.Contains(1));
  EXPECT_TRUE(cache.Contains(0) && cache.Contains(2) && cache.Contains(3));
  EXPECT_EQ(cache.GetBytes(), 300u);
  EXPECT_EQ(cache.GetEvictions(), 1u);
  // A value larger than the budget never fits, and evicts nothing trying.
  cache.NewFrame();
  EXPECT_FALSE(cache.MakeRoom(400, fits));
  EXPECT_EQ(cache.GetCount(), 3u);
  cache.Clear();
  EXPECT_EQ(released.size(), 4u);
  EXPECT_EQ(cache.GetBytes(), 0u);
}

TEST(PatchCache, EvictsUntilFragmentedStorageHasARange)
{
  // Values are ranges of an arena of 4 slots of 100 bytes: after 1 and 3 leave, 200 bytes are
  // free but not in one piece, so a value of 200 evicts on until two neighbours are free.
  atp::BufferArena arena(100);
  arena.Reset(400);
  atp::PatchCache<std::size_t> cache([&](std::size_t& offset) { arena.Free(offset, 100); });
  cache.SetBudget(400);
  for (std::uint32_t key = 0; key < 4; ++key)
  {
    std::optional<std::size_t> offset;
    ASSERT_TRUE(cache.MakeRoom(100, [&] { return (offset = arena.Allocate(100)).has_value(); }));
    cache.Insert(key, *offset, 100);
  }
  EXPECT_EQ(arena.GetUsedBytes(), 400u);
  cache.NewFrame();
  cache.Use(3);
  cache.Use(0);
  cache.Use(2); // least recently used first: 1, then 3, then 0, then 2 (pinned: 3, 0, 2)
  cache.NewFrame();
  cache.Use(0);
  cache.Use(2); // pinned now: 0 and 2; 1 and 3 may go, and freeing both leaves two holes
  std::optional<std::size_t> offset;
  EXPECT_FALSE(cache.MakeRoom(200, [&] { return (offset = arena.Allocate(200)).has_value(); }));
  EXPECT_EQ(cache.GetEvictions(), 2u);
  EXPECT_EQ(arena.GetUsedBytes(), 200u);
  cache.NewFrame(); // nothing pinned: 0 goes next (older than 2), joining two holes
  ASSERT_TRUE(cache.MakeRoom(200, [&] { return (offset = arena.Allocate(200)).has_value(); }));
  EXPECT_EQ(*offset, 0u);
  EXPECT_EQ(cache.GetEvictions(), 3u);
  EXPECT_TRUE(cache.Contains(2));
}

TEST(BufferArena, BestFitAlignedRangesThatJoinWhenFreed)
{
  atp::BufferArena arena(24);
  EXPECT_FALSE(arena.Allocate(1).has_value()); // no buffer yet
  arena.Reset(240);
  EXPECT_EQ(arena.GetCapacity(), 240u);
  const std::size_t a = *arena.Allocate(30); // rounded up to 48
  const std::size_t b = *arena.Allocate(24);
  const std::size_t c = *arena.Allocate(48);
  EXPECT_EQ(a, 0u);
  EXPECT_EQ(b, 48u);
  EXPECT_EQ(c, 72u);
  EXPECT_EQ(arena.GetUsedBytes(), 120u);
  for (const std::size_t offset : { a, b, c })
  {
    EXPECT_EQ(offset % 24, 0u);
  }
  arena.Free(a, 30);
  // Free: [0, 48) and [120, 240). A 48-byte range takes the hole that fits it exactly.
  EXPECT_EQ(*arena.Allocate(40), 0u);
  EXPECT_EQ(*arena.Allocate(24), 120u);
  EXPECT_FALSE(arena.Allocate(120).has_value()); // 96 bytes are left in one range
  // Freeing the middle joins it with both neighbours into one range.
  arena.Free(b, 24);
  arena.Free(c, 48);
  arena.Free(0, 40);
  arena.Free(120, 24);
  EXPECT_EQ(arena.GetUsedBytes(), 0u);
  EXPECT_EQ(*arena.Allocate(240), 0u);
  arena.Free(0, 240);
  // Growing frees the new end, joined with a free range that reached the old end.
  arena.Allocate(24);
  arena.Grow(480);
  EXPECT_EQ(arena.GetCapacity(), 480u);
  EXPECT_EQ(*arena.Allocate(456), 24u);
}

TEST(RenderPatch, LayoutMatchesTheDecodedPatch)
{
  const atp::ModelFile model = atp::ModelFile::Open(TorusModel());
  atp::PatchMesh mesh;
  model.DecodePatch(0, mesh);
  const atp::RenderPatch patch = atp::MakeRenderPatch(mesh, 0);
  ASSERT_EQ(patch.VertexCount, mesh.VertexCount());
  ASSERT_EQ(patch.TriangleCount, mesh.TriangleCount());
  EXPECT_TRUE(patch.ShortIndices);
  for (std::size_t v = 0; v < patch.VertexCount; v += 7)
  {
    float position[3];
    std::int16_t normal[4];
    std::memcpy(position, &patch.Vertices[patch.Stride() * v + atp::RenderPatchPositionOffset], 12);
    std::memcpy(normal, &patch.Vertices[patch.Stride() * v + atp::RenderPatchNormalOffset], 8);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_EQ(position[a], mesh.Positions[3 * v + a]);
      EXPECT_NEAR(normal[a] / 32767.0, mesh.Normals[3 * v + a], 1e-4);
    }
  }
  std::vector<std::uint16_t> indices(patch.Indices.size() / 2);
  std::memcpy(indices.data(), patch.Indices.data(), patch.Indices.size());
  EXPECT_TRUE(std::equal(indices.begin(), indices.end(), mesh.Indices.begin()));
}

TEST(PatchFetcher, DecodesWhatIsAskedOnceAndReportsCorruption)
{
  auto model = std::make_shared<const atp::ModelFile>(atp::ModelFile::Open(TorusModel()));
  atp::PatchFetcher fetcher(model, 3);
  std::vector<std::uint32_t> all(model->NodeCount());
  for (std::uint32_t n = 0; n < all.size(); ++n)
  {
    all[n] = n;
  }
  std::set<std::uint32_t> got;
  std::vector<atp::RenderPatch> finished;
  // Ask again and again while taking (as frames do): every patch arrives exactly once.
  for (int frame = 0; got.size() < all.size() && frame < 100000; ++frame)
  {
    std::vector<std::uint32_t> wanted;
    for (const std::uint32_t n : all)
    {
      if (!got.count(n))
      {
        wanted.push_back(n);
      }
    }
    fetcher.Request(wanted);
    finished.clear();
    fetcher.TakeFinished(1 << 20, finished);
    for (const atp::RenderPatch& p : finished)
    {
      EXPECT_TRUE(p.Error.empty()) << p.Error;
      EXPECT_TRUE(got.insert(p.Node).second) << "node " << p.Node << " decoded twice";
      EXPECT_EQ(p.TriangleCount, model->Node(p.Node).TriangleCount);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  EXPECT_EQ(got.size(), all.size());
  EXPECT_GE(fetcher.DecodedPatches(), all.size());

  // A corrupt patch comes back with an error naming it.
  std::ifstream in(TorusModel(), std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t offset = model->Header().PatchSectionOffset + model->Node(7).PatchOffset + 20;
  bytes[offset] = char(bytes[offset] ^ 0x33);
  std::ofstream(TempPath("corrupt.atp"), std::ios::binary) << bytes;
  auto corrupt = std::make_shared<const atp::ModelFile>(atp::ModelFile::Open(TempPath("corrupt.atp")));
  atp::PatchFetcher broken(corrupt, 1);
  EXPECT_NE(broken.DecodeNow(7).Error.find("node 7"), std::string::npos);
  EXPECT_TRUE(broken.DecodeNow(6).Error.empty());
  ::unlink(TempPath("corrupt.atp").c_str());
}

TEST(Prefetcher, PredictsHalfASecondAheadAndAdvisesMissingPages)
{
  auto model = std::make_shared<const atp::ModelFile>(atp::ModelFile::Open(TorusModel()));
  auto index = std::make_shared<const atp::CutIndex>(*model);
  // Drop the model's pages from the page cache, so the prediction finds pages to advise.
  const int fd = ::open(TorusModel().c_str(), O_RDONLY);
  ASSERT_GE(fd, 0);
  ::fdatasync(fd);
  ::posix_fadvise(fd, 0, 0, POSIX_FADV_DONTNEED);
  ::close(fd);

  atp::Prefetcher prefetcher(model, index);
  atp::ViewPoint view;
  view.TolerancePixels = 0.5;
  view.Eye[2] = 20;
  prefetcher.Observe(view, 1, 0.0);
  view.Eye[2] = 18; // moving in at 2 units per 0.1 s
  prefetcher.Observe(view, 1, 0.1);
  prefetcher.Wait();
  double predicted[3];
  prefetcher.LastPredictedEye(predicted);
  EXPECT_NEAR(predicted[2], 18 - 2 * 5, 1e-9);
  EXPECT_GE(prefetcher.Passes(), 1u);
  EXPECT_GT(prefetcher.AdvisedPages(), 0u);
}

} // namespace
