#include "atpBoundarySketch.h"

#include "atpResidentPages.h"

namespace atp
{

BoundarySketch::BoundarySketch(std::uint64_t vertexCount, const std::string& scratchDirectory)
  : Entries(scratchDirectory, static_cast<std::size_t>(vertexCount))
{
}

void BoundarySketch::ReleaseResidentPages(std::uint64_t first, std::uint64_t count) const
{
  atp::ReleaseResidentPages(this->Entries.Data() + first, count * sizeof(Entry));
}

void BoundarySketch::ReleaseResidentPages() const
{
  atp::ReleaseResidentPages(this->Entries.Data(), this->Entries.Size() * sizeof(Entry));
}

} // namespace atp
