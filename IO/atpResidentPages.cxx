#include "atpResidentPages.h"

#include <cstdint>
#include <sys/mman.h>
#include <unistd.h>

namespace atp
{

void ReleaseResidentPages(const void* begin, std::size_t bytes)
{
  static const std::uintptr_t page = std::uintptr_t(::sysconf(_SC_PAGESIZE));
  const std::uintptr_t first = (std::uintptr_t(begin) + page - 1) / page * page;
  const std::uintptr_t end = (std::uintptr_t(begin) + bytes) / page * page;
  if (end > first)
  {
    // Advice only: a failure leaves the pages resident, which is still correct.
    ::madvise(reinterpret_cast<void*>(first), end - first, MADV_DONTNEED);
  }
}

}
