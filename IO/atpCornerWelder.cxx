#include "atpCornerWelder.h"

#include "atpPositionWelder.h"
#include "atpResidentPages.h"

#include <algorithm>
#include <cstring>
#include <memory>
#include <stdexcept>

namespace atp
{

namespace
{
/// Large enough that a page's write costs little per record, small enough that a page per
/// bucket or range (at most 1024 of each, two streams per range) holds little memory: 32 MiB at
/// most, at 2^32 corners.
constexpr std::size_t StreamPageBytes = 16 << 10;
/// Position buckets: about this many bytes of corner records each (a bucket's PositionWelder
/// holds about twice that), at most MaxBucketBits bits of hash to choose them: past 2^30
/// corners, buckets grow.
constexpr std::uint64_t BucketBytes = 16 << 20;
constexpr int MaxBucketBits = 10;
/// Corners gathered at a time in the last phase (2^32 corners make 1024 ranges): the range's
/// slices of the index and position arrays are resident until it is done (about 6 bytes per
/// corner).
constexpr int RangeBits = 22;

struct CornerRecord
{
  std::uint32_t Key[3]; ///< the position's bits, -0 as +0
  std::uint32_t Corner;
};
struct FirstRecord
{
  std::uint32_t Offset; ///< the corner, from its range's start
  std::uint32_t First;  ///< the first corner with its position: the vertex
};
struct PositionRecord
{
  std::uint32_t Offset; ///< a first corner, from its range's start
  float P[3];
};

/// The records of a stream's page (its buffer holds whole records, written as bytes).
template <typename Record>
const Record* RecordsOf(const unsigned char* bytes)
{
  return reinterpret_cast<const Record*>(bytes);
}

/// Which corners are first corners, and how many come before any corner: its vertex index
/// when it is one.
class FirstCornerRanks
{
public:
  FirstCornerRanks(const std::string& directory, std::uint64_t corners)
    : Bits(directory, static_cast<std::size_t>((corners + 63) / 64))
  {
  }

  void Set(std::uint32_t corner) { this->Bits[corner >> 6] |= std::uint64_t(1) << (corner & 63); }
  /// Lets the bitmap's pages leave the process (they come back from the scratch file).
  void ReleaseResident() const { this->Bits.ReleaseResident(); }

  /// Counts the bits once all are set; returns how many there are.
  std::uint64_t Count()
  {
    const std::size_t words = this->Bits.Size();
    this->BlockStarts.resize((words + 7) / 8);
    std::uint64_t count = 0;
    for (std::size_t w = 0; w < words; ++w)
    {
      if (w % 8 == 0)
      {
        this->BlockStarts[w / 8] = static_cast<std::uint32_t>(count);
      }
      count += static_cast<std::uint64_t>(__builtin_popcountll(this->Bits[w]));
    }
    this->Bits.ReleaseResident();
    return count;
  }

