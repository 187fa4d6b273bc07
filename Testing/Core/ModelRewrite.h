// Models edited behind the writer's back, for tests of what readers and checks refuse: whole
// files read and written, and a model's header and node records rewritten with the checksums
// recomputed as far as a test asks.
#ifndef atpTestModelRewrite_h
#define atpTestModelRewrite_h

#include "atpChecksum.h"
#include "atpModelFormat.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

namespace atp
{
namespace test
{

inline std::vector<std::uint8_t> ReadAll(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
}

inline void WriteAll(const std::string& path, const std::vector<std::uint8_t>& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

enum class Seal
{
  None,       ///< leave every checksum as it was
  HeaderOnly, ///< a node edit shows up as a node section checksum mismatch
  All         ///< only the edit itself is wrong
};

using Edit = std::function<void(ModelHeader&, std::vector<ModelNode>&, std::vector<std::uint8_t>&)>;

/// Rewrites the header and nodes of the model at `path` through `edit`, which may also change
/// raw bytes outside the records, then recomputes the checksums `seal` asks for.
inline void Rewrite(const std::string& path, const Edit& edit, Seal seal)
{
  std::vector<std::uint8_t> raw = ReadAll(path);
  ModelHeader h;
  std::memcpy(&h, raw.data(), sizeof(h));
  const std::size_t nodeOffset = std::size_t(h.NodeSectionOffset);
  std::vector<ModelNode> nodes(std::size_t(h.NodeCount));
  std::memcpy(nodes.data(), raw.data() + nodeOffset, nodes.size() * sizeof(ModelNode));
  edit(h, nodes, raw);
  std::memcpy(raw.data() + nodeOffset, nodes.data(), nodes.size() * sizeof(ModelNode));
  if (seal == Seal::All)
  {
    h.NodeSectionChecksum = Checksum(raw.data() + nodeOffset, nodes.size() * sizeof(ModelNode));
  }
  if (seal != Seal::None)
  {
    h.HeaderChecksum = Checksum(&h, offsetof(ModelHeader, HeaderChecksum));
  }
  std::memcpy(raw.data(), &h, sizeof(h));
  WriteAll(path, raw);
}

} // namespace test
} // namespace atp

#endif
