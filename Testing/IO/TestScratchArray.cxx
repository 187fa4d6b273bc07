// ScratchArray: zero-filled, grows keeping its contents, leaves no file behind.
#include "ProcessMemory.h"
#include "atpResidentPages.h"
#include "atpScratchArray.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <sys/mman.h>
#include <unistd.h>
#include <vector>
#include <stdexcept>

namespace
{
namespace fs = std::filesystem;

TEST(ScratchArray, ZeroFilledAndGrowsKeepingContents)
{
  atp::ScratchArray<std::uint64_t> array(fs::temp_directory_path().string(), 1000);
  ASSERT_EQ(array.Size(), 1000u);
  for (std::size_t i = 0; i < array.Size(); ++i)
  {
    EXPECT_EQ(array[i], 0u);
    array[i] = i * i;
  }
  array.Resize(1 << 20);
  ASSERT_EQ(array.Size(), std::size_t(1) << 20);
  for (std::size_t i = 0; i < 1000; ++i)
  {
    EXPECT_EQ(array[i], i * i);
  }
  EXPECT_EQ(array[(1 << 20) - 1], 0u);
  array.Resize(10); // never shrinks
  EXPECT_EQ(array.Size(), std::size_t(1) << 20);
}

TEST(ScratchArray, LeavesNoFileBehind)
{
  const fs::path directory = fs::temp_directory_path() / "atp-scratch-array-test";
  fs::remove_all(directory);
  fs::create_directory(directory);
  {
    atp::ScratchArray<float> array(directory.string(), 4096);
    array[4095] = 1.0f;
    EXPECT_TRUE(fs::is_empty(directory));
  }
  EXPECT_TRUE(fs::is_empty(directory));
  fs::remove_all(directory);
}

TEST(ScratchArray, MissingDirectoryIsAnError)
{
  EXPECT_THROW(atp::ScratchArray<float>("/nonexistent/atp-scratch", 10), std::runtime_error);
}

TEST(ScratchArray, EmptyArray)
{
  atp::ScratchArray<float> array(fs::temp_directory_path().string(), 0);
  EXPECT_EQ(array.Size(), 0u);
  array.ReleaseResident(); // nothing mapped: nothing to do
}

// The forest and the bucket table grow one record at a time, and construction reuses one array
// per level.
TEST(ScratchArray, GrowsByElementsFillsAndReassigns)
{
  atp::ScratchArray<std::uint32_t> array("");
  for (std::uint32_t i = 0; i < 300000; ++i)
  {
    array.PushBack(i ^ 0x5a5a5a5au);
  }
  ASSERT_EQ(array.Size(), 300000u);
  for (std::uint32_t i = 0; i < 300000; ++i)
  {
    ASSERT_EQ(array[i], i ^ 0x5a5a5a5au) << i;
  }
  array.Resize(300010, 7u); // only the new elements take the fill
  EXPECT_EQ(array[299999], 299999u ^ 0x5a5a5a5au);
  EXPECT_EQ(array[300000], 7u);
  EXPECT_EQ(array[300009], 7u);
  array.Assign(5, 9u); // shrinks, every element filled
  ASSERT_EQ(array.Size(), 5u);
  for (std::size_t i = 0; i < 5; ++i)
  {
    EXPECT_EQ(array[i], 9u);
  }
  array.Resize(7); // over elements Assign gave up: they read zero as new ones do
  ASSERT_EQ(array.Size(), 7u);
  EXPECT_EQ(array[4], 9u);
  EXPECT_EQ(array[5], 0u);
  EXPECT_EQ(array[6], 0u);
}

TEST(ScratchArray, MovesKeepTheContentsAndEmptyTheSource)
{
  atp::ScratchArray<std::uint64_t> a("", 1000), b("", 10);
  for (std::size_t i = 0; i < 1000; ++i)
  {
    a[i] = 3 * i;
  }
  b[9] = 42;
  std::swap(a, b);
  ASSERT_EQ(a.Size(), 10u);
  ASSERT_EQ(b.Size(), 1000u);
  EXPECT_EQ(a[9], 42u);
  EXPECT_EQ(b[999], 2997u);
  atp::ScratchArray<std::uint64_t> c(std::move(b));
  EXPECT_EQ(b.Size(), 0u);
  ASSERT_EQ(c.Size(), 1000u);
  EXPECT_EQ(c[500], 1500u);
  b = std::move(c); // the moved-from array is whole again
  EXPECT_EQ(c.Size(), 0u);
  EXPECT_EQ(b[998], 2994u);
  b.PushBack(1);
  EXPECT_EQ(b[1000], 1u);
}
} // namespace

namespace
{
std::size_t ResidentPages(const void* begin, std::size_t bytes)
{
  const std::size_t page = std::size_t(::sysconf(_SC_PAGESIZE));
  std::vector<unsigned char> in(bytes / page);
  ::mincore(const_cast<void*>(begin), in.size() * page, in.data());
  std::size_t resident = 0;
  for (const unsigned char v : in)
  {
    resident += v & 1;
  }
  return resident;
}
} // namespace

TEST(ScratchArray, ReleasedPagesLeaveMemoryButKeepTheirContents)
{
  // mincore reports page-cache residency, not the process's: use the process's own measure.
  const auto residentKiB = atp::testing::MappedFileKiB;
  constexpr std::size_t count = std::size_t(64) << 20 >> 3; // 64 MiB of uint64
  atp::ScratchArray<std::uint64_t> array(fs::temp_directory_path().string(), count);
  for (std::size_t i = 0; i < count; ++i)
  {
    array[i] = i * 2654435761u;
  }
  const long before = residentKiB();
  atp::ReleaseResidentPages(array.Data(), count * sizeof(std::uint64_t));
  const long after = residentKiB();
  EXPECT_GE(before - after, 60L << 10) << "released pages still counted as resident";
  EXPECT_GT(ResidentPages(array.Data(), count * sizeof(std::uint64_t)), 0u)
    << "the page cache keeps them";
  for (std::size_t i = 0; i < count; i += 4099)
  {
    ASSERT_EQ(array[i], i * 2654435761u);
  }
}

TEST(ScratchArray, AssignHoldsASliceOfResidentMemory)
{
  // Released slice by slice, a third of an array of 12-byte elements stayed resident: the
  // kernel maps a file's pages up to 2 MiB at a time, and a block a release covered only in
  // part stayed mapped in whole.
  using Element = std::array<float, 3>;
  constexpr std::size_t count = std::size_t(12) << 20; // 144 MiB
  atp::ScratchArray<Element> array(fs::temp_directory_path().string(), count);
  const long before = atp::testing::MappedFileKiB();
  array.Assign(count, Element{ { 1, 2, 3 } });
  EXPECT_LT(atp::testing::MappedFileKiB() - before, 16L << 10) << "KiB left resident by Assign";
  ASSERT_EQ(array.Size(), count);
  for (std::size_t i = 0; i < count; i += 100003)
  {
    ASSERT_EQ(array[i], (Element{ { 1, 2, 3 } })) << i;
  }
  EXPECT_EQ(array[count - 1], (Element{ { 1, 2, 3 } }));
}
