// Fuzz target: the patch decoder, on any bytes (a patch whose checksum matched but was written
// by a broken or hostile writer). It must decode or throw PatchFormatError; what it decodes has
// every index below the vertex count.
#include "atpPatchCodec.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  atp::QuantizationGrid grid;
  grid.Origin[0] = grid.Origin[1] = grid.Origin[2] = -1;
  grid.Step = 1.0 / 1024;
  atp::PatchMesh mesh;
  try
  {
    atp::DecodePatch(data, size, grid, mesh);
  }
  catch (const atp::PatchFormatError&)
  {
    return 0;
  }
  for (const std::uint32_t index : mesh.Indices)
  {
    if (index >= mesh.VertexCount())
    {
      std::abort();
    }
  }
  return 0;
}
