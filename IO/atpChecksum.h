// The one checksum of the .atp format (XXH3, 64 bits): fast enough to check every patch on its
// first decode without showing up in a profile.
#ifndef atpChecksum_h
#define atpChecksum_h

#include "vtkATPIOModule.h"

#include <cstddef>
#include <cstdint>

namespace atp
{

VTKATPIO_EXPORT std::uint64_t Checksum(const void* data, std::size_t bytes);

} // namespace atp

#endif
