#include "atpRenderPatch.h"

#include <cmath>
#include <cstring>

namespace atp
{

RenderPatch MakeRenderPatch(const PatchMesh& mesh, std::uint32_t node)
{
  RenderPatch patch;
  patch.Node = node;
  patch.VertexCount = std::uint32_t(mesh.VertexCount());
  patch.TriangleCount = std::uint32_t(mesh.TriangleCount());
  patch.HasColors = mesh.HasColors();
  patch.ShortIndices = patch.VertexCount <= 65536;
  const std::size_t stride = patch.Stride();
  patch.Vertices.resize(stride * patch.VertexCount);
  for (std::size_t v = 0; v < patch.VertexCount; ++v)
  {
    std::uint8_t* out = &patch.Vertices[stride * v];
    std::memcpy(out + RenderPatchPositionOffset, &mesh.Positions[3 * v], 12);
    std::int16_t normal[4] = { 0, 0, 0, 0 };
    for (int a = 0; a < 3; ++a)
    {
      normal[a] = std::int16_t(std::lround(mesh.Normals[3 * v + a] * 32767.0f));
    }
    std::memcpy(out + RenderPatchNormalOffset, normal, 8);
    if (patch.HasColors)
    {
      std::memcpy(out + RenderPatchColorOffset, &mesh.Colors[4 * v], 4);
    }
  }
  if (mesh.Indices.empty())
  {
    return patch; // an empty patch: nothing to copy (and no buffers to copy from)
  }
  if (patch.ShortIndices)
  {
    std::vector<std::uint16_t> shorts(mesh.Indices.begin(), mesh.Indices.end());
    patch.Indices.resize(2 * shorts.size());
    std::memcpy(patch.Indices.data(), shorts.data(), patch.Indices.size());
  }
  else
  {
    patch.Indices.resize(4 * mesh.Indices.size());
    std::memcpy(patch.Indices.data(), mesh.Indices.data(), patch.Indices.size());
  }
  return patch;
}

} // namespace atp
