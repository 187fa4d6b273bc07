// Writes a .atp model (docs/atp-format.md) so that a crash, a full disk or a killed process never
// leaves a file that looks valid: everything goes to a temporary file beside the target, which
// replaces the target by an atomic rename only once it is complete and on disk. The temporary
// file has no name until then (O_TMPFILE), so a killed build leaves nothing at all behind.
#ifndef atpModelWriter_h
#define atpModelWriter_h

#include "atpModelFormat.h"
#include "vtkATPIOModule.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace atp
{

class VTKATPIO_EXPORT ModelWriter
{
public:
  /// Creates an unnamed temporary file in the target's directory (a named `path`.partial-XXXXXX
  /// where the file system lacks O_TMPFILE); nothing at `path` changes until Commit. Throws std::runtime_error("cannot write <path>: <reason>").
  ModelWriter(const std::string& path, std::uint64_t nodeCount);
  /// Removes the temporary file unless committed.
  ~ModelWriter();
  ModelWriter(const ModelWriter&) = delete;
  ModelWriter& operator=(const ModelWriter&) = delete;

  /// Nodes in file order, each with its patch: the i-th call holds node i. The writer fills the
  /// node's PatchOffset, PatchBytes, PatchChecksum and zeroes its reserved bytes; nodes and
  /// patches go to the file as they come, so writing needs the same memory for any model. Each
  /// patch starts 16-byte aligned in the file (zero padding between patches). Calling it more
  /// than nodeCount times throws std::logic_error; a failed write throws std::runtime_error and
  /// removes the temporary file.
  void Add(ModelNode node, const void* patch, std::size_t patchBytes);

  /// `header`: the caller fills the model fields (box, lattice, quantization, counts, options,
  /// depth, flags, ErrorScale); the writer fills magic, version, byte order, record sizes,
  /// section offsets and sizes, FileBytes, every checksum, and zeroes the reserved bytes.
  /// Writes what is left, fsyncs, renames over `path` and fsyncs the directory. Fewer than
  /// nodeCount nodes added throws std::logic_error; after a write failure or a successful
  /// Commit the writer is finished and further calls throw std::logic_error.
  void Commit(ModelHeader header);

  /// Where the sections go for a model of `nodeCount` nodes (the one layout of version 1).
  static std::uint64_t NodeSectionOffset();
  static std::uint64_t PatchSectionOffset(std::uint64_t nodeCount);
  static constexpr std::uint64_t PatchAlignment = 16;

private:
  struct SectionHash;

  /// Writes the buffered patches and nodes.
  void Flush();
  void WriteAt(std::uint64_t offset, const void* data, std::size_t bytes);
  /// mkstemp beside the target, for file systems without O_TMPFILE.
  int CreateNamedTemporary();
  /// Links the O_TMPFILE file to a temporary name beside the target.
  void NameAnonymousFile();
  /// Removes the temporary file and throws "cannot write <path>: <strerror(err)>".
  [[noreturn]] void Fail(int err);
  void RequireOpen() const;

  std::string Path;
  std::string TempPath; ///< empty while the file has no name
  int Fd = -1;
  bool Finished = false;
  std::uint64_t NodeCount = 0;
  std::uint64_t PatchStart = 0;   ///< file offset of the patch section
  std::uint64_t PatchEnd = 0;     ///< bytes of the patch section so far, padding included
  std::uint64_t WrittenEnd = 0;   ///< bytes of the patch section already in the file
  std::vector<std::uint8_t> Buffer;
  std::uint64_t NodesAdded = 0;
  std::vector<ModelNode> NodeBuffer; ///< the nodes after the first NodesAdded - size() ones
  std::unique_ptr<SectionHash> PatchHash, NodeHash;
};

} // namespace atp

#endif
