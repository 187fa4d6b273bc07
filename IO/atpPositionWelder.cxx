#include "atpPositionWelder.h"

#include "atpResidentPages.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace atp
{

namespace
{
/// Large enough that a page's write costs little per record, small enough that a page per
/// bucket or range (at most 1024 of each, two streams per range) holds little memory: 48 MiB at
/// most, at 2^32 corners.
constexpr std::size_t StreamPageBytes = 16 << 10;
/// Position buckets: about this many bytes of corner records each, at most MaxBucketBits bits
/// of hash to choose them.
constexpr std::uint64_t BucketBytes = 16 << 20;
constexpr int MaxBucketBits = 10;
/// Corners gathered at a time in the last phase (2^32 corners make 1024 ranges): the range's
/// first corners and new positions are held in memory (about 7 bytes per corner).
constexpr int RangeBits = 22;
constexpr std::uint32_t NoCorner = 0xFFFFFFFFu; ///< above every corner number (MaxCorners)

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

std::uint64_t PositionHash(const std::uint32_t key[3])
{
  std::uint64_t h = key[0] * 0x9e3779b97f4a7c15ULL;
  h = (h ^ key[1]) * 0xbf58476d1ce4e5b9ULL;
  h = (h ^ key[2]) * 0x94d049bb133111ebULL;
  return h ^ (h >> 31);
}

/// The records of a stream's page (its buffer holds whole records, written as bytes).
template <typename Record>
const Record* RecordsOf(const unsigned char* bytes)
{
  return reinterpret_cast<const Record*>(bytes);
}

/// The first corner of each position in one bucket: open addressing, grown at half full (a soup
/// of unshared corners makes every position new).
class FirstCorners
{
public:
  /// Empties the table for a bucket of about `expected` positions (its memory is reused).
  void Clear(std::size_t expected)
  {
    std::size_t capacity = 64;
    while (capacity < 2 * expected)
    {
      capacity *= 2;
    }
    this->Slots.assign(capacity, Slot{ { 0, 0, 0 }, NoCorner });
    this->Used = 0;
  }

  /// The first corner with the record's position; the record's own when it is the first.
  std::uint32_t FirstOf(const CornerRecord& record, std::uint64_t hash)
  {
    if (2 * (this->Used + 1) > this->Slots.size())
    {
      this->Grow();
    }
    std::size_t mask = this->Slots.size() - 1;
    for (std::size_t i = hash & mask;; i = (i + 1) & mask)
    {
      Slot& slot = this->Slots[i];
      if (slot.First == NoCorner)
      {
        std::memcpy(slot.Key, record.Key, sizeof(slot.Key));
        slot.First = record.Corner;
        ++this->Used;
        return record.Corner;
      }
      if (std::memcmp(slot.Key, record.Key, sizeof(slot.Key)) == 0)
      {
        return slot.First;
      }
    }
  }

private:
  struct Slot
  {
    std::uint32_t Key[3];
    std::uint32_t First;
  };

  void Grow()
  {
    std::vector<Slot> old(2 * this->Slots.size(), Slot{ { 0, 0, 0 }, NoCorner });
    old.swap(this->Slots);
    const std::size_t mask = this->Slots.size() - 1;
    for (const Slot& slot : old)
    {
      if (slot.First == NoCorner)
      {
        continue;
      }
      std::size_t i = PositionHash(slot.Key) & mask;
      while (this->Slots[i].First != NoCorner)
      {
        i = (i + 1) & mask;
      }
      this->Slots[i] = slot;
    }
  }

  std::vector<Slot> Slots;
  std::size_t Used = 0;
};

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
    this->Bits.ReleaseResident(); // read back where the ranks are asked for, mostly nearby
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

PositionWelder::PositionWelder(const std::string& scratchDirectory, std::uint64_t expectedCorners)
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

void PositionWelder::Add(const float p[3])
{
  if (this->CornerCount == MaxCorners)
  {
    throw std::length_error(
      "more than " + std::to_string(MaxCorners) + " triangle corners (not supported)");
  }
  CornerRecord record;
  for (int a = 0; a < 3; ++a)
  {
    const float x = p[a] + 0.0f; // -0 and +0 are the same position
    std::memcpy(&record.Key[a], &x, sizeof(float));
  }
  record.Corner = static_cast<std::uint32_t>(this->CornerCount++);
  const std::uint64_t hash = PositionHash(record.Key);
  this->Buckets.Append(this->BucketBits == 0 ? 0 : hash >> (64 - this->BucketBits), &record);
}

PositionWelder::Mesh PositionWelder::Finish()
{
  const std::uint64_t corners = this->CornerCount;
  const std::size_t ranges = static_cast<std::size_t>((corners + (1u << RangeBits) - 1) >> RangeBits);
  ScratchStreams firsts(this->Directory, ranges, sizeof(FirstRecord));
  ScratchStreams positions(this->Directory, ranges, sizeof(PositionRecord));
  FirstCornerRanks ranks(this->Directory, corners);

  // Each bucket holds every corner of its positions, in the order added: the first one met is
  // the first corner of its position.
  FirstCorners table;
  for (std::size_t bucket = 0; bucket < (std::size_t(1) << this->BucketBits); ++bucket)
  {
    table.Clear(static_cast<std::size_t>(this->Buckets.Records(bucket) / 4));
    this->Buckets.Drain(bucket, [&](const unsigned char* page, std::size_t count) {
      const CornerRecord* records = RecordsOf<CornerRecord>(page);
      for (std::size_t i = 0; i < count; ++i)
      {
        const CornerRecord& record = records[i];
        const std::uint32_t first = table.FirstOf(record, PositionHash(record.Key));
        const std::size_t range = record.Corner >> RangeBits;
        const std::uint32_t offset = record.Corner & ((1u << RangeBits) - 1);
        const FirstRecord vertex{ offset, first };
        firsts.Append(range, &vertex);
        if (first == record.Corner)
        {
          ranks.Set(first);
          PositionRecord position{ offset, { 0, 0, 0 } };
          std::memcpy(position.P, record.Key, sizeof(position.P));
          positions.Append(range, &position);
        }
      }
    });
  }
  table = FirstCorners(); // its memory goes before the gathering

  Mesh mesh(this->Directory);
  mesh.VertexCount = ranks.Count();
  mesh.Indices.Resize(static_cast<std::size_t>(corners));
  mesh.Positions.Resize(static_cast<std::size_t>(3 * mesh.VertexCount));
  std::vector<std::uint32_t> firstOf;
  std::vector<PositionRecord> news;
  std::size_t vertex = 0;
  for (std::size_t range = 0; range < ranges; ++range)
  {
    const std::uint64_t start = std::uint64_t(range) << RangeBits;
    const std::size_t count = static_cast<std::size_t>(std::min<std::uint64_t>(corners - start, 1u << RangeBits));
    firstOf.assign(count, NoCorner);
    firsts.Drain(range, [&](const unsigned char* page, std::size_t records) {
      const FirstRecord* first = RecordsOf<FirstRecord>(page);
      for (std::size_t i = 0; i < records; ++i)
      {
        firstOf[first[i].Offset] = first[i].First;
      }
    });
    std::uint32_t* indices = mesh.Indices.Data() + start;
    for (std::size_t i = 0; i < count; ++i)
    {
      indices[i] = ranks.Rank(firstOf[i]);
    }
    ReleaseResidentPages(indices, count * sizeof(std::uint32_t));

    // A range's new vertices in the order of their first corners: their indices' order.
    news.clear();
    positions.Drain(range, [&](const unsigned char* page, std::size_t records) {
      const PositionRecord* found = RecordsOf<PositionRecord>(page);
      news.insert(news.end(), found, found + records);
    });
    std::sort(news.begin(), news.end(),
      [](const PositionRecord& a, const PositionRecord& b) { return a.Offset < b.Offset; });
    float* out = mesh.Positions.Data() + 3 * vertex;
    for (const PositionRecord& record : news)
    {
      std::memcpy(out, record.P, sizeof(record.P));
      out += 3;
    }
    ReleaseResidentPages(mesh.Positions.Data() + 3 * vertex, news.size() * 3 * sizeof(float));
    vertex += news.size();
  }
  return mesh;
}

} // namespace atp
