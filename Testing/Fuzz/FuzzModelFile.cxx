// Fuzz target: opening a .atp model and using it as the renderer and `atp extract` do. The
// checksums would stop almost every mutation at the door, so the harness first makes them agree
// with the mutated bytes (where the header's layout lets it find them): what is fuzzed is the
// validation of structure and values behind them, the diamond index, the cut and the decoder.
// Any input must be refused with ModelError or PatchFormatError, or work; never crash or hang.
#include "FuzzInput.h"
#include "atpChecksum.h"
#include "atpCut.h"
#include "atpCutIndex.h"
#include "atpModelFile.h"
#include "atpModelFormat.h"
#include "atpPatchCodec.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace
{
using atp::ModelHeader;
using atp::ModelNode;

bool Within(std::uint64_t offset, std::uint64_t bytes, std::uint64_t size)
{
  return offset <= size && bytes <= size - offset;
}

/// Rewrites every checksum the header's layout can locate inside `file`.
void AgreeChecksums(std::vector<std::uint8_t>& file)
{
  if (file.size() < sizeof(ModelHeader))
  {
    return;
  }
  ModelHeader h;
  std::memcpy(&h, file.data(), sizeof(h));
  const std::uint64_t size = file.size();
  if (h.NodeSectionBytes % sizeof(ModelNode) == 0 &&
    Within(h.NodeSectionOffset, h.NodeSectionBytes, size) &&
    Within(h.PatchSectionOffset, h.PatchSectionBytes, size))
  {
    std::uint8_t* nodeBytes = file.data() + h.NodeSectionOffset;
    for (std::uint64_t i = 0; i < h.NodeSectionBytes / sizeof(ModelNode); ++i)
    {
      ModelNode n;
      std::memcpy(&n, nodeBytes + i * sizeof(n), sizeof(n));
      if (Within(n.PatchOffset, n.PatchBytes, h.PatchSectionBytes))
      {
        n.PatchChecksum =
          atp::Checksum(file.data() + h.PatchSectionOffset + n.PatchOffset, n.PatchBytes);
        std::memcpy(nodeBytes + i * sizeof(n), &n, sizeof(n));
      }
    }
    h.NodeSectionChecksum = atp::Checksum(nodeBytes, std::size_t(h.NodeSectionBytes));
    h.PatchSectionChecksum =
      atp::Checksum(file.data() + h.PatchSectionOffset, std::size_t(h.PatchSectionBytes));
  }
  h.HeaderChecksum = atp::Checksum(&h, offsetof(ModelHeader, HeaderChecksum));
  std::memcpy(file.data(), &h, sizeof(h));
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  std::vector<std::uint8_t> file(data, data + size);
  AgreeChecksums(file);
  const std::string path = atp::fuzz::InputFile("model.atp", file.data(), file.size());
  try
  {
    const atp::ModelFile model = atp::ModelFile::Open(path);
    model.Verify();
    const atp::CutIndex index(model);
    atp::ViewPoint view;
    view.Eye[2] = 4 * (model.Header().BoxMax[2] - model.Header().BoxMin[2]) + 1;
    atp::SelectCut(model, view);
    for (int level = 0; level <= int(model.Header().Depth); ++level)
    {
      atp::ExtractCut(model, atp::SelectLevel(model, level));
    }
  }
  catch (const atp::ModelError&)
  {
  }
  catch (const atp::PatchFormatError&)
  {
  }
  return 0;
}
