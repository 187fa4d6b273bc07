// Edges of indexed meshes for tests: how often each is used, and the open ones. A crack in a
// cut shows up as open edges that are not the input's own boundary.
#ifndef atpTestMeshEdges_h
#define atpTestMeshEdges_h

#include "atpPatchMesh.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace atp
{
namespace test
{
using Position = std::array<float, 3>;
using Edge = std::pair<Position, Position>;

/// How many triangles use each edge (vertex pair) of an indexed mesh.
inline std::map<std::pair<std::uint32_t, std::uint32_t>, int> EdgeUses(const atp::PatchMesh& mesh)
{
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (std::size_t t = 0; t < mesh.TriangleCount(); ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      std::uint32_t a = mesh.Indices[3 * t + std::size_t(c)];
      std::uint32_t b = mesh.Indices[3 * t + std::size_t(c + 1) % 3];
      ++uses[{ std::min(a, b), std::max(a, b) }];
    }
  }
  return uses;
}

/// The vertices on open edges (used by one triangle) of an indexed mesh, by index.
inline std::set<std::uint32_t> OpenEdgeVertices(const atp::PatchMesh& mesh)
{
  std::set<std::uint32_t> vertices;
  for (const auto& [edge, count] : EdgeUses(mesh))
  {
    if (count == 1)
    {
      vertices.insert(edge.first);
      vertices.insert(edge.second);
    }
  }
  return vertices;
}

/// Open edges (used by one triangle) of a welded mesh, as position pairs.
inline std::vector<Edge> OpenEdges(const atp::PatchMesh& mesh)
{
  const auto uses = EdgeUses(mesh);
  std::vector<Edge> open;
  const auto at = [&mesh](std::uint32_t v) {
    return Position{ { mesh.Positions[3 * v], mesh.Positions[3 * v + 1], mesh.Positions[3 * v + 2] } };
  };
  for (const auto& [edge, count] : uses)
  {
    if (count == 1)
    {
      open.push_back({ at(edge.first), at(edge.second) });
    }
  }
  return open;
}

/// The vertices the edges join, as positions.
inline std::set<Position> EdgeEnds(const std::vector<Edge>& edges)
{
  std::set<Position> ends;
  for (const Edge& e : edges)
  {
    ends.insert(e.first);
    ends.insert(e.second);
  }
  return ends;
}

} // namespace test
} // namespace atp

#endif
