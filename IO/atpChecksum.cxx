#include "atpChecksum.h"

#include <xxhash.h>

namespace atp
{

std::uint64_t Checksum(const void* data, std::size_t bytes)
{
  return XXH3_64bits(data, bytes);
}

} // namespace atp
