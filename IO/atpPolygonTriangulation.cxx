#include "atpPolygonTriangulation.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <array>
#include <cmath>
#include <deque>

namespace atp
{
namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
/// A vertex knows its corner's place in the polygon.
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
/// A face knows how many constrained edges separate it from the outside (-1: not reached yet):
/// odd is inside the polygon.
using FaceBase = CGAL::Triangulation_face_base_with_info_2<int, Kernel,
  CGAL::Constrained_triangulation_face_base_2<Kernel>>;
using Triangulation = CGAL::Constrained_Delaunay_triangulation_2<Kernel,
  CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>, CGAL::No_constraint_intersection_tag>;

/// The fan from corner `from`.
void AppendFan(const std::uint32_t* corners, std::uint32_t count, std::vector<std::uint32_t>& out,
  std::uint32_t from = 0)
{
  for (std::uint32_t k = 1; k + 1 < count; ++k)
  {
    out.insert(out.end(), { corners[from], corners[(from + k) % count], corners[(from + k + 1) % count] });
  }
}

/// The corners where the projected polygon turns against its normal (none: it is convex, or
/// goes straight there).
void FindReflexCorners(const std::vector<std::array<double, 2>>& p, bool turned, std::vector<std::uint32_t>& reflex)
{
  reflex.clear();
  const std::size_t n = p.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    const auto& a = p[(k + n - 1) % n];
    const auto& b = p[k];
    const auto& c = p[(k + 1) % n];
    const double turn = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
    if (turned ? turn > 0 : turn < 0)
    {
      reflex.push_back(std::uint32_t(k));
    }
  }
}

/// Numbers every face by the constrained edges crossed on the way from the outside, breadth
/// first from the infinite face, one nesting level after another.
void NumberNesting(Triangulation& triangulation)
{
  for (const auto face : triangulation.all_face_handles())
  {
    face->info() = -1;
  }
  std::deque<Triangulation::Face_handle> level{ triangulation.infinite_face() }, next;
  triangulation.infinite_face()->info() = 0;
  for (int nesting = 0; !level.empty(); ++nesting)
  {
    while (!level.empty())
    {
      const Triangulation::Face_handle face = level.front();
      level.pop_front();
      for (int i = 0; i < 3; ++i)
      {
        const Triangulation::Face_handle neighbor = face->neighbor(i);
        if (neighbor->info() != -1)
        {
          continue;
        }
        if (triangulation.is_constrained(Triangulation::Edge(face, i)))
        {
          next.push_back(neighbor); // numbered when its level comes, unless reached before
        }
        else
        {
          neighbor->info() = nesting;
          level.push_back(neighbor);
        }
      }
    }
    for (const Triangulation::Face_handle face : next)
    {
      if (face->info() == -1)
      {
        face->info() = nesting + 1;
        level.push_back(face);
      }
    }
    next.clear();
  }
}

/// The triangles of the polygon from a constrained Delaunay triangulation of its projection;
/// false when that is not count - 2 triangles of its own corners.
bool AppendTriangulated(const std::uint32_t* corners, const std::vector<std::array<double, 2>>& points,
  bool turned, std::vector<std::uint32_t>& out)
{
  const std::uint32_t count = std::uint32_t(points.size());
  Triangulation triangulation;
  std::vector<Triangulation::Vertex_handle> handles(count);
  try
  {
    for (std::uint32_t k = 0; k < count; ++k)
    {
      handles[k] = triangulation.insert(Triangulation::Point(points[k][0], points[k][1]));
      if (triangulation.number_of_vertices() != k + 1)
      {
        return false; // a corner repeated, in the plane at least
      }
      handles[k]->info() = k;
    }
    for (std::uint32_t k = 0; k < count; ++k)
    {
      triangulation.insert_constraint(handles[k], handles[(k + 1) % count]);
    }
  }
  catch (const Triangulation::Intersection_of_constraints_exception&)
  {
    return false; // the polygon crosses itself
  }
  NumberNesting(triangulation);
  const std::size_t start = out.size();
  for (const auto face : triangulation.finite_face_handles())
  {
    if (face->info() % 2 == 1)
    {
      const std::uint32_t a = face->vertex(0)->info(), b = face->vertex(1)->info(),
                          c = face->vertex(2)->info();
      // Counterclockwise in the projection: the polygon's winding unless the projection turned.
      out.insert(out.end(), { corners[a], corners[turned ? c : b], corners[turned ? b : c] });
    }
  }
  if (out.size() - start != 3 * std::size_t(count - 2))
  {
    out.resize(start);
    return false;
  }
  return true;
}
} // namespace

void PolygonTriangulator::Triangulate(const std::uint32_t* corners, std::uint32_t count,
  const VertexView& vertices, std::vector<std::uint32_t>& out)
{
  // Corners that repeat the one before (an index or a position written twice, as exporters do)
  // turn nowhere and would hide a reflex corner beside them: the polygon goes without them.
  Corners.clear();
  Points.clear();
  for (std::uint32_t k = 0; k < count; ++k)
  {
    float p[3];
    vertices.Get(corners[k], p);
    const std::array<double, 3> point{ { p[0], p[1], p[2] } };
    if (Points.empty() || point != Points.back())
    {
      Corners.push_back(corners[k]);
      Points.push_back(point);
    }
  }
  while (Points.size() > 1 && Points.back() == Points.front())
  {
    Points.pop_back();
    Corners.pop_back();
  }
  const std::uint32_t kept = std::uint32_t(Corners.size());
  if (kept < 3)
  {
    AppendFan(corners, count, out); // no area: its triangles are dropped as degenerate
    return;
  }
  if (kept > 3)
  {
    double normal[3] = { 0, 0, 0 }; // Newell's: twice the projected areas
    for (std::uint32_t k = 0; k < kept; ++k)
    {
      const auto& a = Points[k];
      const auto& b = Points[(k + 1) % kept];
      normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
      normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
      normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
    {
      axis = std::fabs(normal[a]) > std::fabs(normal[axis]) ? a : axis;
    }
    // Projected on the plane across the normal's largest component, (x, y) for z, (y, z) for x,
    // (z, x) for y: counterclockwise about the normal stays so unless the normal points against
    // that axis (turned).
    const bool turned = normal[axis] < 0;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    Projected.resize(kept);
    for (std::uint32_t k = 0; k < kept; ++k)
    {
      Projected[k] = { { Points[k][std::size_t(u)], Points[k][std::size_t(v)] } };
    }
    if (normal[axis] != 0) // an area to keep
    {
      FindReflexCorners(Projected, turned, Reflex);
      if (kept == 4 && Reflex.size() == 1)
      {
        // A dart: the diagonal from its one reflex corner lies inside it. Quads are common, and
        // a noisy one can turn back a little: no triangulation for them.
        AppendFan(Corners.data(), kept, out, Reflex[0]);
        return;
      }
      if (!Reflex.empty() && AppendTriangulated(Corners.data(), Projected, turned, out))
      {
        return;
      }
    }
  }
  AppendFan(Corners.data(), kept, out);
}

} // namespace atp
