#include "atpMergePatches.h"

#include <cstring>

namespace atp
{

namespace
{

std::uint64_t HashPosition(const std::uint32_t bits[3])
{
  std::uint64_t h = bits[0] * 0x9E3779B97F4A7C15ull;
  h ^= (h >> 29) ^ (bits[1] * 0xC2B2AE3D27D4EB4Full);
  h ^= (h >> 31) ^ (bits[2] * 0x165667B19E3779F9ull);
  return h ^ (h >> 32);
}

} // namespace

PatchMesh MergePatches(
  const std::vector<const PatchMesh*>& patches, std::vector<std::uint32_t>* trianglePatch)
{
  std::size_t vertexCount = 0;
  std::size_t triangleCount = 0;
  bool normals = false;
  bool colors = false;
  for (const PatchMesh* p : patches)
  {
    vertexCount += p->VertexCount();
    triangleCount += p->TriangleCount();
    normals = normals || !p->Normals.empty();
    colors = colors || p->HasColors();
  }

  PatchMesh out;
  out.Positions.reserve(3 * vertexCount);
  out.Normals.reserve(normals ? 3 * vertexCount : 0);
  out.Colors.reserve(colors ? 4 * vertexCount : 0);
  out.Indices.reserve(3 * triangleCount);
  out.BoundaryEdges.reserve(triangleCount);

  // Open addressing on the position bits; slots hold output index + 1 (0 is empty). Only
  // lookups touch the table, so its layout cannot influence the output order.
  std::size_t capacity = 16;
  while (capacity < 2 * vertexCount)
  {
    capacity *= 2;
  }
  std::vector<std::uint32_t> slots(capacity, 0);
  std::vector<std::uint32_t> remap;
  if (trianglePatch)
  {
    trianglePatch->clear();
    trianglePatch->reserve(triangleCount);
  }
  for (std::uint32_t source = 0; source < patches.size(); ++source)
  {
    const PatchMesh* p = patches[source];
    const std::size_t n = p->VertexCount();
    remap.resize(n);
    for (std::size_t v = 0; v < n; ++v)
    {
      std::uint32_t bits[3];
      std::memcpy(bits, &p->Positions[3 * v], sizeof(bits));
      std::size_t s = HashPosition(bits) & (capacity - 1);
      for (; slots[s] != 0; s = (s + 1) & (capacity - 1))
      {
        if (std::memcmp(&out.Positions[3 * (slots[s] - 1)], bits, sizeof(bits)) == 0)
        {
          break;
        }
      }
      if (slots[s] == 0)
      {
        slots[s] = std::uint32_t(out.VertexCount() + 1);
        out.Positions.insert(out.Positions.end(), &p->Positions[3 * v], &p->Positions[3 * v] + 3);
        if (normals)
        {
          const float up[3] = { 0, 0, 1 };
          const float* normal = p->Normals.empty() ? up : &p->Normals[3 * v];
          out.Normals.insert(out.Normals.end(), normal, normal + 3);
        }
        if (colors)
        {
          const std::uint8_t white[4] = { 255, 255, 255, 255 };
          const std::uint8_t* color = p->HasColors() ? &p->Colors[4 * v] : white;
          out.Colors.insert(out.Colors.end(), color, color + 4);
        }
      }
      remap[v] = slots[s] - 1;
    }
    for (std::size_t t = 0; t < p->TriangleCount(); ++t)
    {
      const std::uint32_t a = remap[p->Indices[3 * t]];
      const std::uint32_t b = remap[p->Indices[3 * t + 1]];
      const std::uint32_t c = remap[p->Indices[3 * t + 2]];
      if (a == b || b == c || c == a)
      {
        continue;
      }
      out.Indices.insert(out.Indices.end(), { a, b, c });
      out.BoundaryEdges.push_back(t < p->BoundaryEdges.size() ? p->BoundaryEdges[t] : 0);
      if (trianglePatch)
      {
        trianglePatch->push_back(source);
      }
    }
  }
  return out;
}

} // namespace atp
