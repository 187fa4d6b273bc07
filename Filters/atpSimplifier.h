// The constrained simplifier of a diamond (paper, sections 3 and 5.2): half-edge collapses
// ordered by a quadric error with normals and colors, the diamond-external boundary locked, the
// original boundary kept as a polyline that only loses vertices, and a triangle quota per region
// (per member tetrahedron of the diamond).
#ifndef atpSimplifier_h
#define atpSimplifier_h

#include "atpPatchMesh.h"
#include "vtkATPFiltersModule.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace atp
{

/// The region (0..regionCount-1) of a triangle, from its centroid in input coordinates. `likely`
/// is a region in range that the point probably lies in (the triangle's region before a
/// collapse moved it, or the previous triangle's): a function that searches may try it first.
using RegionFunction = std::function<int(const double point[3], int likely)>;

struct SimplifyOptions
{
  /// Weight of a unit normal deviation against a position deviation of the mesh's bounding box
  /// diagonal: a normal off by 0.1 costs like the position off by 0.1 * NormalWeight diagonals.
  /// Small, so that shading guides the order of collapses without trading away geometry.
  /// Measured with atp-bench-simplify on 16 chunks each of the brain, the 2M torus and the
  /// bundled torus: 0.002 keeps the sampled Hausdorff distance under meshopt_simplify's on all
  /// three (0.0035 and 0.005 went over it), with a mean normal error 29% under that of
  /// positions alone on the brain (docs/construction.md, "Weighing normals").
  double NormalWeight = 0.002;
  /// The same for colors, each channel scaled to [0, 1].
  double ColorWeight = 0.005;
  /// At most this many triangles in all, besides each region's own quota: the regions then
  /// share what they give up, each only held to its quota.
  std::uint64_t TotalQuota = UINT64_MAX;
  /// Optional, with several regions: the region whose interior holds a point so deeply that
  /// regionOf gives that region for any convex combination of points this gives it for, or -1
  /// (MemberLocator::DeepMemberOf). Output vertices are input vertices, so each is asked once,
  /// and a triangle whose corners share an answer needs no call of regionOf: most triangles,
  /// since few lie near a region's border.
  RegionFunction DeepRegionOf;
};

struct SimplifyResult
{
  /// One compact mesh per region: its triangles in input order, the vertices they use in order
  /// of first use, and the BoundaryEdges bits of its triangles.
  std::vector<PatchMesh> Regions;
  /// Object-space error of the result against the input of this call: the largest distance from
  /// an input vertex to the output surface (an upper bound of it: each removed vertex is measured
  /// exactly, in double, against the output triangles around the vertex it collapsed into).
  /// Output vertices are input vertices, so this is the one-sided Hausdorff distance from the
  /// input's vertices to the output; callers add the children's errors on top. A removed piece's
  /// vertices count as moved to the center of its box. 0 when nothing collapsed or went.
  double Error = 0;
  std::size_t Collapses = 0;
  /// Pieces removed whole (see Simplify).
  std::size_t PiecesRemoved = 0;
  /// The mesh's triangles face either way at random: its edges run the same way by both of their
  /// triangles, counted at each of the two, outnumber half its triangles (facing at random gives
  /// about 1.5 per triangle; a seam between sheets that each face one way, a few percent, and up
  /// to a tenth in a small diamond along it). It simplified with them turned one way, but
  /// normals summed over such faces are noise, and the input's winding, kept in the output,
  /// shades speckled.
  bool FacingAtRandom = false;
  /// Triangles above the quotas, summed over the regions that end over theirs, plus those
  /// above the total quota: locked or topologically constrained geometry can keep some.
  std::uint64_t TrianglesOverQuotas = 0;
  bool QuotasMet() const { return TrianglesOverQuotas == 0; }
};

/// Simplifies `mesh` by half-edge collapses until every region holds at most quotas[region]
/// triangles (a triangle belongs to regionOf(its centroid)) and all of them at most
/// options.TotalQuota. Every output vertex is an input vertex with its exact position, normal
/// and color. Vertices on diamond-external boundary edges (open edges whose BoundaryEdges bit is
/// clear), on non-manifold edges or with a non-manifold fan never move; a vertex on the original
/// boundary (bit set) only collapses along it. No collapse flips or degenerates a triangle or
/// breaks manifoldness (link condition). None turns a moved face more than about 80 degrees from
/// the normal of the moved vertex's fan (the sum of its faces' area vectors) unless a region
/// cannot meet its quota otherwise, nor against it unless a region cannot meet its quota even
/// then. When no legal collapse is left for the regions over their quotas, pieces (connected
/// components with no vertex that may not move, closed like the tetrahedra an isosurface's
/// specks end as, or open only along the input's boundary like a lone triangle of a "sand")
/// with a triangle in such a region are removed whole,
/// smallest box first: before that guard relaxes, those whose box's half-diagonal is within the
/// error made so far; once it is off, any.
/// Deterministic and reentrant: concurrent calls on different meshes are safe. regionOf is
/// not called when regionCount is 1.
/// Triangles with a repeated corner are dropped from the input. Throws std::invalid_argument
/// when quotas.size() != regionCount, regionCount is over 32767, the input uses are not sized per
/// vertex and corner, regionOf returns a region out of range or the mesh has 2^30
/// triangles or more (a diamond's mesh holds tens of thousands).
VTKATPFILTERS_EXPORT SimplifyResult Simplify(const PatchMesh& mesh, int regionCount,
  const RegionFunction& regionOf, const std::vector<std::uint32_t>& quotas,
  const SimplifyOptions& options = {});

} // namespace atp

#endif
