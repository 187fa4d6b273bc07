// The triangles of one polygon of an input mesh. A fan (c0, c1, c2), (c0, c2, c3), ... covers a
// convex polygon and only it; a concave one (an L, a star, a notched CAD face) gets a fan that
// spills outside it and overlaps itself, so it is triangulated in its plane instead, as
// VTK's own triangulation of polygons does.
#ifndef atpPolygonTriangulation_h
#define atpPolygonTriangulation_h

#include "atpPolygonMesh.h"
#include "vtkATPIOModule.h" // export macro

#include <array>
#include <cstdint>
#include <vector>

namespace atp
{

/// Triangulates polygons one after another, its working arrays kept from one to the next
/// (both passes over a mesh's faces triangulate every polygon of more than three corners).
class VTKATPIO_EXPORT PolygonTriangulator
{
public:
  /// Appends the triangles of the polygon with `count` (3 or more) corners, vertex indices
  /// into `vertices`, to `out` (three indices each, wound as the polygon). Corners that repeat
  /// the position before them are left out first. A polygon that turns one way at every
  /// corner, seen along its Newell normal, is fanned from its first corner, a quad that turns
  /// back at one corner from that corner; any other is triangulated by a constrained Delaunay
  /// triangulation of its corners projected on the plane across its normal's largest
  /// component (CGAL), keeping the triangles inside it. Where that does not give two triangles
  /// fewer than its corners, all of its own corners (a polygon that crosses or touches itself,
  /// or comes back to a corner), the fan stands: such a polygon has no inside to keep.
  void Triangulate(const std::uint32_t* corners, std::uint32_t count, const VertexView& vertices,
    std::vector<std::uint32_t>& out);

private:
  std::vector<std::uint32_t> Corners;          ///< without repeats
  std::vector<std::array<double, 3>> Points;   ///< theirs
  std::vector<std::array<double, 2>> Projected;
  std::vector<std::uint32_t> Reflex;
};

} // namespace atp

#endif
