// Out-of-core partitioning: bucket pages on disk, leaf capacity, conformity, nothing lost.
#include "ConformityCheck.h"
#include "ProcessMemory.h"
#include "atpPartitioner.h"
#include "atpStreamPartition.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <csignal>
#include <cstdio>
#include <sys/resource.h>
#include <cstring>
#include <map>
#include <random>

using namespace atp;

namespace
{
SoupTriangle MakeTriangle(float x, float y, float z, float size, std::uint8_t flags = 0)
{
  SoupTriangle t{};
  const float corners[3][3] = { { x, y, z }, { x + size, y, z }, { x, y + size, z + size / 2 } };
  std::memcpy(t.V, corners, sizeof(corners));
  t.BoundaryEdges = flags;
  return t;
}

bool SameTriangle(const SoupTriangle& a, const SoupTriangle& b)
{
  return std::memcmp(a.V, b.V, sizeof(a.V)) == 0 && a.BoundaryEdges == b.BoundaryEdges;
}

std::vector<SoupTriangle> RandomSoup(unsigned seed, std::size_t n)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-5, 5);
  std::vector<SoupTriangle> soup;
  for (std::size_t i = 0; i < n; ++i)
  {
    // Clustered on a sphere-like shell, as surfaces are: depth varies across the cube.
    float p[3] = { u(rng), u(rng), u(rng) };
    const float r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) + 1e-3f;
    for (float& c : p)
    {
      c = c / r * 4;
    }
    soup.push_back(MakeTriangle(p[0], p[1], p[2], 0.01f, std::uint8_t(i % 8)));
  }
  return soup;
}

Box BoxOf(const std::vector<SoupTriangle>& soup)
{
  Box box;
  for (const auto& t : soup)
  {
    for (const auto& v : t.V)
    {
      box.Add(v);
    }
  }
  return box;
}
} // namespace

/// Appends, evicts, recycles and reads back triangles, with their colors or without (then
/// they come back opaque white). Prefetches go to buckets of every kind along the way (the
/// next one appended, evicted ones, ones that do not exist yet): they must change nothing.
void CheckEvictionAndReuse(bool colors)
{
  // Eight frames for hundreds of buckets: almost every append evicts a page to disk.
  BucketStore store("", 1, colors);
  ASSERT_EQ(store.PoolPages(), 8u);
  std::map<std::uint32_t, std::vector<SoupTriangle>> reference;
  std::mt19937 rng(7);
  for (int i = 0; i < 60000; ++i)
  {
    const std::uint32_t bucket = rng() % 300;
    // Every tenth triangle repeats a corner of the one before in its bucket (shared corners).
    SoupTriangle t = MakeTriangle(float(i), float(bucket), 0, 1, std::uint8_t(i & 7));
    if (i % 10 == 0 && !reference[bucket].empty())
    {
      std::memcpy(t.V[0], reference[bucket].back().V[2], sizeof(t.V[0]));
    }
    t.Normals[1][0] = std::int16_t(i);
    std::memset(t.Colors, i & 0xff, sizeof(t.Colors));
    store.Prefetch(bucket, t);
    store.Prefetch(std::uint32_t(rng() % 400), t);
    store.Append(bucket, t);
    if (!colors)
    {
      std::memset(t.Colors, 255, sizeof(t.Colors));
    }
    reference[bucket].push_back(t);
    if (i % 5000 == 4999)
    {
      // Empty some buckets so pages get recycled.
      const std::uint32_t victim = rng() % 300;
      store.Clear(victim);
      reference[victim].clear();
    }
  }
  std::uint64_t live = 0;
  for (const auto& [bucket, expected] : reference)
  {
    std::vector<SoupTriangle> got;
    store.Read(bucket, got);
    ASSERT_EQ(got.size(), expected.size()) << "bucket " << bucket;
    ASSERT_EQ(store.Count(bucket), expected.size());
    for (std::size_t i = 0; i < got.size(); ++i)
    {
      ASSERT_EQ(std::memcmp(&got[i], &expected[i], sizeof(SoupTriangle)), 0)
        << "bucket " << bucket << " record " << i;
    }
    live += expected.size();
  }
  EXPECT_GT(store.Stats().BytesWritten, 0u);
  EXPECT_GT(store.Stats().BytesRead, 0u);
  // Recycled pages keep the scratch file near the live data (one partial page per bucket);
  // these triangles share few corners: about 3 corners and a 7-byte record each.
  const std::uint64_t soupBytes = 3 * (colors ? 20 : 16) + 7;
  EXPECT_LE(store.Stats().PeakScratchBytes, live * soupBytes + 2 * 300 * BucketStore::PageBytes);
}

