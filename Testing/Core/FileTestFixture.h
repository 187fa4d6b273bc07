// A gtest fixture for tests that write files: each test gets a fresh directory of its own
// (named after the test, so parallel CTest runs never share one), removed afterwards.
#ifndef FileTestFixture_h
#define FileTestFixture_h

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

class FileTestFixture : public ::testing::Test
{
protected:
  void SetUp() override
  {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    this->Dir = std::filesystem::temp_directory_path() /
      ("atp-test-" + std::to_string(::getpid()) + "-" + info->test_suite_name() + "-" +
        info->name());
    std::filesystem::remove_all(this->Dir);
    std::filesystem::create_directories(this->Dir);
  }
  void TearDown() override { std::filesystem::remove_all(this->Dir); }

  std::string Path(const std::string& name) const { return (this->Dir / name).string(); }

  /// Writes `bytes` to the file `name` in the test's directory; returns its path.
  std::string Write(const std::string& name, const std::string& bytes) const
  {
    std::ofstream(this->Path(name), std::ios::binary) << bytes;
    return this->Path(name);
  }

  std::filesystem::path Dir;
};

#endif
