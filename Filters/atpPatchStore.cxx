#include "atpPatchStore.h"

#include "atpNormalEncoding.h"

#include <cstring>
#include <vector>

namespace atp
{
namespace
{
struct Counts
{
  std::uint32_t Vertices;
  std::uint32_t Triangles;
  std::uint32_t HasColors;
  std::uint32_t HasUses; ///< PatchMesh::InputUses and CornerUses follow the boundary bits
};

/// Patches of fewer vertices store 16-bit indices.
constexpr std::size_t ShortIndexVertices = std::size_t(1) << 16;

template<typename T>
std::uint8_t* Copy(std::uint8_t* to, const T* values, std::size_t count)
{
  if (count > 0)
  {
    std::memcpy(to, values, count * sizeof(T));
  }
  return to + count * sizeof(T);
}

template<typename T>
const std::uint8_t* Take(const std::uint8_t* from, std::size_t count, std::vector<T>& values)
{
  values.resize(count);
  if (count > 0)
  {
    std::memcpy(values.data(), from, count * sizeof(T));
  }
  return from + count * sizeof(T);
}
} // namespace

PatchStore::PatchStore(const std::string& scratchDirectory)
  : File(scratchDirectory)
{
}

// The record: counts, positions, normals as EncodeNormal's 2 x int16 (every normal here was
// decoded from that encoding, and decoding what it encodes gives the same floats: lossless at a
// third of the bytes), colors, indices (16 bits when they fit), boundary bits, input uses.
PatchStore::Handle PatchStore::Put(const PatchMesh& patch)
{
  const std::size_t vertices = patch.VertexCount(), indices = patch.Indices.size();
  const bool shortIndices = vertices <= ShortIndexVertices;
  const Counts counts{ std::uint32_t(vertices), std::uint32_t(patch.TriangleCount()),
    std::uint32_t(patch.HasColors()), std::uint32_t(!patch.InputUses.empty()) };
  std::vector<std::uint8_t> bytes(sizeof(counts) + vertices * (3 * sizeof(float) + 4) +
    patch.Colors.size() + indices * (shortIndices ? 2 : 4) + patch.BoundaryEdges.size() +
    patch.InputUses.size() + patch.CornerUses.size());
  std::uint8_t* at = Copy(bytes.data(), &counts, 1);
  at = Copy(at, patch.Positions.data(), patch.Positions.size());
  std::vector<std::int16_t> normals(2 * vertices);
  for (std::size_t v = 0; v < vertices; ++v)
  {
    EncodeNormal(&patch.Normals[3 * v], &normals[2 * v]);
  }
  at = Copy(at, normals.data(), normals.size());
  at = Copy(at, patch.Colors.data(), patch.Colors.size());
  if (shortIndices)
  {
    const std::vector<std::uint16_t> narrow(patch.Indices.begin(), patch.Indices.end());
    at = Copy(at, narrow.data(), narrow.size());
  }
  else
  {
    at = Copy(at, patch.Indices.data(), indices);
  }
  at = Copy(at, patch.BoundaryEdges.data(), patch.BoundaryEdges.size());
  at = Copy(at, patch.InputUses.data(), patch.InputUses.size());
  Copy(at, patch.CornerUses.data(), patch.CornerUses.size());
  const Handle handle{ End, bytes.size() };
  File.WriteAt(End, bytes.data(), bytes.size());
  End += bytes.size();
  Live += bytes.size();
  Peak = std::max(Peak, Live);
  return handle;
}

void PatchStore::Get(const Handle& handle, PatchMesh& out) const
{
  std::vector<std::uint8_t> bytes(std::size_t(handle.Bytes));
  File.ReadAt(handle.Offset, bytes.data(), bytes.size());
  Counts counts;
  std::memcpy(&counts, bytes.data(), sizeof(counts));
  const std::size_t vertices = counts.Vertices, indices = 3 * std::size_t(counts.Triangles);
  const std::uint8_t* at = bytes.data() + sizeof(counts);
  at = Take(at, 3 * vertices, out.Positions);
  std::vector<std::int16_t> normals;
  at = Take(at, 2 * vertices, normals);
  out.Normals.resize(3 * vertices);
  for (std::size_t v = 0; v < vertices; ++v)
  {
    DecodeNormal(&normals[2 * v], &out.Normals[3 * v]);
  }
  at = Take(at, counts.HasColors ? 4 * vertices : 0, out.Colors);
  if (vertices <= ShortIndexVertices)
  {
    std::vector<std::uint16_t> narrow;
    at = Take(at, indices, narrow);
    out.Indices.assign(narrow.begin(), narrow.end());
  }
  else
  {
    at = Take(at, indices, out.Indices);
  }
  at = Take(at, std::size_t(counts.Triangles), out.BoundaryEdges);
  at = Take(at, counts.HasUses ? vertices : 0, out.InputUses);
  Take(at, counts.HasUses ? indices : 0, out.CornerUses);
}

void PatchStore::Release(const Handle& handle)
{
  File.Release(handle.Offset, handle.Bytes);
  Live -= handle.Bytes;
}

} // namespace atp