TEST(BucketStore, KeepsEveryTriangleThroughEvictionAndReuse)
{
  CheckEvictionAndReuse(true);
}

TEST(BucketStore, WithoutColorsTrianglesReadBackWhite)
{
  CheckEvictionAndReuse(false);
}

TEST(BucketStore, AMemoryBudgetBeyondTheMachineIsRefusedWithAMessage)
{
  try
  {
    BucketStore store("", std::size_t(1) << 52, false); // 4 PiB: no mapping of that size
    ADD_FAILURE() << "no error";
  }
  catch (const std::runtime_error& error)
  {
    EXPECT_NE(std::string(error.what()).find("MiB for the triangle buckets (the bucket memory asked for): out of memory"),
      std::string::npos)
      << error.what();
  }
}

namespace
{
bool SameTriangles(const std::vector<SoupTriangle>& a, const std::vector<SoupTriangle>& b)
{
  return a.size() == b.size() &&
    (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(SoupTriangle)) == 0);
}

/// Resident memory of this process (VmRSS), in bytes.
std::uint64_t ResidentBytes()
{
  return std::uint64_t(atp::testing::StatusKiB("VmRSS")) * 1024;
}
} // namespace

// Once partitioning is over, construction empties the buckets one by one: the memory of their
// pool frames goes back to the system as it does (a construction of the brain dropped from
// 300 to 50 MiB), and appending still works after it.
TEST(BucketStore, DiscardedBucketsGiveTheirPoolMemoryBack)
{
  const std::size_t budget = std::size_t(48) << 20;
  BucketStore store("", budget, false);
  std::vector<std::vector<SoupTriangle>> reference(64);
  // About 30 MiB of pages (no shared corners: some 55 bytes a triangle).
  for (int i = 0; i < 550000; ++i)
  {
    const std::uint32_t bucket = std::uint32_t(i % 64);
    SoupTriangle t = MakeTriangle(float(i), float(bucket), 1, 0.5f, std::uint8_t(i & 7));
    std::memset(t.Colors, 255, sizeof(t.Colors));
    store.Append(bucket, t);
    reference[bucket].push_back(t);
  }
  store.StopAppending(); // gives back the free frames and corner lookups
  for (std::uint32_t bucket = 0; bucket < 60; ++bucket)
  {
    std::vector<SoupTriangle> got;
    store.Read(bucket, got);
    ASSERT_TRUE(SameTriangles(got, reference[bucket])) << "bucket " << bucket;
  }
  // Nothing allocated in between (an allocator may keep what it is given back, as
  // AddressSanitizer's quarantine does): only the pool can change.
  const std::uint64_t full = ResidentBytes();
  for (std::uint32_t bucket = 0; bucket < 60; ++bucket)
  {
    store.Discard(bucket);
  }
  const std::uint64_t drained = ResidentBytes();
  for (std::uint32_t bucket = 0; bucket < 60; ++bucket)
  {
    reference[bucket].clear();
  }
  EXPECT_GT(full, drained + (std::uint64_t(20) << 20)) << full << " -> " << drained << " bytes";
  // Appends still work: to a kept bucket (its last page's corner lookup is rebuilt), to a
  // discarded one, to a new one.
  for (const std::uint32_t bucket : { 61u, 3u, 100u })
  {
    if (bucket >= reference.size())
    {
      reference.resize(bucket + 1);
    }
    for (int i = 0; i < 2000; ++i)
    {
      SoupTriangle t = MakeTriangle(float(i), -float(bucket), 2, 0.25f);
      std::memset(t.Colors, 255, sizeof(t.Colors));
      if (i > 0)
      {
        std::memcpy(t.V[0], reference[bucket].back().V[1], sizeof(t.V[0])); // shared corners
      }
      store.Append(bucket, t);
      reference[bucket].push_back(t);
    }
  }
  for (std::uint32_t bucket = 0; bucket < reference.size(); ++bucket)
  {
    std::vector<SoupTriangle> got;
    store.Read(bucket, got);
    ASSERT_TRUE(SameTriangles(got, reference[bucket])) << "bucket " << bucket;
  }
}

