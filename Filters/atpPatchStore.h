// Full-precision patches waiting for their parent diamond, in a scratch file: construction keeps
// only the diamonds it is working on in memory, whatever the size of the model.
#ifndef atpPatchStore_h
#define atpPatchStore_h

#include "atpPatchMesh.h"
#include "atpScratchFile.h"
#include "vtkATPFiltersModule.h"

#include <cstdint>
#include <string>

namespace atp
{

class VTKATPFILTERS_EXPORT PatchStore
{
public:
  struct Handle
  {
    std::uint64_t Offset = 0;
    std::uint64_t Bytes = 0;
  };

  explicit PatchStore(const std::string& scratchDirectory);

  /// Appends a patch (one writer thread). Throws std::runtime_error when the disk is full.
  /// Normals are kept as EncodeNormal's 2 x int16: exact for the normals construction holds
  /// (all decoded from that encoding), within 0.004 degrees for any other.
  Handle Put(const PatchMesh& patch);
  /// Reads a patch back; safe from several threads at once.
  void Get(const Handle& handle, PatchMesh& out) const;
  /// Gives the disk blocks of a patch, or of consecutive patches (a Handle spanning them, each
  /// released once), back to the file system: they will not be read again.
  void Release(const Handle& handle);

  std::uint64_t BytesWritten() const { return End; }
  std::uint64_t PeakBytes() const { return Peak; }

private:
  ScratchFile File;
  std::uint64_t End = 0;
  std::uint64_t Live = 0;
  std::uint64_t Peak = 0;
};

} // namespace atp

#endif
