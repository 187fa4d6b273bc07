#include "atpStlMesh.h"

#include "atpBufferedReader.h"
#include "atpInputFile.h"
#include "atpCornerWelder.h"
#include "atpResidentPages.h"
#include "atpScratchArray.h"
#include "atpTextParsing.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace atp
{
namespace
{
constexpr std::uint64_t HeaderBytes = 84; // 80-byte header, uint32 triangle count
constexpr std::uint64_t RecordBytes = 50; // normal, 3 corners, uint16 attribute
/// The fewest bytes an ASCII corner takes ("vertex 0 0 0" and its share of the facet's lines):
/// sizes the welder's buckets from the file's size.
constexpr std::uint64_t LeastAsciiCornerBytes = 20;
/// Facet sizes written between releases of the sizes' pages (4 MiB of them).
constexpr std::size_t SizesReleaseInterval = std::size_t(1) << 20;

/// The welded soup, in scratch arrays whose pages leave the process as the faces stream by.
class StlMesh final : public PolygonMesh
{
public:
  StlMesh(CornerWelder::Mesh welded, std::uint64_t faces, ScratchArray<std::uint32_t> sizes)
    : Welded(std::move(welded))
    , Faces(faces)
    , Sizes(std::move(sizes))
  {
    if (this->AllTriangles())
    {
      this->Threes.assign(PolygonBatchFaces, 3);
    }
  }

  VertexView Vertices() const override
  {
    VertexView view;
    view.Base = reinterpret_cast<const unsigned char*>(this->Welded.Positions.Data());
    view.Count = this->Welded.VertexCount;
    view.FileBacked = true;
    return view;
  }

  void Rewind() override
  {
    this->ReleaseBatch();
    this->NextFace = 0;
    this->NextCorner = 0;
  }

  bool NextBatch(PolygonBatch& batch) override
  {
    this->ReleaseBatch();
    if (this->NextFace == this->Faces)
    {
      return false;
    }
    const std::size_t count =
      static_cast<std::size_t>(std::min<std::uint64_t>(PolygonBatchFaces, this->Faces - this->NextFace));
    batch.Indices = this->Welded.Indices.Data() + this->NextCorner;
    batch.Sizes = this->AllTriangles() ? this->Threes.data() : this->Sizes.Data() + this->NextFace;
    batch.Count = count;
    std::uint64_t corners = 3 * std::uint64_t(count);
    if (!this->AllTriangles())
    {
      corners = std::accumulate(batch.Sizes, batch.Sizes + count, std::uint64_t(0));
    }
    this->Batch = batch;
    this->BatchCorners = corners;
    this->NextFace += count;
    this->NextCorner += corners;
    return true;
  }

private:
  bool AllTriangles() const { return this->Sizes.Size() == 0; }
  /// The last batch handed out is no longer valid: its pages may leave the process.
  void ReleaseBatch()
  {
    if (this->Batch.Count == 0)
    {
      return;
    }
    ReleaseResidentPages(this->Batch.Indices, this->BatchCorners * sizeof(std::uint32_t));
    if (!this->AllTriangles())
    {
      ReleaseResidentPages(this->Batch.Sizes, this->Batch.Count * sizeof(std::uint32_t));
    }
    this->Batch = PolygonBatch();
  }

  CornerWelder::Mesh Welded;
  std::uint64_t Faces;
  ScratchArray<std::uint32_t> Sizes; ///< corners per facet; empty when all are triangles
  std::vector<std::uint32_t> Threes; ///< a batch's sizes when all are triangles
  std::uint64_t NextFace = 0;
  std::uint64_t NextCorner = 0;
  PolygonBatch Batch;
  std::uint64_t BatchCorners = 0;
};

/// Adds a corner to the welder; its limit becomes the file's error.
void AddCorner(const InputFile& file, CornerWelder& welder, const float p[3])
{
  try
  {
    welder.Add(p);
  }
  catch (const std::length_error& e)
  {
    file.Fail(e.what());
  }
}

/// An ASCII STL keyword, in any case: the format's are lowercase, but some writers use capitals.
bool IsKeyword(std::string_view token, std::string_view keyword)
{
  return token.size() == keyword.size() &&
    std::equal(token.begin(), token.end(), keyword.begin(),
      [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
}

/// ASCII STL starts with "solid" (in any case) and is text; a binary header may start with "solid" too, but
/// its count and float records soon contain bytes that text never does.
bool LooksLikeAscii(const InputFile& file)
{
  char buffer[512];
  const std::string_view head =
    WithoutByteOrderMark(std::string_view(buffer, file.ReadAt(0, buffer, sizeof(buffer))));
  if (head.size() < 5 || !IsKeyword(head.substr(0, 5), "solid"))
  {
    return false;
  }
  return std::none_of(head.begin(), head.end(),
    [](char c)
    {
      const unsigned char u = static_cast<unsigned char>(c);
      return u == 0 || (u < 32 && u != '\n' && u != '\r' && u != '\t' && u != '\f' && u != '\v');
    });
}

std::unique_ptr<PolygonMesh> ReadBinary(const InputFile& file, std::uint64_t count, const std::string& scratch)
{
  CornerWelder welder(scratch, 3 * count);
  // The welder numbers corners in 32 bits; past that, say so before reading gigabytes.
  if (3 * count > CornerWelder::MaxCorners)
  {
    file.Fail("holds " + std::to_string(count) + " triangles; at most " +
      std::to_string(CornerWelder::MaxCorners / 3) + " are supported");
  }
  BufferedReader reader(file, HeaderBytes);
  for (std::uint64_t t = 0; t < count; ++t)
  {
    const unsigned char* record = reader.Take(RecordBytes); // size checked: never null
    for (int c = 0; c < 3; ++c)
    {
      float p[3];
      std::memcpy(p, record + 12 * (c + 1), sizeof(p)); // STL is little-endian, as is the host
      if (const char* bad = FirstNonFinite(p))
      {
        file.Fail("triangle " + std::to_string(t) + " has a non-finite coordinate (" + bad + ")");
      }
      AddCorner(file, welder, p);
    }
  }
  return std::make_unique<StlMesh>(welder.Finish(), count, ScratchArray<std::uint32_t>(scratch));
}

std::unique_ptr<PolygonMesh> ReadAscii(const InputFile& file, const std::string& scratch)
{
  CornerWelder welder(scratch, file.Size() / LeastAsciiCornerBytes);
  ScratchArray<std::uint32_t> sizes(scratch);
  std::uint64_t facets = 0;
  bool allTriangles = true;
  BufferedReader reader(file, 0);
  std::string_view token;
  std::uint32_t corners = 0; // of the facet being read
  bool inLoop = false;
  for (bool first = true; reader.NextToken(token); first = false)
  {
    token = first ? WithoutByteOrderMark(token) : token;
    if (IsKeyword(token, "solid") || IsKeyword(token, "endsolid"))
    {
      reader.NextLine(token); // the rest of the line is a name
    }
    else if (IsKeyword(token, "facet"))
    {
      // "facet normal nx ny nz": the normal is not used (the builder sums its own).
      if (!reader.NextToken(token) || !IsKeyword(token, "normal"))
      {
        file.FailAtLine(reader.Line(), "expected 'normal' after 'facet'");
      }
      for (int k = 0; k < 3; ++k)
      {
        double value;
        if (!reader.NextToken(token) || !ParseReal(token, value))
        {
          file.FailAtLine(reader.Line(), "a facet normal needs three numbers");
        }
      }
    }
    else if (IsKeyword(token, "endfacet"))
    {
    }
    else if (IsKeyword(token, "outer"))
    {
      if (inLoop)
      {
        file.FailAtLine(reader.Line(), "'outer loop' inside a loop (no 'endloop' before it)");
      }
      if (!reader.NextToken(token) || !IsKeyword(token, "loop"))
      {
        file.FailAtLine(reader.Line(), "expected 'loop' after 'outer'");
      }
      corners = 0;
      inLoop = true;
    }
    else if (IsKeyword(token, "vertex"))
    {
      if (!inLoop)
      {
        file.FailAtLine(reader.Line(), "a vertex outside 'outer loop' ... 'endloop'");
      }
      float p[3];
      for (float& x : p)
      {
        double value;
        if (!reader.NextToken(token))
        {
          file.Fail("truncated: the file ends inside a vertex");
        }
        if (!ParseReal(token, value))
        {
          file.FailAtLine(
            reader.Line(), "expected a coordinate, found " + Quoted(token));
        }
        x = ToFloatCoordinate(value);
      }
      if (const char* bad = FirstNonFinite(p))
      {
        file.FailAtLine(reader.Line(), std::string("non-finite coordinate (") + bad + ")");
      }
      AddCorner(file, welder, p);
      ++corners;
    }
    else if (IsKeyword(token, "endloop"))
    {
      if (!inLoop)
      {
        file.FailAtLine(reader.Line(), "'endloop' without 'outer loop'");
      }
      // Sizes are kept only once a facet is not a triangle (STL's are, by its definition).
      if (allTriangles && corners != 3)
      {
        allTriangles = false;
        sizes.Assign(static_cast<std::size_t>(facets), 3);
      }
      if (!allTriangles)
      {
        sizes.PushBack(corners);
        if (sizes.Size() % SizesReleaseInterval == 0)
        {
          sizes.ReleaseResident(); // written once, read when the faces stream by
        }
      }
      ++facets;
      inLoop = false;
    }
    else
    {
      file.FailAtLine(reader.Line(), "unexpected " + Quoted(token));
    }
  }
  if (inLoop)
  {
    file.Fail("truncated: the file ends inside a facet");
  }
  return std::make_unique<StlMesh>(welder.Finish(), facets, std::move(sizes));
}
} // namespace

std::unique_ptr<PolygonMesh> OpenStlMesh(const std::string& path, const std::string& scratchDirectory)
{
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "binary STL is read in place");
  InputFile file(path);
  std::uint32_t count = 0;
  const bool hasCount = file.Size() >= HeaderBytes && file.ReadAt(80, &count, 4) == 4;
  // The exact size identifies a binary STL, even one whose header starts with "solid".
  if (hasCount && file.Size() == HeaderBytes + RecordBytes * count)
  {
    return ReadBinary(file, count, scratchDirectory);
  }
  if (LooksLikeAscii(file))
  {
    return ReadAscii(file, scratchDirectory);
  }
  if (hasCount)
  {
    file.Fail("truncated or corrupt binary STL: the header claims " + std::to_string(count) +
      " triangles (" + std::to_string(HeaderBytes + RecordBytes * count) +
      " bytes) but the file has " + std::to_string(file.Size()) + " bytes");
  }
  file.Fail("not an STL file: neither ASCII ('solid ...') nor long enough for a binary header");
}

} // namespace atp