// The bucket table has a record per node of the forest: its pages leave the process when it
// says so, and the records come back unchanged.
TEST(BucketStore, ReleasedTableLeavesMemoryAndKeepsEveryBucket)
{
  BucketStore store("", std::size_t(8) << 20, false);
  const std::uint32_t buckets = 400000; // 6 MiB of records
  std::vector<SoupTriangle> appended;
  for (std::uint32_t bucket = 0; bucket < buckets; bucket += 40000)
  {
    appended.push_back(MakeTriangle(float(bucket), 1, 2, 0.5f));
    store.Append(bucket, appended.back());
  }
  store.Append(buckets - 1, MakeTriangle(0, 0, 0, 1)); // the table now spans every bucket
  std::uint64_t total = 0;
  for (std::uint32_t bucket = 0; bucket < buckets; ++bucket)
  {
    total += store.Count(bucket); // every record read: all of the table resident
  }
  ASSERT_EQ(total, appended.size() + 1);
  const long before = atp::testing::MappedFileKiB();
  store.ReleaseResident();
  const long after = atp::testing::MappedFileKiB();
  EXPECT_GE(before - after, 5L << 10) << before << " -> " << after << " KiB";
  for (std::uint32_t bucket = 0, i = 0; bucket < buckets; bucket += 40000, ++i)
  {
    std::vector<SoupTriangle> got;
    store.Read(bucket, got);
    ASSERT_EQ(got.size(), 1u) << bucket;
    EXPECT_TRUE(SameTriangle(got[0], appended[i])) << bucket;
  }
  EXPECT_EQ(store.Count(buckets - 1), 1u);
  EXPECT_EQ(store.Count(buckets - 2), 0u);
}

// Stream neighbours share corners, which a bucket finds again without a page lookup. Buckets
// whose numbers agree in their low bits, appended in turn, and a bucket emptied and filled
// again (its recycled page starts without corners) must not take each other's corner numbers.
TEST(BucketStore, BucketsAppendedInTurnKeepTheirOwnSharedCorners)
{
  BucketStore store("", 1, true);
  const std::uint32_t buckets[] = { 7, 7 + (1u << 13), 7 + (1u << 20), 7 + (1u << 24) };
  std::map<std::uint32_t, std::vector<SoupTriangle>> reference;
  for (int k = 0; k < 4; ++k)
  {
    // Corners of its own first, so that each bucket numbers the common corners differently.
    for (int filler = 0; filler < k; ++filler)
    {
      const SoupTriangle t = MakeTriangle(-1, float(k), float(filler), 1);
      store.Append(buckets[k], t);
      reference[buckets[k]].push_back(t);
    }
  }
  for (int i = 0; i < 4000; ++i)
  {
    const std::uint32_t bucket = buckets[i % 4];
    std::vector<SoupTriangle>& expected = reference[bucket];
    // The same corners in every bucket, two of them shared with the triangle before.
    SoupTriangle t = MakeTriangle(float(i / 4), 0, 0, 1);
    if (i >= 4)
    {
      std::memcpy(t.V[0], expected.back().V[1], sizeof(t.V[0]));
      std::memcpy(t.V[2], expected.back().V[2], sizeof(t.V[2]));
    }
    store.Append(bucket, t);
    expected.push_back(t);
    if (i == 2001)
    {
      store.Clear(buckets[1]);
      reference[buckets[1]].clear();
      // Its last triangle again: its old corners, in a page that holds none of them yet.
      store.Append(buckets[1], t);
      reference[buckets[1]].push_back(t);
    }
  }
  for (const auto& [bucket, expected] : reference)
  {
    std::vector<SoupTriangle> got;
    store.Read(bucket, got);
    ASSERT_EQ(got.size(), expected.size()) << "bucket " << bucket;
    for (std::size_t i = 0; i < got.size(); ++i)
    {
      ASSERT_EQ(std::memcmp(&got[i], &expected[i], sizeof(SoupTriangle)), 0)
        << "bucket " << bucket << " triangle " << i;
    }
  }
}

