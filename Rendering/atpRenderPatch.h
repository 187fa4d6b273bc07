// A patch laid out for the GPU: what a decode thread prepares so that the render thread only
// copies bytes into buffer objects. Plain C++: no VTK, no OpenGL.
//
// Vertices are interleaved, RenderPatchStride bytes each: position as 3 float32 (model
// coordinates), normal as 4 int16 normalized (x, y, z, 0), and with colors RGBA as 4 uint8.
// Indices are uint16 when the patch has at most 65536 vertices (halving index bandwidth and
// cache bytes), uint32 otherwise.
#ifndef atpRenderPatch_h
#define atpRenderPatch_h

#include "atpPatchMesh.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace atp
{

constexpr std::size_t RenderPatchPositionOffset = 0;
constexpr std::size_t RenderPatchNormalOffset = 12;
constexpr std::size_t RenderPatchColorOffset = 20;

/// Bytes per vertex: 20, or 24 with colors.
constexpr std::size_t RenderPatchStride(bool hasColors)
{
  return hasColors ? 24 : 20;
}

struct RenderPatch
{
  std::uint32_t Node = 0;
  std::vector<std::uint8_t> Vertices;
  std::vector<std::uint8_t> Indices;
  std::uint32_t VertexCount = 0;
  std::uint32_t TriangleCount = 0;
  bool ShortIndices = true;
  bool HasColors = false;
  std::string Error; ///< non-empty: the patch is corrupt and holds nothing

  std::size_t Stride() const { return RenderPatchStride(HasColors); }
  std::size_t Bytes() const { return Vertices.size() + Indices.size(); }
};

/// Lays out a decoded patch of node `node` (unit normals, indices below the vertex count).
RenderPatch MakeRenderPatch(const PatchMesh& mesh, std::uint32_t node);

} // namespace atp

#endif
