// A .atp model opened for reading (docs/atp-format.md): the header and nodes read into memory
// and validated up front in O(nodes), the patches memory-mapped and never read whole, so that a
// corrupt, truncated or foreign file is a clear error rather than a crash or a wrong picture
// later. Patch bytes are checked lazily (on decode) or all at once (Verify, for `atp verify`),
// always on a copy taken from the map: a file truncated or rewritten while open is an error,
// not a SIGBUS.
#ifndef atpModelFile_h
#define atpModelFile_h

#include "atpModelFormat.h"
#include "atpPatchMesh.h"
#include "atpQuantizationGrid.h"
#include "vtkATPIOModule.h"

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace atp
{

/// A model file that cannot be used; the message is "<path>: <problem>".
class VTKATPIO_EXPORT ModelError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

class VTKATPIO_EXPORT ModelFile
{
public:
  /// Reads and validates the header, the section layout, the node section's checksum and the
  /// forest's structure, then memory-maps the patches. Counts in the header are checked
  /// against the file's size before anything is sized from them. Throws ModelError.
  static ModelFile Open(const std::string& path);

  ModelFile(ModelFile&& other) noexcept;
  ModelFile& operator=(ModelFile&& other) noexcept;
  ModelFile(const ModelFile&) = delete;
  ModelFile& operator=(const ModelFile&) = delete;
  ~ModelFile();

  const ModelHeader& Header() const { return *reinterpret_cast<const ModelHeader*>(Head.data()); }
  std::size_t NodeCount() const { return Count; }
  const ModelNode& Node(std::size_t i) const { return NodeArray[i]; }
  const ModelNode* Nodes() const { return NodeArray; }
  /// The encoded bytes of node i's patch, inside the map (16-byte aligned; Node(i).PatchBytes
  /// of them). Not checked, and gone if the file shrinks: read patches with ReadPatch; this is
  /// for page-level advice (prefetching) and tests.
  const std::uint8_t* PatchData(std::size_t i) const { return PatchSection + NodeArray[i].PatchOffset; }
  /// Copies node i's patch into `bytes` and compares it with its checksum; throws ModelError
  /// naming the node when it is corrupt, or saying the file shrank when it is no longer there.
  void ReadPatch(std::size_t i, std::vector<std::uint8_t>& bytes) const;
  /// ReadPatch, keeping nothing.
  void CheckPatch(std::size_t i) const;
  /// The grid every patch of this model stores its positions on.
  QuantizationGrid PatchGrid() const;
  /// ReadPatch, then decodes node i's patch into `out` (reusing its capacity). Throws
  /// ModelError or PatchFormatError.
  void DecodePatch(std::size_t i, PatchMesh& out) const;
  /// Drops the whole pages of node i's patch from the process's resident memory: they stay in
  /// the kernel's page cache, so a renderer's memory follows its caches, not the file's size.
  void ReleasePatchPages(std::size_t i) const;
  /// Full verification: the patch section's checksum and every patch's. Returns the problems
  /// found (empty: valid), at most the first 100 patches listed.
  std::vector<std::string> Verify() const;
  const std::string& Path() const { return FilePath; }

private:
  ModelFile() = default;
  void Release();
  void ReadHead(int fd);
  void ValidateHeader();
  void ValidateNodes();
  /// Copies [from, to) of the patch section; false where the file no longer holds it.
  bool CopyPatchSection(std::uint64_t from, std::uint64_t to, std::vector<std::uint8_t>& bytes) const;
  [[noreturn]] void Throw(const std::string& problem) const;

  std::string FilePath;
  /// The header, the node section and the padding up to the patch section, as in the file.
  std::vector<std::uint8_t> Head;
  const std::uint8_t* Map = nullptr;
  std::size_t MapBytes = 0;
  const ModelNode* NodeArray = nullptr;
  std::size_t Count = 0;
  const std::uint8_t* PatchSection = nullptr;
};

} // namespace atp

#endif
