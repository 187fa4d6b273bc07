// HugePageBuffer: zero-filled, aligned to a huge page, movable, advised for transparent huge
// pages, memory given back by ranges, and a request beyond the address space is refused.
#include "atpHugePageBuffer.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <new>
#include <sstream>
#include <string>
#include <sys/mman.h>
#include <unistd.h>
#include <vector>

namespace
{
using atp::HugePageBuffer;

TEST(HugePageBuffer, ZeroFilledAlignedAndWritable)
{
  const std::size_t bytes = 5 * atp::HugePageBytes + 123;
  HugePageBuffer buffer(bytes);
  ASSERT_NE(buffer.Data(), nullptr);
  EXPECT_EQ(buffer.Size(), bytes);
  EXPECT_EQ(std::uintptr_t(buffer.Data()) % atp::HugePageBytes, 0u);
  auto* data = static_cast<std::uint8_t*>(buffer.Data());
  std::size_t nonzero = 0;
  for (std::size_t i = 0; i < bytes; ++i)
  {
    nonzero += data[i] != 0;
    data[i] = std::uint8_t(i * 7);
  }
  EXPECT_EQ(nonzero, 0u);
  for (std::size_t i = 0; i < bytes; i += 4099)
  {
    ASSERT_EQ(data[i], std::uint8_t(i * 7));
  }
}

TEST(HugePageBuffer, PrefaultKeepsWhatIsWrittenAndStaysInRange)
{
  const std::size_t bytes = 3 * atp::HugePageBytes + 1000;
  HugePageBuffer buffer(bytes);
  auto* data = static_cast<std::uint8_t*>(buffer.Data());
  data[atp::HugePageBytes + 17] = 5;
  data[bytes - 1] = 6;
  buffer.Prefault(atp::HugePageBytes, bytes); // past the end: clipped
  buffer.Prefault(0, atp::HugePageBytes + 1);
  buffer.Prefault(bytes, 100);               // nothing there
  std::size_t nonzero = 0;
  for (std::size_t i = 0; i < bytes; ++i)
  {
    nonzero += data[i] != 0;
  }
  EXPECT_EQ(nonzero, 2u);
  EXPECT_EQ(data[atp::HugePageBytes + 17], 5);
  EXPECT_EQ(data[bytes - 1], 6);
  HugePageBuffer small(100);
  small.Prefault(0, 100); // heap memory: a no-op
  EXPECT_EQ(static_cast<std::uint8_t*>(small.Data())[99], 0);
}

/// How many of the 4 KiB-or-larger pages of [begin, end) are resident (mincore).
std::size_t ResidentPages(const void* begin, std::size_t bytes)
{
  const std::size_t page = std::size_t(::sysconf(_SC_PAGESIZE));
  std::vector<unsigned char> flags((bytes + page - 1) / page);
  if (::mincore(const_cast<void*>(begin), bytes, flags.data()) != 0)
  {
    return ~std::size_t(0);
  }
  std::size_t resident = 0;
  for (unsigned char f : flags)
  {
    resident += f & 1;
  }
  return resident;
}

TEST(HugePageBuffer, ReleasedRangesReadZeroAndLeaveMemory)
{
  const std::size_t bytes = 4 * atp::HugePageBytes;
  const std::size_t page = std::size_t(::sysconf(_SC_PAGESIZE));
  HugePageBuffer buffer(bytes);
  auto* data = static_cast<std::uint8_t*>(buffer.Data());
  for (std::size_t i = 0; i < bytes; ++i)
  {
    data[i] = std::uint8_t(i % 251 + 1);
  }
  ASSERT_EQ(ResidentPages(data, bytes), bytes / page);
  // Unaligned ends: the partial pages are zeroed, the whole ones in between unmapped.
  const std::size_t first = atp::HugePageBytes + 100, last = 3 * atp::HugePageBytes - 100;
  buffer.Release(first, last - first);
  buffer.Release(bytes - 10, 1000); // clipped at the end
  buffer.Release(bytes, 10);        // nothing there
  // Before reading it back: a read maps the zero page, which mincore counts.
  const std::size_t wholePages = (last / page) - (first / page + 1);
  EXPECT_EQ(ResidentPages(data + (first / page + 1) * page, wholePages * page), 0u);
  EXPECT_EQ(ResidentPages(data, atp::HugePageBytes), atp::HugePageBytes / page);
  for (std::size_t i = 0; i < bytes; ++i)
  {
    const bool released = (i >= first && i < last) || i >= bytes - 10;
    ASSERT_EQ(data[i], released ? 0 : std::uint8_t(i % 251 + 1)) << "byte " << i;
  }
  data[2 * atp::HugePageBytes] = 9; // usable again
  EXPECT_EQ(data[2 * atp::HugePageBytes], 9);

  HugePageBuffer small(100); // heap memory: zeroed only
  std::fill_n(static_cast<std::uint8_t*>(small.Data()), 100, std::uint8_t(3));
  small.Release(10, 20);
  for (std::size_t i = 0; i < 100; ++i)
  {
    ASSERT_EQ(static_cast<std::uint8_t*>(small.Data())[i], i >= 10 && i < 30 ? 0 : 3);
  }
}

TEST(HugePageBuffer, EmptyAndMoved)
{
  HugePageBuffer empty;
  EXPECT_EQ(empty.Data(), nullptr);
  EXPECT_EQ(empty.Size(), 0u);
  EXPECT_EQ(HugePageBuffer(0).Data(), nullptr);

  HugePageBuffer first(1000);
  static_cast<char*>(first.Data())[999] = 42;
  void* const data = first.Data();
  HugePageBuffer second(std::move(first));
  EXPECT_EQ(first.Data(), nullptr);
  EXPECT_EQ(second.Data(), data);
  EXPECT_EQ(second.Size(), 1000u);
  EXPECT_EQ(static_cast<char*>(second.Data())[999], 42);
  second = HugePageBuffer(10);
  EXPECT_EQ(second.Size(), 10u);
  EXPECT_EQ(static_cast<char*>(second.Data())[9], 0);
}

TEST(HugePageBuffer, RefusesWhatTheAddressSpaceCannotHold)
{
  EXPECT_THROW(HugePageBuffer(std::numeric_limits<std::size_t>::max() - 100), std::bad_alloc);
  EXPECT_THROW(HugePageBuffer(std::size_t(1) << 62), std::bad_alloc);
}

/// The "THPeligible" line of the mapping holding `address` in /proc/self/smaps: -1 if absent.
int HugePageEligible(const void* address)
{
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line))
  {
    unsigned long long begin = 0, end = 0;
    if (std::sscanf(line.c_str(), "%llx-%llx ", &begin, &end) == 2 && line.find(':') > line.find('-'))
    {
      inside = std::uintptr_t(address) >= begin && std::uintptr_t(address) < end;
    }
    else if (inside && line.rfind("THPeligible:", 0) == 0)
    {
      return std::stoi(line.substr(12));
    }
  }
  return -1;
}

TEST(HugePageBuffer, AdvisedForHugePagesUntilStopped)
{
  std::ifstream mode("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  std::getline(mode, modes);
  if (modes.find("[madvise]") == std::string::npos && modes.find("[always]") == std::string::npos)
  {
    GTEST_SKIP() << "transparent huge pages are off on this machine: " << modes;
  }
  HugePageBuffer buffer(2 * atp::HugePageBytes);
  static_cast<char*>(buffer.Data())[0] = 1;
  const int eligible = HugePageEligible(buffer.Data());
  if (eligible < 0)
  {
    GTEST_SKIP() << "this kernel's smaps has no THPeligible line";
  }
  EXPECT_EQ(eligible, 1);
  // Once it only shrinks, khugepaged must not fill released pieces back in.
  buffer.StopHugePages();
  EXPECT_EQ(HugePageEligible(buffer.Data()), 0);
  EXPECT_EQ(static_cast<char*>(buffer.Data())[0], 1);
}

} // namespace