// Triangles that add no corner still take room: the same triangle over and over fills pages
// with triangle records alone, and every one reads back.
TEST(BucketStore, PagesOfRepeatedCornersFillUp)
{
  BucketStore store("", 1, true);
  SoupTriangle t = MakeTriangle(1, 2, 3, 1, 5);
  std::memset(t.Colors, 7, sizeof(t.Colors));
  const std::size_t count = 3 * BucketStore::PageBytes / 7 + 100; // several pages
  for (std::size_t i = 0; i < count; ++i)
  {
    store.Append(9, t);
  }
  std::vector<SoupTriangle> got;
  store.Read(9, got);
  ASSERT_EQ(got.size(), count);
  for (const SoupTriangle& g : got)
  {
    ASSERT_EQ(std::memcmp(&g, &t, sizeof(t)), 0);
  }
}

// A bucket of a streamed mesh: triangles of a grid, each corner shared by up to 6 of them,
// take little more than a third of their soup size (52 bytes a triangle without colors; a
// corner is 17 bytes: position, normal and input uses).
TEST(BucketStore, SharedCornersAreStoredOnce)
{
  BucketStore store("", 1, false);
  std::vector<SoupTriangle> grid;
  const int n = 200;
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < n; ++j)
    {
      const float x = float(i), y = float(j);
      const float quad[4][3] = { { x, y, 0 }, { x + 1, y, 0 }, { x + 1, y + 1, 0 }, { x, y + 1, 0 } };
      for (const auto& corners : { std::array<int, 3>{ 0, 1, 2 }, std::array<int, 3>{ 0, 2, 3 } })
      {
        SoupTriangle t{};
        for (int k = 0; k < 3; ++k)
        {
          std::memcpy(t.V[k], quad[corners[std::size_t(k)]], sizeof(t.V[k]));
          t.InputUses[k] = 6; // kept, and a key of the corner like its position
        }
        std::memset(t.Colors, 255, sizeof(t.Colors));
        grid.push_back(t);
      }
    }
  }
  for (const SoupTriangle& t : grid)
  {
    store.Append(0, t);
  }
  std::vector<SoupTriangle> got;
  store.Read(0, got);
  ASSERT_EQ(got.size(), grid.size());
  for (std::size_t i = 0; i < got.size(); ++i)
  {
    ASSERT_EQ(std::memcmp(&got[i], &grid[i], sizeof(SoupTriangle)), 0) << "triangle " << i;
  }
  const double bytesPerTriangle = double(store.Stats().PeakScratchBytes) / double(grid.size());
  std::printf("a streamed grid in buckets: %.1f bytes per triangle\n", bytesPerTriangle);
  EXPECT_LT(bytesPerTriangle, 18.5);
}

