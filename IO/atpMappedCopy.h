// Copies bytes out of a memory-mapped file that another process may shrink meanwhile. Reading a
// page past the new end of a mapped file raises SIGBUS, which would kill a viewer whose model is
// truncated or rewritten under it; here the fault is caught and reported as a failed copy.
#ifndef atpMappedCopy_h
#define atpMappedCopy_h

#include <cstddef>

namespace atp
{

/// memcpy from a file mapping; false (with `destination` partly written) where the source pages
/// are no longer backed by the file. Installs a SIGBUS handler on first use that handles only
/// faults inside a copy of this thread and passes every other SIGBUS to the handler before it.
bool CopyFromMapping(void* destination, const void* source, std::size_t bytes);

} // namespace atp

#endif
