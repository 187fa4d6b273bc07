#include "atpMergePatches.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace atp
{

PatchMesh MergePatches(
  const std::vector<const PatchMesh*>& patches, std::vector<std::uint32_t>* trianglePatch)
{
  std::size_t vertexCount = 0;
  std::size_t triangleCount = 0;
  bool normals = false;
  bool colors = false;
  bool uses = false;
  for (const PatchMesh* p : patches)
  {
    uses = uses || !p->InputUses.empty();
    vertexCount += p->VertexCount();
    triangleCount += p->TriangleCount();
    normals = normals || !p->Normals.empty();
    colors = colors || p->HasColors();
  }

  // Sized for the most there can be, written in place, trimmed at the end.
  PatchMesh out;
  out.Positions.resize(3 * vertexCount);
  out.Normals.resize(normals ? 3 * vertexCount : 0);
  out.Colors.resize(colors ? 4 * vertexCount : 0);
  out.Indices.resize(3 * triangleCount);
  out.BoundaryEdges.resize(triangleCount);
  out.InputUses.assign(uses ? vertexCount : 0, 0);
  out.CornerUses.resize(uses ? 3 * triangleCount : 0);
  std::size_t triangles = 0;
  PositionWelder welder(vertexCount, out.Positions.data());
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
      bool added = false;
      const std::uint32_t w = welder.Weld(&p->Positions[3 * v], added);
      if (added && normals)
      {
        const float up[3] = { 0, 0, 1 };
        std::copy_n(p->Normals.empty() ? up : &p->Normals[3 * v], 3, &out.Normals[3 * std::size_t(w)]);
      }
      if (added && colors)
      {
        const std::uint8_t white[4] = { 255, 255, 255, 255 };
        std::copy_n(p->HasColors() ? &p->Colors[4 * v] : white, 4, &out.Colors[4 * std::size_t(w)]);
      }
      if (!p->InputUses.empty())
      {
        out.InputUses[w] = std::max(out.InputUses[w], p->InputUses[v]);
      }
      remap[v] = w;
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
      out.Indices[3 * triangles] = a;
      out.Indices[3 * triangles + 1] = b;
      out.Indices[3 * triangles + 2] = c;
      for (int k = 0; k < 3 && uses; ++k)
      {
        // A patch without counts stands for nothing: its vertices' counts fall short.
        out.CornerUses[3 * triangles + std::size_t(k)] = p->CornerUses.empty() ? 0 : p->CornerUses[3 * t + std::size_t(k)];
      }
      out.BoundaryEdges[triangles++] = t < p->BoundaryEdges.size() ? p->BoundaryEdges[t] : 0;
      if (trianglePatch)
      {
        trianglePatch->push_back(source);
      }
    }
  }
  const std::size_t vertices = welder.Count();
  out.Positions.resize(3 * vertices);
  out.Normals.resize(normals ? 3 * vertices : 0);
  out.Colors.resize(colors ? 4 * vertices : 0);
  out.InputUses.resize(uses ? vertices : 0);
  out.CornerUses.resize(uses ? 3 * triangles : 0);
  out.Indices.resize(3 * triangles);
  out.BoundaryEdges.resize(triangles);
  return out;
}

} // namespace atp
