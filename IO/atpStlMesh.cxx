#include "atpStlMesh.h"

#include "atpBufferedReader.h"
#include "atpInMemoryMesh.h"
#include "atpInputFile.h"
#include "atpTextParsing.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <unordered_map>

namespace atp
{
namespace
{
constexpr std::uint64_t HeaderBytes = 84; // 80-byte header, uint32 triangle count
constexpr std::uint64_t RecordBytes = 50; // normal, 3 corners, uint16 attribute

/// Gives each distinct position one vertex index.
class Welder
{
public:
  Welder(const InputFile& file, InMemoryMesh& mesh)
    : File(file)
    , Mesh(mesh)
  {
  }

  std::uint32_t Add(const float p[3])
  {
    Key key;
    for (int a = 0; a < 3; ++a)
    {
      const float x = p[a] + 0.0f; // -0 and +0 are the same position
      std::memcpy(&key[a], &x, sizeof(float));
    }
    if (this->Index.size() == MaxVertices)
    {
      this->File.Fail(
        "too many distinct vertices (at most " + std::to_string(MaxVertices) + " are supported)");
    }
    auto inserted = this->Index.try_emplace(key, static_cast<std::uint32_t>(this->Index.size()));
    if (inserted.second)
    {
      this->Mesh.Positions.insert(this->Mesh.Positions.end(), p, p + 3);
    }
    return inserted.first->second;
  }

private:
  using Key = std::array<std::uint32_t, 3>;
  struct KeyHash
  {
    std::size_t operator()(const Key& k) const
    {
      std::uint64_t h = k[0] * 0x9e3779b97f4a7c15ULL;
      h = (h ^ k[1]) * 0xbf58476d1ce4e5b9ULL;
      h = (h ^ k[2]) * 0x94d049bb133111ebULL;
      return static_cast<std::size_t>(h ^ (h >> 31));
    }
  };

  const InputFile& File;
  InMemoryMesh& Mesh;
  std::unordered_map<Key, std::uint32_t, KeyHash> Index;
};

/// ASCII STL starts with "solid" and is text; a binary header may start with "solid" too, but
/// its count and float records soon contain bytes that text never does.
bool LooksLikeAscii(const InputFile& file)
{
  char head[512];
  const std::size_t n = file.ReadAt(0, head, sizeof(head));
  if (n < 5 || std::memcmp(head, "solid", 5) != 0)
  {
    return false;
  }
  return std::none_of(head, head + n,
    [](char c)
    {
      const unsigned char u = static_cast<unsigned char>(c);
      return u == 0 || (u < 32 && u != '\n' && u != '\r' && u != '\t' && u != '\f' && u != '\v');
    });
}

void ReadBinary(const InputFile& file, std::uint64_t count, InMemoryMesh& mesh)
{
  Welder welder(file, mesh);
  BufferedReader reader(file, HeaderBytes);
  mesh.Indices.reserve(static_cast<std::size_t>(3 * count));
  mesh.Sizes.assign(static_cast<std::size_t>(count), 3);
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
      mesh.Indices.push_back(welder.Add(p));
    }
  }
}

void ReadAscii(const InputFile& file, InMemoryMesh& mesh)
{
  Welder welder(file, mesh);
  BufferedReader reader(file, 0);
  std::string_view token;
  std::vector<std::uint32_t> facet; // corners of the facet being read
  bool inLoop = false;
  while (reader.NextToken(token))
  {
    if (token == "solid" || token == "endsolid")
    {
      reader.NextLine(token); // the rest of the line is a name
    }
    else if (token == "outer")
    {
      facet.clear();
      inLoop = true;
    }
    else if (token == "vertex")
    {
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
            reader.Line(), "expected a coordinate, found '" + std::string(token) + "'");
        }
        x = ToFloatCoordinate(value);
      }
      if (const char* bad = FirstNonFinite(p))
      {
        file.FailAtLine(reader.Line(), std::string("non-finite coordinate (") + bad + ")");
      }
      facet.push_back(welder.Add(p));
    }
    else if (token == "endloop")
    {
      mesh.Indices.insert(mesh.Indices.end(), facet.begin(), facet.end());
      mesh.Sizes.push_back(static_cast<std::uint32_t>(facet.size()));
      inLoop = false;
    }
  }
  if (inLoop)
  {
    file.Fail("truncated: the file ends inside a facet");
  }
}
} // namespace

std::unique_ptr<PolygonMesh> OpenStlMesh(const std::string& path)
{
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "binary STL is read in place");
  InputFile file(path);
  auto mesh = std::make_unique<InMemoryMesh>();
  std::uint32_t count = 0;
  const bool hasCount = file.Size() >= HeaderBytes && file.ReadAt(80, &count, 4) == 4;
  // The exact size identifies a binary STL, even one whose header starts with "solid".
  if (hasCount && file.Size() == HeaderBytes + RecordBytes * count)
  {
    ReadBinary(file, count, *mesh);
  }
  else if (LooksLikeAscii(file))
  {
    ReadAscii(file, *mesh);
  }
  else if (hasCount)
  {
    file.Fail("truncated or corrupt binary STL: the header claims " + std::to_string(count) +
      " triangles (" + std::to_string(HeaderBytes + RecordBytes * count) +
      " bytes) but the file has " + std::to_string(file.Size()) + " bytes");
  }
  else
  {
    file.Fail("not an STL file: neither ASCII ('solid ...') nor long enough for a binary header");
  }
  return mesh;
}

} // namespace atp
