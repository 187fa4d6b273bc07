// ScratchArray: zero-filled, grows keeping its contents, leaves no file behind.
#include "atpScratchArray.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
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
