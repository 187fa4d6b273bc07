// This process's memory as the kernel counts it (/proc/self/status), for tests that check what
// gives memory back.
#ifndef ProcessMemory_h
#define ProcessMemory_h

#include <fstream>
#include <string>

namespace atp
{
namespace testing
{

/// A field of /proc/self/status (VmRSS, VmHWM, RssFile...), in KiB; 0 when absent.
inline long StatusKiB(const std::string& key)
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    if (line.rfind(key + ":", 0) == 0)
    {
      return std::stol(line.substr(key.size() + 1));
    }
  }
  return 0;
}

/// Pages of files mapped in this process, in KiB: a scratch file on a disk counts as file
/// pages, on tmpfs as shared memory.
inline long MappedFileKiB()
{
  return StatusKiB("RssFile") + StatusKiB("RssShmem");
}

} // namespace testing
} // namespace atp

#endif
