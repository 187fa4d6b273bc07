#include "atpProcessMemory.h"

#include <fstream>
#include <string>
#include <sys/resource.h>
#include <unistd.h>

namespace atp
{

double ResidentMiB()
{
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return double(resident) * double(::sysconf(_SC_PAGESIZE)) / 1048576.0;
}

double PeakResidentMiB()
{
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0; // Linux reports KiB
}

ResidentKinds ResidentByKind()
{
  ResidentKinds kinds;
  std::ifstream status("/proc/self/status");
  for (std::string key; status >> key;)
  {
    double kib = 0;
    if (key == "RssAnon:" && status >> kib)
    {
      kinds.AnonymousMiB = kib / 1024.0;
    }
    else if (key == "RssFile:" && status >> kib)
    {
      kinds.FileMiB = kib / 1024.0;
    }
  }
  return kinds;
}

}
