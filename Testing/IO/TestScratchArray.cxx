// ScratchArray: zero-filled, grows keeping its contents, leaves no file behind.
#include "atpResidentPages.h"
#include "atpScratchArray.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
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
  // mincore reports page-cache residency, not the process's: use the process's own measure
  // (a scratch file on tmpfs counts as shared memory, on a disk as file pages).
  auto residentKiB = [] {
    std::ifstream status("/proc/self/status");
    std::string line;
    long total = 0;
    while (std::getline(status, line))
    {
      if (line.rfind("RssFile:", 0) == 0 || line.rfind("RssShmem:", 0) == 0)
      {
        total += std::stol(line.substr(line.find(':') + 1));
      }
    }
    return total;
  };
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
