// A .atp model opened for reading (docs/atp-format.md): memory-mapped, never read whole, and
// validated up front in O(nodes) so that a corrupt, truncated or foreign file is a clear error
// rather than a crash or a wrong picture later. Patch bytes are checked lazily (CheckPatch, on
// first decode) or all at once (Verify, for `atp verify`).
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
  /// Memory-maps the file and validates the header, the section layout, the node section's
  /// checksum and the forest's structure. Throws ModelError.
  static ModelFile Open(const std::string& path);

  ModelFile(ModelFile&& other) noexcept;
  ModelFile& operator=(ModelFile&& other) noexcept;
  ModelFile(const ModelFile&) = delete;
  ModelFile& operator=(const ModelFile&) = delete;
  ~ModelFile();

  const ModelHeader& Header() const { return *reinterpret_cast<const ModelHeader*>(Map); }
  std::size_t NodeCount() const { return Count; }
  const ModelNode& Node(std::size_t i) const { return NodeArray[i]; }
  const ModelNode* Nodes() const { return NodeArray; }
  /// The encoded bytes of node i's patch, inside the map (16-byte aligned; Node(i).PatchBytes
  /// of them). Not checked: call CheckPatch before trusting them.
  const std::uint8_t* PatchData(std::size_t i) const { return PatchSection + NodeArray[i].PatchOffset; }
  /// Compares node i's patch with its checksum; throws ModelError naming the node.
  void CheckPatch(std::size_t i) const;
  /// The grid every patch of this model stores its positions on.
  QuantizationGrid PatchGrid() const;
  /// CheckPatch, then decodes node i's patch into `out` (reusing its capacity). Throws
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
  void Validate();
  [[noreturn]] void Throw(const std::string& problem) const;

  std::string FilePath;
  const std::uint8_t* Map = nullptr;
  std::size_t MapBytes = 0;
  const ModelNode* NodeArray = nullptr;
  std::size_t Count = 0;
  const std::uint8_t* PatchSection = nullptr;
};

} // namespace atp

#endif
