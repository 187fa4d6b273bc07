#include "atpObjMesh.h"

#include "atpBufferedReader.h"
#include "atpInputFile.h"
#include "atpScratchArray.h"
#include "atpTextParsing.h"

#include <algorithm>
#include <vector>

namespace atp
{
namespace
{
enum class LineKind
{
  Vertex,
  Face,
  Other
};

/// What a line declares; `rest` is left holding what follows the keyword.
LineKind Classify(std::string_view line, std::string_view& rest)
{
  // A comment that ends a line is no content either.
  line = WithoutByteOrderMark(line);
  rest = line.substr(0, line.find('#'));
  const std::string_view keyword = NextWord(rest);
  return keyword == "v" ? LineKind::Vertex : (keyword == "f" ? LineKind::Face : LineKind::Other);
}

/// The common extension "v x y z r g b": `rest` (after x, y, z) is exactly three fractions of 1.
bool ParseColor(std::string_view rest, std::uint8_t rgb[3])
{
  for (int k = 0; k < 3; ++k)
  {
    double value;
    if (!ParseReal(NextWord(rest), value))
    {
      return false;
    }
    rgb[k] = ColorByte(value);
  }
  return NextWord(rest).empty();
}

class ObjMesh final : public PolygonMesh
{
public:
  ObjMesh(const std::string& path, const std::string& scratchDirectory)
    : File(path)
    , Reader(this->File, 0)
    , Positions(scratchDirectory, 0)
    , Colors(scratchDirectory, 0)
  {
    this->ReadVertices();
    this->Rewind();
  }

  VertexView Vertices() const override
  {
    VertexView view;
    view.Base = reinterpret_cast<const unsigned char*>(this->Positions.Data());
    view.Count = this->VertexCount;
    view.FileBacked = true;
    if (this->AllColored && this->VertexCount > 0)
    {
      view.Colors = this->Colors.Data();
      view.ColorStride = 3;
      view.ColorComponents = 3;
    }
    return view;
  }

  void Rewind() override
  {
    this->Reader.Seek(0);
    this->VerticesSoFar = 0;
  }

  bool NextBatch(PolygonBatch& batch) override;

private:
  void ReadVertices();
  std::uint32_t Resolve(std::string_view corner) const;

  InputFile File;
  BufferedReader Reader;
  ScratchArray<float> Positions;
  ScratchArray<std::uint8_t> Colors; ///< r, g, b per vertex while every vertex has them
  bool AllColored = true;
  std::uint64_t VertexCount = 0;
  std::uint64_t VerticesSoFar = 0; // 'v' lines before the current line, for relative indices
  std::vector<std::uint32_t> Indices;
  std::vector<std::uint32_t> Sizes;
};

void ObjMesh::ReadVertices()
{
  std::string_view line;
  std::string_view rest;
  while (this->Reader.NextLine(line))
  {
    if (Classify(line, rest) != LineKind::Vertex)
    {
      continue;
    }
    if (this->VertexCount == MaxVertices)
    {
      this->File.FailAtLine(this->Reader.Line(),
        "too many vertices (at most " + std::to_string(MaxVertices) + " are supported)");
    }
    float p[3];
    for (float& x : p)
    {
      const std::string_view word = NextWord(rest);
      double value;
      if (!ParseReal(word, value))
      {
        this->File.FailAtLine(this->Reader.Line(),
          word.empty() ? "a vertex needs three coordinates"
                       : "expected a coordinate, found " + Quoted(word));
      }
      x = ToFloatCoordinate(value);
    }
    if (const char* bad = FirstNonFinite(p))
    {
      this->File.FailAtLine(
        this->Reader.Line(), std::string("non-finite coordinate (") + bad + ")");
    }
    const std::size_t needed = static_cast<std::size_t>(3 * (this->VertexCount + 1));
    if (needed > this->Positions.Size())
    {
      // Doubling keeps the number of remaps logarithmic.
      this->Positions.Resize(std::max<std::size_t>(needed, 2 * this->Positions.Size()));
    }
    std::copy(p, p + 3, &this->Positions[needed - 3]);
    std::uint8_t rgb[3];
    this->AllColored = this->AllColored && ParseColor(rest, rgb);
    if (this->AllColored)
    {
      if (needed > this->Colors.Size())
      {
        this->Colors.Resize(this->Positions.Size());
      }
      std::copy(rgb, rgb + 3, &this->Colors[needed - 3]);
    }
    ++this->VertexCount;
  }
}

std::uint32_t ObjMesh::Resolve(std::string_view corner) const
{
  // A corner is "i", "i/t", "i//n" or "i/t/n": only i matters.
  std::int64_t index;
  const std::size_t length = ParseIntegerPrefix(corner, index);
  if (length == 0 || (length < corner.size() && corner[length] != '/'))
  {
    this->File.FailAtLine(this->Reader.Line(), "bad face corner " + Quoted(corner));
  }
  // Positive indices count from 1 over the whole file, negative ones back from this line.
  const std::int64_t resolved =
    index > 0 ? index - 1 : static_cast<std::int64_t>(this->VerticesSoFar) + index;
  if (index == 0 || resolved < 0 || static_cast<std::uint64_t>(resolved) >= this->VertexCount)
  {
    this->File.FailAtLine(this->Reader.Line(),
      "face index " + std::to_string(index) + " out of range (file has " +
        std::to_string(this->VertexCount) + " vertices" +
        (index < 0 ? ", " + std::to_string(this->VerticesSoFar) + " before this line" : "") + ")");
  }
  return static_cast<std::uint32_t>(resolved);
}

bool ObjMesh::NextBatch(PolygonBatch& batch)
{
  this->Indices.clear();
  this->Sizes.clear();
  std::string_view line;
  std::string_view rest;
  while (this->Sizes.size() < PolygonBatchFaces && this->Reader.NextLine(line))
  {
    const LineKind kind = Classify(line, rest);
    if (kind == LineKind::Vertex)
    {
      ++this->VerticesSoFar;
    }
    else if (kind == LineKind::Face)
    {
      std::uint32_t corners = 0;
      for (std::string_view word = NextWord(rest); !word.empty(); word = NextWord(rest))
      {
        this->Indices.push_back(this->Resolve(word));
        ++corners;
      }
      if (corners < 3)
      {
        this->File.FailAtLine(this->Reader.Line(),
          "a face needs 3 corners or more, this one has " + std::to_string(corners));
      }
      this->Sizes.push_back(corners);
    }
  }
  batch.Indices = this->Indices.data();
  batch.Sizes = this->Sizes.data();
  batch.Count = this->Sizes.size();
  return batch.Count > 0;
}
} // namespace

std::unique_ptr<PolygonMesh> OpenObjMesh(
  const std::string& path, const std::string& scratchDirectory)
{
  return std::make_unique<ObjMesh>(path, scratchDirectory);
}

} // namespace atp