TEST(Partitioner, RespectsCapacityLosesNothingAndConforms)
{
  for (const std::size_t memory : { std::size_t(1), std::size_t(64) << 20 })
  {
    const auto soup = RandomSoup(1, 50000);
    PartitionOptions options;
    options.LeafCapacity = 500;
    options.BucketMemoryBytes = memory; // 1 byte: the smallest pool, buckets live on disk
    Partitioner partitioner(BoxOf(soup), options);
    for (std::size_t i = 0; i < soup.size(); i += 1000)
    {
      partitioner.Insert(&soup[i], std::min<std::size_t>(1000, soup.size() - i));
    }
    const PartitionStats stats = partitioner.Stats();
    EXPECT_EQ(stats.Triangles, soup.size());
    EXPECT_LE(stats.LargestLeaf, 500u);
    EXPECT_EQ(stats.OverfullLeaves, 0u);
    EXPECT_GE(stats.Depth, 6);

    const TetraForest& forest = partitioner.Forest();
    std::vector<SoupTriangle> all;
    std::vector<Tetra> leaves;
    for (const auto leaf : forest.Leaves())
    {
      leaves.push_back(forest.Geometry(leaf));
      std::vector<SoupTriangle> bucket;
      partitioner.ReadLeaf(leaf, bucket);
      for (const auto& t : bucket)
      {
        double c[3];
        partitioner.Centroid(t, c);
        ASSERT_EQ(forest.LeafContaining(c), leaf) << "triangle stored in the wrong leaf";
        ASSERT_TRUE(forest.Geometry(leaf).Contains(c));
      }
      all.insert(all.end(), bucket.begin(), bucket.end());
    }
    EXPECT_EQ(atp::testing::FaceMatchingProblem(leaves), "");
    // The same triangles, flags included.
    auto order = [](const SoupTriangle& a, const SoupTriangle& b) {
      return std::memcmp(&a, &b, sizeof(SoupTriangle)) < 0;
    };
    auto expected = soup;
    std::sort(expected.begin(), expected.end(), order);
    std::sort(all.begin(), all.end(), order);
    ASSERT_EQ(all.size(), expected.size());
    for (std::size_t i = 0; i < all.size(); ++i)
    {
      ASSERT_TRUE(SameTriangle(all[i], expected[i]));
    }
  }
}

TEST(Partitioner, TrianglesSharingOneCentroidStopAtTheDeepestLevel)
{
  std::vector<SoupTriangle> soup(300, MakeTriangle(1, 2, 3, 0.5f));
  soup.push_back(MakeTriangle(-4, 0, 0, 0.5f)); // sets a non-trivial box
  PartitionOptions options;
  options.LeafCapacity = 100;
  Partitioner partitioner(BoxOf(soup), options);
  partitioner.Insert(soup.data(), soup.size());
  const PartitionStats stats = partitioner.Stats();
  EXPECT_EQ(stats.Depth, MaxLevel);
  EXPECT_EQ(stats.OverfullLeaves, 1u);
  EXPECT_EQ(stats.LargestLeaf, 300u);
}

TEST(Partitioner, IsDeterministic)
{
  const auto soup = RandomSoup(2, 20000);
  PartitionOptions options;
  options.LeafCapacity = 300;
  Partitioner a(BoxOf(soup), options), b(BoxOf(soup), options);
  a.Insert(soup.data(), soup.size());
  for (const auto& t : soup)
  {
    b.Insert(&t, 1); // batch size must not matter
  }
  ASSERT_EQ(a.Forest().Size(), b.Forest().Size());
  for (std::size_t i = 0; i < a.Forest().Size(); ++i)
  {
    const auto n = TetraForest::NodeIndex(i);
    ASSERT_EQ(a.Forest()[n].Id, b.Forest()[n].Id);
    ASSERT_EQ(a.TriangleCount(n), b.TriangleCount(n));
  }
}