  std::uint32_t Rank(std::uint32_t corner) const
  {
    const std::size_t word = corner >> 6;
    std::uint32_t rank = this->BlockStarts[word / 8];
    for (std::size_t w = word & ~std::size_t(7); w < word; ++w)
    {
      rank += static_cast<std::uint32_t>(__builtin_popcountll(this->Bits[w]));
    }
    const std::uint64_t below = (std::uint64_t(1) << (corner & 63)) - 1;
    return rank + static_cast<std::uint32_t>(__builtin_popcountll(this->Bits[word] & below));
  }

private:
  ScratchArray<std::uint64_t> Bits;
  std::vector<std::uint32_t> BlockStarts; ///< bits set before each block of 8 words
};
} // namespace

ScratchStreams::ScratchStreams(const std::string& directory, std::size_t streams, std::size_t recordBytes)
  : File(directory)
  , RecordBytes(recordBytes)
  , PageBytes(StreamPageBytes / recordBytes * recordBytes)
  , Streams(streams)
{
}

void ScratchStreams::Append(std::size_t stream, const void* record)
{
  Stream& s = this->Streams[stream];
  if (s.Page.empty())
  {
    s.Page.resize(this->PageBytes);
  }
  std::memcpy(s.Page.data() + s.Used, record, this->RecordBytes);
  s.Used += this->RecordBytes;
  ++s.Records;
  if (s.Used == this->PageBytes)
  {
    this->File.WriteAt(this->FileEnd, s.Page.data(), this->PageBytes);
    s.Pages.push_back(this->FileEnd);
    this->FileEnd += this->PageBytes;
    s.Used = 0;
  }
}

void ScratchStreams::ReadPage(std::uint64_t offset)
{
  this->ReadBuffer.resize(this->PageBytes);
  this->File.ReadAt(offset, this->ReadBuffer.data(), this->PageBytes);
  this->File.Release(offset, this->PageBytes);
}

CornerWelder::CornerWelder(const std::string& scratchDirectory, std::uint64_t expectedCorners)
  : Directory(scratchDirectory)
  , BucketBits([expectedCorners] {
    int bits = 0;
    while (bits < MaxBucketBits && (expectedCorners * sizeof(CornerRecord) >> bits) > BucketBytes)
    {
      ++bits;
    }
    return bits;
  }())
  , Buckets(scratchDirectory, std::size_t(1) << BucketBits, sizeof(CornerRecord))
{
}

void CornerWelder::Add(const float p[3])
{
  if (this->CornerCount == MaxCorners)
  {
    throw std::length_error(
      "more than " + std::to_string(MaxCorners) + " triangle corners (not supported)");
  }
  CornerRecord record;
  PositionBits(p, record.Key);
  record.Corner = static_cast<std::uint32_t>(this->CornerCount++);
  const std::uint64_t hash = PositionHash(record.Key);
  this->Buckets.Append(this->BucketBits == 0 ? 0 : hash >> (64 - this->BucketBits), &record);
}

CornerWelder::Mesh CornerWelder::Finish()
{
  const std::uint64_t corners = this->CornerCount;
  const std::size_t ranges = static_cast<std::size_t>((corners + (1u << RangeBits) - 1) >> RangeBits);
  ScratchStreams firsts(this->Directory, ranges, sizeof(FirstRecord));
  ScratchStreams positions(this->Directory, ranges, sizeof(PositionRecord));
  FirstCornerRanks ranks(this->Directory, corners);

  // Each bucket holds every corner of its positions, in the order added: the first one met at
  // a position is its first corner.
  std::unique_ptr<float[]> bucketPositions; // untouched beyond what the welder writes
  std::size_t bucketRoom = 0;
  std::vector<std::uint32_t> firstCorners; // per position of the bucket
  PositionWelder welder(0, nullptr);
  for (std::size_t bucket = 0; bucket < (std::size_t(1) << this->BucketBits); ++bucket)
  {
    const std::size_t count = static_cast<std::size_t>(this->Buckets.Records(bucket));
    if (count > bucketRoom)
    {
      bucketPositions.reset(new float[3 * count]);
      bucketRoom = count;
    }
    welder.Reset(count, bucketPositions.get());
    firstCorners.clear();
    this->Buckets.Drain(bucket, [&](const unsigned char* page, std::size_t records) {
      const CornerRecord* corners = RecordsOf<CornerRecord>(page);
      for (std::size_t i = 0; i < records; ++i)
      {
        const CornerRecord& record = corners[i];
        float p[3];
        std::memcpy(p, record.Key, sizeof(p));
        bool added = false;
        const std::uint32_t position = welder.Weld(p, added);
        if (added)
        {
          firstCorners.push_back(record.Corner);
        }
        const std::uint32_t first = firstCorners[position];
        const std::size_t range = record.Corner >> RangeBits;
        const std::uint32_t offset = record.Corner & ((1u << RangeBits) - 1);
        const FirstRecord vertex{ offset, first };
        firsts.Append(range, &vertex);
        if (added)
        {
          ranks.Set(first);
          const PositionRecord position{ offset, { p[0], p[1], p[2] } };
          positions.Append(range, &position);
        }
      }
    });
    ranks.ReleaseResident(); // set at random: the next bucket's bits lie anywhere
  }
  bucketPositions.reset();
  welder = PositionWelder(0, nullptr); // its table goes before the gathering

  Mesh mesh(this->Directory);
  mesh.VertexCount = ranks.Count();
  mesh.Indices.Resize(static_cast<std::size_t>(corners));
  mesh.Positions.Resize(static_cast<std::size_t>(3 * mesh.VertexCount));
  for (std::size_t range = 0; range < ranges; ++range)
  {
    // Each corner of the range has one record; each new position, its first corner's.
    const std::uint64_t start = std::uint64_t(range) << RangeBits;
    const std::size_t count = static_cast<std::size_t>(std::min<std::uint64_t>(corners - start, 1u << RangeBits));
    if (firsts.Records(range) != count)
    {
      throw std::logic_error("CornerWelder: a corner went missing between the phases");
    }
    std::uint32_t* indices = mesh.Indices.Data() + start;
    firsts.Drain(range, [&](const unsigned char* page, std::size_t records) {
      const FirstRecord* first = RecordsOf<FirstRecord>(page);
      for (std::size_t i = 0; i < records; ++i)
      {
        indices[first[i].Offset] = ranks.Rank(first[i].First);
      }
    });
    ReleaseResidentPages(indices, count * sizeof(std::uint32_t));
    // The range's new vertices are numbered in a row, from the first corners before it.
    const std::size_t firstVertex = ranks.Rank(static_cast<std::uint32_t>(start));
    const std::size_t newVertices = static_cast<std::size_t>(positions.Records(range));
    positions.Drain(range, [&](const unsigned char* page, std::size_t records) {
      const PositionRecord* found = RecordsOf<PositionRecord>(page);
      for (std::size_t i = 0; i < records; ++i)
      {
        const std::uint32_t vertex = ranks.Rank(static_cast<std::uint32_t>(start + found[i].Offset));
        std::memcpy(mesh.Positions.Data() + 3 * std::size_t(vertex), found[i].P, sizeof(found[i].P));
      }
    });
    ReleaseResidentPages(mesh.Positions.Data() + 3 * firstVertex, newVertices * 3 * sizeof(float));
    ranks.ReleaseResident(); // a range's first corners lie mostly in it, some anywhere before
  }
  return mesh;
}

} // namespace atp
