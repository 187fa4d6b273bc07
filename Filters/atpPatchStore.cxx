#include "atpPatchStore.h"

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
  std::uint32_t Padding;
};

template<typename T>
void Append(std::vector<std::uint8_t>& bytes, const std::vector<T>& values)
{
  const std::size_t at = bytes.size();
  bytes.resize(at + values.size() * sizeof(T));
  if (!values.empty())
  {
    std::memcpy(bytes.data() + at, values.data(), values.size() * sizeof(T));
  }
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

PatchStore::Handle PatchStore::Put(const PatchMesh& patch)
{
  const Counts counts{ std::uint32_t(patch.VertexCount()), std::uint32_t(patch.TriangleCount()),
    std::uint32_t(patch.HasColors()), 0 };
  std::vector<std::uint8_t> bytes(sizeof(counts));
  std::memcpy(bytes.data(), &counts, sizeof(counts));
  Append(bytes, patch.Positions);
  Append(bytes, patch.Normals);
  Append(bytes, patch.Colors);
  Append(bytes, patch.Indices);
  Append(bytes, patch.BoundaryEdges);
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
  const std::uint8_t* at = bytes.data() + sizeof(counts);
  at = Take(at, 3 * std::size_t(counts.Vertices), out.Positions);
  at = Take(at, 3 * std::size_t(counts.Vertices), out.Normals);
  at = Take(at, counts.HasColors ? 4 * std::size_t(counts.Vertices) : 0, out.Colors);
  at = Take(at, 3 * std::size_t(counts.Triangles), out.Indices);
  Take(at, std::size_t(counts.Triangles), out.BoundaryEdges);
}

void PatchStore::Release(const Handle& handle)
{
  File.Release(handle.Offset, handle.Bytes);
  Live -= handle.Bytes;
}

} // namespace atp
