#include "atpBoundarySketch.h"

namespace atp
{

BoundarySketch::BoundarySketch(std::uint64_t vertexCount, const std::string& scratchDirectory)
  : Entries(scratchDirectory, static_cast<std::size_t>(vertexCount))
{
}

} // namespace atp
