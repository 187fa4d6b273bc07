// The build context, jobs and results as bytes, for runners that ship them to other processes
// (the MPI build). Fields are memory images: both ends must run the same atp on the same
// architecture, which the context message checks (a layout signature) before any job is read.
#ifndef atpPatchJobMessages_h
#define atpPatchJobMessages_h

#include "atpPatchJob.h"
#include "vtkATPFiltersModule.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace atp
{

/// Decoding throws std::runtime_error for a message that is truncated, too long or not of this
/// layout; it never reads past `bytes`.
VTKATPFILTERS_EXPORT std::vector<std::uint8_t> EncodeContext(const PatchJobContext& context);
VTKATPFILTERS_EXPORT PatchJobContext DecodeContext(const std::uint8_t* data, std::size_t bytes);

/// `out` is replaced (its capacity reused).
VTKATPFILTERS_EXPORT void EncodeJob(const PatchJob& job, std::vector<std::uint8_t>& out);
VTKATPFILTERS_EXPORT void DecodeJob(const std::uint8_t* data, std::size_t bytes, PatchJob& out);

VTKATPFILTERS_EXPORT void EncodeResult(
  const PatchJobResult& result, std::vector<std::uint8_t>& out);
VTKATPFILTERS_EXPORT void DecodeResult(
  const std::uint8_t* data, std::size_t bytes, PatchJobResult& out);

} // namespace atp

#endif