namespace
{
/// Triangles from memory, as a TriangleSource.
class VectorSource final : public TriangleSource
{
public:
  explicit VectorSource(std::vector<SoupTriangle> triangles)
    : Triangles(std::move(triangles))
    , Bounds_(BoxOf(Triangles))
  {
  }
  Box Bounds() const override { return Bounds_; }
  std::uint64_t ExpectedTriangles() const override { return Triangles.size(); }
  std::size_t Read(SoupTriangle* out, std::size_t max) override
  {
    const std::size_t n = std::min(max, Triangles.size() - Next);
    std::copy_n(Triangles.begin() + std::ptrdiff_t(Next), n, out);
    Next += n;
    if (Next >= FailAfter)
    {
      throw InputError("test.ply: truncated");
    }
    return n;
  }
  const InputStats& Stats() const override { return Counts; }

  std::size_t FailAfter = SIZE_MAX;

private:
  std::vector<SoupTriangle> Triangles;
  Box Bounds_;
  std::size_t Next = 0;
  InputStats Counts;
};
} // namespace

TEST(PartitionStream, OverlapsReadingAndGivesTheSameForest)
{
  const auto soup = RandomSoup(3, 300000);
  PartitionOptions options;
  options.LeafCapacity = 400;
  VectorSource source(soup);
  std::uint64_t lastProgress = 0;
  auto streamed = PartitionStream(source, options, [&](std::uint64_t done) {
    EXPECT_GT(done, lastProgress);
    lastProgress = done;
  });
  EXPECT_EQ(lastProgress, soup.size());
  Partitioner direct(BoxOf(soup), options);
  direct.Insert(soup.data(), soup.size());
  ASSERT_EQ(streamed->Forest().Size(), direct.Forest().Size());
  EXPECT_EQ(streamed->Stats().Leaves, direct.Stats().Leaves);
  // The reading thread locates against its own copy of the forest, which lags the inserting
  // thread's by the splits of a batch or two: node for node and triangle for triangle, the
  // same partition.
  std::vector<SoupTriangle> a, b;
  std::size_t splits = 0;
  for (std::size_t i = 0; i < direct.Forest().Size(); ++i)
  {
    const auto n = TetraForest::NodeIndex(i);
    ASSERT_EQ(streamed->Forest()[n].Id.Bits, direct.Forest()[n].Id.Bits) << "node " << i;
    ASSERT_EQ(streamed->Forest()[n].FirstChild, direct.Forest()[n].FirstChild) << "node " << i;
    splits += !direct.Forest()[n].IsLeaf();
    a.clear();
    b.clear();
    streamed->ReadLeaf(n, a);
    direct.ReadLeaf(n, b);
    ASSERT_EQ(a.size(), b.size()) << "node " << i;
    ASSERT_TRUE(a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(SoupTriangle)) == 0)
      << "node " << i;
  }
  EXPECT_GT(splits, 500u) << "the copy should lag many splits";
}

TEST(PartitionStream, ReaderErrorsReachTheCaller)
{
  VectorSource source(RandomSoup(4, 200000));
  source.FailAfter = 100000;
  EXPECT_THROW(PartitionStream(source, PartitionOptions(), [](std::uint64_t) {}), InputError);
}

TEST(PartitionStream, CancelledByTheCallerJoinsTheReader)
{
  VectorSource source(RandomSoup(5, 400000));
  EXPECT_THROW(PartitionStream(source, PartitionOptions(),
                 [](std::uint64_t done) {
                   if (done > 70000)
                   {
                     throw std::runtime_error("cancelled");
                   }
                 }),
    std::runtime_error);
}

TEST(PartitionStream, AFullScratchDiskIsAnErrorNotACrash)
{
  // A file size limit makes the scratch file's writes fail as on a full disk.
  std::signal(SIGXFSZ, SIG_IGN);
  rlimit saved{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  rlimit small = saved;
  small.rlim_cur = 1 << 20;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  VectorSource source(RandomSoup(6, 200000)); // 8 MB of triangles
  PartitionOptions options;
  options.BucketMemoryBytes = 1; // everything goes to the scratch file
  try
  {
    PartitionStream(source, options, [](std::uint64_t) {});
    ADD_FAILURE() << "no error although the scratch file could not grow";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("cannot write scratch data"), std::string::npos)
      << e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &saved);
}
