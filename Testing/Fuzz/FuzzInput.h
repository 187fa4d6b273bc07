// What the fuzz targets share: the fuzzer's bytes as a file on disk, since the readers under test
// take paths (and map them) like the applications do.
#ifndef FuzzInput_h
#define FuzzInput_h

#include <cstddef>
#include <cstdint>
#include <string>

namespace atp
{
namespace fuzz
{

/// Writes `bytes` to a file named `name` in a directory of this process, replacing the last
/// input, and returns its path. Aborts when it cannot (the harness is broken, not the input).
std::string InputFile(const std::string& name, const std::uint8_t* bytes, std::size_t size);

/// The directory for the readers' scratch files.
std::string ScratchDirectory();

} // namespace fuzz
} // namespace atp

#endif
