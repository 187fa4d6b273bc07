// A temporary file for data that does not fit in memory. It never has a name (O_TMPFILE; where
// the file system lacks it, it is unlinked as soon as it is created), so nothing is left behind
// however the process ends (crash, SIGKILL, full disk).
#ifndef atpScratchFile_h
#define atpScratchFile_h

#include "vtkATPIOModule.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace atp
{

class VTKATPIO_EXPORT ScratchFile
{
public:
  /// Creates the file in `directory` (empty: $TMPDIR or /tmp). Throws std::runtime_error naming
  /// the directory when it cannot.
  explicit ScratchFile(const std::string& directory);
  ~ScratchFile();
  ScratchFile(ScratchFile&& other) noexcept;
  ScratchFile& operator=(ScratchFile&& other) noexcept;
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  /// Full writes and reads at an offset; a short write (disk full) or read throws
  /// std::runtime_error with the system's reason.
  void WriteAt(std::uint64_t offset, const void* data, std::size_t bytes);
  void ReadAt(std::uint64_t offset, void* data, std::size_t bytes) const;
  /// Grows or shrinks the file (for memory mapping); reserves the blocks so a full disk is
  /// reported here rather than as SIGBUS on first touch of a mapped page.
  void Resize(std::uint64_t bytes);
  /// Gives the blocks of a range that will not be read again back to the file system (a hole;
  /// best effort: file systems without hole punching keep them).
  void Release(std::uint64_t offset, std::uint64_t bytes);
  int Descriptor() const { return Fd; }

private:
  int Fd = -1;
  std::string Directory;
};

} // namespace atp

#endif
