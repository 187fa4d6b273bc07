// Welds a stream of corner positions into an indexed mesh out of core: every distinct position
// (bit for bit, -0 and +0 alike) gets one vertex index, numbered in order of first appearance.
// Resident memory does not grow with the corners up to about 2^30 of them (a bucket, a range and
// a page per stream; the bitmap of first corners, an eighth of a byte per corner, is let go of
// as it is filled and read); the welder takes at most 2^32 - 1. For inputs that are triangle
// soups (STL), whose shared edges and boundary are found on vertex indices.
//
// Corners go to scratch buckets by a hash of their position; each bucket is welded in memory
// (PositionWelder: a corner's vertex is the first corner with its position), then the corners
// go back to scratch by their place in the stream, and are gathered range by range into the
// index array, each first corner counted into its vertex index. Scratch disk, given back as it
// is read: 16 bytes per corner while bucketed, then 8 per corner and 16 per vertex while
// gathered, beside the result (4 per corner and 12 per vertex): about 24 bytes per corner for a
// welded mesh, 40 where no two corners share a position.
#ifndef atpCornerWelder_h
#define atpCornerWelder_h

#include "atpScratchArray.h"
#include "atpScratchFile.h"
#include "vtkATPIOModule.h" // export macro

#include <cstdint>
#include <string>
#include <vector>

namespace atp
{

/// Fixed-size records appended to numbered streams that share one ScratchFile, a page at a time:
/// each stream keeps one page in memory, and reading a stream back gives its pages' blocks back
/// to the file system.
class VTKATPIO_EXPORT ScratchStreams
{
public:
  ScratchStreams(const std::string& directory, std::size_t streams, std::size_t recordBytes);

  void Append(std::size_t stream, const void* record);
  std::uint64_t Records(std::size_t stream) const { return this->Streams[stream].Records; }
  /// Reads stream `stream` back in the order it was written, a page at a time, calling
  /// visit(const unsigned char* records, std::size_t count) for each, and empties it.
  template <typename Visit>
  void Drain(std::size_t stream, Visit visit)
  {
    Stream& s = this->Streams[stream];
    for (const std::uint64_t page : s.Pages)
    {
      this->ReadPage(page);
      visit(this->ReadBuffer.data(), this->PageBytes / this->RecordBytes);
    }
    if (s.Used > 0)
    {
      visit(s.Page.data(), s.Used / this->RecordBytes);
    }
    s = Stream();
  }

private:
  /// Reads the page at `offset` into ReadBuffer and gives its blocks back to the file system.
  void ReadPage(std::uint64_t offset);

  struct Stream
  {
    std::vector<unsigned char> Page; ///< the page being filled (allocated on first use)
    std::size_t Used = 0;            ///< bytes of Page filled
    std::vector<std::uint64_t> Pages; ///< offsets of its full pages in the file
    std::uint64_t Records = 0;
  };

  ScratchFile File;
  std::uint64_t FileEnd = 0;
  std::size_t RecordBytes;
  std::size_t PageBytes;
  std::vector<Stream> Streams;
  std::vector<unsigned char> ReadBuffer;
};

class VTKATPIO_EXPORT CornerWelder
{
public:
  /// Most corners a welder takes: corners are numbered in 32 bits.
  static constexpr std::uint64_t MaxCorners = 0xFFFFFFFFu;

  /// `expectedCorners` (a guess is fine: it only sizes the buckets) is how many Add will see.
  CornerWelder(const std::string& scratchDirectory, std::uint64_t expectedCorners);

  /// The next corner's position (finite). Throws std::length_error past MaxCorners.
  void Add(const float p[3]);
  std::uint64_t Corners() const { return this->CornerCount; }

  struct Mesh
  {
    explicit Mesh(const std::string& directory)
      : Positions(directory)
      , Indices(directory)
    {
    }
    ScratchArray<float> Positions;       ///< x, y, z per vertex, in order of first appearance
    ScratchArray<std::uint32_t> Indices; ///< per corner, in the order added: its vertex
    std::uint64_t VertexCount = 0;
  };

  /// Welds what was added; the arrays' pages are released as they are written.
  Mesh Finish();

private:
  std::string Directory;
  std::uint64_t CornerCount = 0;
  int BucketBits = 0;
  ScratchStreams Buckets;
};

} // namespace atp

#endif
