#include "atpSimplifier.h"

#include "atpClosestPoint.h"
#include "atpCollapseQueues.h"
#include "atpQuadric.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace atp
{

namespace
{

constexpr std::uint32_t None = ~0u;
/// An original-boundary edge adds the plane through it, perpendicular to its triangle, with this
/// weight times its squared length (the triangle planes weigh their area): the outline of a hole
/// moves only where moving it costs about as little as flattening the surface does. Heavier
/// weights (10 before) measured worse in sampled Hausdorff on chunks with holes.
constexpr double BoundaryPlaneWeight = 1;
/// A collapse may not leave a triangle whose angle at the moved corner has a sine below 1e-6.
constexpr double DegenerateSine2 = 1e-12;
/// A moved triangle should face within about 80 degrees of the normal of the moved vertex's fan
/// as it stands (the sum of its faces' cross products), not just under 90: a face almost edge-on
/// to the surface it replaces is a fin standing off it. In its first form, against the corners'
/// input normals, a guard of this angle lowered the sampled Hausdorff distance by 4% and 1% on 16
/// chunks each of the brain and the 2M torus (docs/construction.md, "Weighing normals"); against
/// the fan, 70 and 60 degrees made the brain's cuts larger than 80. Only a preference: fins are
/// allowed once the regions over quota have no other collapse left.
constexpr double FinCosine = 0.17;
/// At most 3 normal components and 4 color channels.
constexpr int MaxAttributes = 7;

/// How a moved face must face the moved vertex's fan normal, strictest first (Run relaxes the
/// guard one stage at a time, up to Off, the last). The fan as it stands rather than the input
/// normals of the corners: at the coarse levels those no longer describe the few vertices kept,
/// and held to them the guard forced detours of hundreds of times the usual cost there
/// (docs/construction.md, "The facing guard: the fan, not the input normals").
enum class FacingGuard : std::uint8_t
{
  NoFins, ///< within about 80 degrees of it (FinCosine)
  Fins,   ///< within 90 degrees: a fin standing off the surface is allowed
  /// Not held to it: a patch over its budget is the worse evil, it costs every frame that draws
  /// it.
  Off
};

enum class VertexKind : std::uint8_t
{
  Free,     ///< interior manifold vertex: may collapse onto any neighbor
  Boundary, ///< on the original boundary: collapses only along it
  Locked,   ///< diamond-external boundary, non-manifold, or unused: never moves
  Removed   ///< collapsed
};

struct Candidate
{
  double Cost = 0;
  std::uint32_t Target = None; ///< None: nothing queued
  int Region = 0; ///< the queue it waits in: the region of a triangle it removes
  /// 0: removes triangles of regions over quota only, 1: some, 2: none.
  int Rank = 0;
};

/// The order of collapses: by rank, then cost, ties by target.
inline bool Before(const Candidate& a, const Candidate& b)
{
  if (a.Rank != b.Rank)
  {
    return a.Rank < b.Rank;
  }
  return a.Cost < b.Cost || (a.Cost == b.Cost && a.Target < b.Target);
}

/// Corner k of triangle t as one number: 4t + k rather than 3t + k, so that taking it apart,
/// which every walk around a vertex does for every corner, is a shift and a mask instead of a
/// division by 3. Meshes stay far below the 2^30 triangles this allows (checked).
constexpr std::uint32_t CornerOf(std::uint32_t t, int k)
{
  return t << 2 | std::uint32_t(k);
}
constexpr std::uint32_t TriangleOf(std::uint32_t c)
{
  return c >> 2;
}
constexpr int CornerSlot(std::uint32_t c)
{
  return int(c & 3);
}
constexpr std::size_t MaxTriangles = std::size_t(1) << 30;

// The next and previous of corners 0, 1, 2 read from bit tables rather than compared: walks
// step around fans in an order no branch predictor learns (these were 14% of a chunk's
// mispredicted branches).
inline int NextCorner(int k)
{
  return (1 << k) & 3; // 1, 2, 0
}
inline int PrevCorner(int k)
{
  return (0x12 >> (2 * k)) & 3; // 2, 0, 1
}

/// A triangle's BoundaryEdges bits once corners 1 and 2 swap (either way): edges 0-1, 1-2, 2-0
/// become 0-2, 2-1, 1-0, so edge bits 0 and 2 trade places, as do the many-sheet bits 3 and 5.
constexpr std::uint8_t FlippedBits(std::uint8_t bits)
{
  return std::uint8_t((bits & 0xD2) | ((bits & 0x01) << 2) | ((bits & 0x04) >> 2) |
    ((bits & 0x08) << 2) | ((bits & 0x20) >> 2));
}

inline void Sub(const double* a, const double* b, double* out)
{
  out[0] = a[0] - b[0];
  out[1] = a[1] - b[1];
  out[2] = a[2] - b[2];
}
inline void Cross(const double* a, const double* b, double* out)
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}
inline double Dot(const double* a, const double* b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// Sets mark to stamp; returns all ones when it held the stamp already, else zero, for the counts
/// kept under the mark to be ANDed with. Without a branch: around a fan, each neighbor is met
/// once or twice in an order no branch predictor learns.
inline std::uint32_t Restamp(std::uint32_t& mark, std::uint32_t stamp)
{
  const std::uint32_t keep = 0u - std::uint32_t(mark == stamp);
  mark = stamp;
  return keep;
}

/// A triangle of the working mesh with all that a walk around a vertex reads from it: its
/// corners, its region and open-edge bits, and whether it is gone.
struct Face
{
  std::uint32_t V[3];
  std::int16_t Region = 0; ///< 16 bits (CheckedRegionCount): a diamond has at most 8 members
  std::uint8_t Bits = 0; ///< BoundaryEdges: bit k (3 + k) for the edge from corner k to k + 1
  std::uint8_t Removed = 0;
  /// PatchMesh::CornerUses, here rather than in an array of their own: a collapse rewrites
  /// them for every triangle of the moved vertex's fan, whose records it reads anyway.
  std::uint8_t Uses[3] = { 0, 0, 0 };
};
static_assert(sizeof(Face) == 20, "a face record stays 20 bytes");

/// Where a vertex's fan lies in the corner pool.
struct FanSlice
{
  std::uint32_t Start = 0;
  std::uint32_t Count = 0;
};

/// A gathered fan: its live corners, read where they lie in the pool. Valid until the pool
/// changes (a collapse) or the vertex's fan is gathered again.
struct FanView
{
  const std::uint32_t* First = nullptr;
  std::uint32_t Count = 0;
  const std::uint32_t* begin() const { return First; }
  const std::uint32_t* end() const { return First + Count; }
  std::size_t size() const { return Count; }
  bool empty() const { return Count == 0; }
  std::uint32_t operator[](std::size_t i) const { return First[i]; }
};

/// Turns the counts of consecutive runs (Start, Count) into their starts, the counts zeroed to
/// count again as the runs fill; returns the sum of the counts.
template <typename Runs>
std::uint32_t StartRuns(Runs& runs)
{
  std::uint32_t start = 0;
  for (auto& run : runs)
  {
    run.Start = start;
    start += run.Count;
    run.Count = 0;
  }
  return start;
}

/// A piece of the mesh wholly inside the diamond (a connected component with no locked vertex:
/// none on the external border, on a non-manifold edge or fan), closed or open only along the
/// input's boundary, which collapses cannot take below a tetrahedron or a lone triangle. An
/// isosurface's specks end as such: the brain's coarsest diamond held 579 of them, 2,316
/// triangles for a quota of 3,271; so does a "sand" of separate triangles.
struct Piece
{
  double Radius2 = 0;         ///< half its box's diagonal, squared: no vertex is farther from Center
  double Center[3] = { 0, 0, 0 };
  std::uint32_t Start = 0;    ///< its triangles: PieceTriangles[Start, Start + Count)
  std::uint32_t Count = 0;
  std::uint32_t Smallest = 0; ///< its smallest vertex: orders pieces of equal radius
  bool Removed = false;
};

/// One call's state. A vertex's fan is a run of corners (CornerOf) in one pool, in the order of
/// a walk around it; removed triangles drop out lazily as fans are gathered. A collapse writes
/// the target's new fan at the end of the pool. Runs rather than lists linked through the
/// triangles: a walk's reads of the triangles no longer wait on each other, which matters once a
/// diamond's mesh outgrows the cache.
class Simplifier
{
public:
  Simplifier(const PatchMesh& mesh, int regionCount, const RegionFunction& regionOf,
    const std::vector<std::uint32_t>& quotas, const SimplifyOptions& options);
  SimplifyResult Run();

private:
  void LinkCorners();
  void AssignRegions();
  void Classify(std::uint32_t u);
  /// Flips triangles (two corners swapped, their edge bits with them) so that every edge two
  /// triangles share runs one way in one and the other way in the other, where the mesh allows
  /// (Flipped notes them, and Extract turns them back). Classify locks the ends of an edge that
  /// two triangles run the same way: a mesh whose triangles face every which way would keep
  /// nearly all of them. Returns whether any triangle flipped; the fans must then be linked
  /// again.
  bool OrientConsistently();
  void BuildQuadrics();
  /// BuildQuadrics with the attribute count Fixed as a constant (Quadric::WithAttributeCount):
  /// it runs for every triangle of every diamond.
  template <int Fixed>
  void BuildQuadricsWith();
  /// Drops u's removed corners from its run, and points Fan at it.
  void GatherFan(std::uint32_t u);
  /// Works out FanCross and FanNormal for u, unless they are u's already: once for all the
  /// targets a vertex is checked against. Fan must hold u's fan.
  void ShapeFan(std::uint32_t u);
  bool CanCollapse(std::uint32_t u, std::uint32_t v);
  /// Queues u's cheapest collapse; only a legal one when checkLegal, otherwise legality is
  /// checked when it comes out of the queue (most evaluations are superseded before that).
  /// checkLegal is for a vertex whose popped collapse onto `refused` just failed CanCollapse:
  /// Fan holds its fan, shaped already, and that target is not checked again (nothing changed).
  void Evaluate(std::uint32_t u, bool checkLegal, std::uint32_t refused = None)
  {
    Quadric::WithAttributeCount(
      Attributes, [&](auto fixed) { EvaluateWith<decltype(fixed)::value>(u, checkLegal, refused); });
  }
  /// Evaluate with the attribute count Fixed as a constant: it prices every neighbor of u, and
  /// dispatching once per vertex instead of once per price saved 0.76% of a build's
  /// instructions.
  template <int Fixed>
  void EvaluateWith(std::uint32_t u, bool checkLegal, std::uint32_t refused);
  /// After a neighbor of x collapsed onto v: x's queued collapse keeps its cost (x's quadric and
  /// its target's position are unchanged), so only the new candidate x -> v needs pricing,
  /// unless x lost its target or has nothing queued. With several regions, the regions of the
  /// triangles x -> v removes come from NoteRegionsAround(v).
  void Offer(std::uint32_t x, std::uint32_t v);
  /// For each neighbor x of v: the regions of the triangles where v follows x and where v
  /// precedes x (those x -> v would remove), marked with StampV in MarkV. One walk around v
  /// instead of one around every neighbor.
  void NoteRegionsAround(std::uint32_t v);
  /// The collapse u -> target, which removes a triangle of regionA and one of regionB.
  Candidate Price(std::uint32_t u, std::uint32_t target, int regionA, int regionB) const
  {
    return Quadric::WithAttributeCount(Attributes, [&](auto fixed) {
      return Ranked(Cost<decltype(fixed)::value>(Record(u), target), target, regionA, regionB);
    });
  }
  /// u's quadric (record) at the target, per unit of its planes' weight; Fixed is the attribute
  /// count as a constant (Quadric::WithAttributeCount).
  template <int Fixed>
  [[gnu::always_inline]] double Cost(const double* record, std::uint32_t target) const
  {
    return QuadricError<Fixed>(record, target) / Weight(record);
  }
  template <int Fixed>
  [[gnu::always_inline]] double QuadricError(const double* record, std::uint32_t target) const
  {
    return Quadric::EvaluateWith<Fixed>(record, Attributes, Position(target), AttributesOf(target));
  }
  double Weight(const double* record) const { return std::max(record[RecordSize - 1], 1e-300); }
  /// Rank 0 when the collapse removes triangles of over-quota regions only, 1 for one of them,
  /// 2 for none.
  int RankOf(int regionA, int regionB) const { return 2 - int(OverQuota(regionA)) - int(OverQuota(regionB)); }
  Candidate Ranked(double cost, std::uint32_t target, int regionA, int regionB) const
  {
    Candidate candidate;
    candidate.Cost = cost;
    candidate.Target = target;
    candidate.Rank = RankOf(regionA, regionB);
    candidate.Region = OverQuota(regionA) || !OverQuota(regionB) ? regionA : regionB;
    return candidate;
  }
  /// Calls consider(target, regionA, regionB) for every collapse u may make: onto any neighbor
  /// for a Free vertex, along the original boundary for a Boundary one. Fan must hold u's fan.
  template <typename Consider>
  void ForEachCollapse(std::uint32_t u, Consider consider);
  void Queue(std::uint32_t u, const Candidate& candidate);
  /// Sum over regions of max(0, count - quota), plus max(0, Total - TotalQuota).
  std::int64_t ExcessOverQuotas() const;
  /// Finds the pieces (Piece), smallest first.
  void FindPieces();
  /// Removes the smallest piece with a triangle in a region over quota, its vertices
  /// counted as moved to its center; false when there is none. Unless anySize, only a piece
  /// within the deviation the collapses made so far: its removal leaves the error as it is.
  bool RemoveSmallestPiece(bool anySize);
  /// The region of triangle t once its corner u moves onto v, by its centroid.
  int MovedRegionOf(std::uint32_t t, std::uint32_t u, std::uint32_t v) const;
  /// Change of the total excess over the quotas if u moves onto v; fills MovedRegions.
  std::int64_t ExcessChange(std::uint32_t u, std::uint32_t v);
  void Collapse(std::uint32_t u, std::uint32_t v);
  /// Rewrites the pool with each fan's live corners only, with room for `extra` more and as
  /// many again: what collapses leave behind is reclaimed, so a vertex that keeps absorbing
  /// its neighbors (its whole fan written anew each time) cannot grow the pool without bound.
  void CompactCorners(std::size_t extra);
  /// Appends the corners of `run` whose triangles are live to `out` (with room for all of
  /// run's corners when `out` is the pool itself, which then must not reallocate under the
  /// reads).
  void AppendLiveCorners(FanSlice run, std::vector<std::uint32_t>& out) const
  {
    // Every corner written, only live ones kept (as GatherFan): which triangles a collapse just
    // removed from the fans it joins follows no pattern.
    std::size_t live = out.size();
    out.resize(live + run.Count);
    for (std::uint32_t i = run.Start; i < run.Start + run.Count; ++i)
    {
      const std::uint32_t c = Corners[i];
      out[live] = c;
      live += std::size_t(!Faces[TriangleOf(c)].Removed);
    }
    out.resize(live);
  }
  void FixOpenEdge(std::uint32_t t, std::uint32_t u, std::uint32_t v, std::uint32_t w);
  /// For a triangle t = (u, v, w) that u -> v removes, before u's corners move: the triangle
  /// across w-u (around u, not holding v), which takes the edge v-w over; None where there is
  /// none. Fan must hold u's fan.
  std::uint32_t TriangleAcrossWU(std::uint32_t t, std::uint32_t v, std::uint32_t w) const;
  /// The same for the triangle across v-w (around v, not holding u), before v's fan takes in
  /// u's corners.
  std::uint32_t TriangleAcrossVW(std::uint32_t t, std::uint32_t u, std::uint32_t v, std::uint32_t w) const;
  /// The input triangles t stands for at v and at w go to the triangle that takes its edge
  /// v-w over (PatchMesh::CornerUses), once u has moved onto v.
  void HandOverUses(std::uint32_t t, std::uint32_t v, std::uint32_t w, std::uint32_t heir);
  int RegionOf(const double point[3], int likely) const;
  /// The region of a triangle with corners a, b, c when all three lie deep in it
  /// (SimplifyOptions::DeepRegionOf), else -1: regionOf must then be asked.
  int SharedDeepRegion(std::uint32_t a, std::uint32_t b, std::uint32_t c) const
  {
    if (DeepRegion.empty())
    {
      return -1;
    }
    const int r = DeepRegion[a];
    return DeepRegion[b] == r && DeepRegion[c] == r ? r : -1;
  }
  bool OverQuota(int r) const { return Total > TotalQuota || Over[std::size_t(r)] != 0; }
  /// Adds delta to region r's live triangle count, keeping its Over flag current.
  void CountTriangles(int r, std::int64_t delta)
  {
    const std::size_t i = std::size_t(r);
    Total += delta;
    Counts[i] += delta;
    const bool over = Counts[i] > std::int64_t(Quotas[i]);
    RegionsOver += std::size_t(over) - std::size_t(Over[i]);
    Over[i] = over;
  }
  /// Corner c: its vertex.
  std::uint32_t& VertexAt(std::uint32_t c) { return Faces[TriangleOf(c)].V[CornerSlot(c)]; }
  bool Contains(std::uint32_t t, std::uint32_t v) const
  {
    return Faces[t].V[0] == v || Faces[t].V[1] == v || Faces[t].V[2] == v;
  }
  /// Calls visit(t, k) for every live triangle t around v, v being its corner k.
  template <typename Visit>
  void ForEachCorner(std::uint32_t v, Visit visit) const
  {
    const std::uint32_t* corners = Corners.data() + Fans[v].Start;
    for (std::uint32_t i = 0; i < Fans[v].Count; ++i)
    {
      const std::uint32_t c = corners[i];
      if (!Faces[TriangleOf(c)].Removed)
      {
        visit(TriangleOf(c), CornerSlot(c));
      }
    }
  }
  /// Bit index of the edge between vertices a and b of triangle t.
  int EdgeBit(std::uint32_t t, std::uint32_t a, std::uint32_t b) const;
  const double* Position(std::uint32_t v) const { return &Point[PointSize * v]; }
  const double* AttributesOf(std::uint32_t v) const { return &Point[PointSize * v + 3]; }
  double* Record(std::uint32_t v) { return &Records[RecordSize * v]; }
  const double* Record(std::uint32_t v) const { return &Records[RecordSize * v]; }
  /// The largest distance from an input vertex to the mesh as it stands (see SimplifyResult).
  double Deviation();
  PatchMesh Extract(const std::vector<std::uint32_t>& triangles);

  const PatchMesh& Mesh;
  const int RegionCount;
  const RegionFunction& RegionFn;
  const RegionFunction& DeepRegionFn;
  const std::vector<std::uint32_t>& Quotas;
  const std::size_t VertexCount;
  const std::size_t TriangleCount;

  std::vector<Face> Faces;                // the working mesh
  std::vector<std::uint32_t> Corners;      // the fans, run after run
  std::vector<FanSlice> Fans;              // per vertex: its run in Corners

  double Origin[3] = { 0, 0, 0 };
  double Scale = 1; // bounding box diagonal: positions are normalized by it
  int Attributes = 0;
  bool NormalAttributes = false; ///< the first 3 attributes are the vertices' normals
  /// Per vertex, together since a price reads both: the normalized position, then the
  /// weighted attributes (PointSize doubles).
  std::size_t PointSize = 3;
  std::vector<double> Point;
  /// Per vertex, one record: the area-weighted plane + attribute-field quadric that orders the
  /// collapses (Quadric::Size(Attributes) doubles), then the total weight of its planes.
  std::size_t RecordSize = 0;
  std::vector<double> Records;
  /// Per removed vertex: the vertex it collapsed onto, itself when it vanished with its piece.
  std::vector<std::uint32_t> Into;
  std::vector<std::uint32_t> CollapseOrder; // the removed vertices, first collapsed first
  std::vector<VertexKind> Kind;
  /// Edges Classify found run the same way by both of their triangles, counted once at each
  /// triangle.
  std::size_t MisorientedEdges = 0;
  bool FacingAtRandom = false; ///< see SimplifyResult
  /// Per triangle, after OrientConsistently: flipped (empty when none was).
  std::vector<std::uint8_t> Flipped;
  std::vector<Candidate> Best; // per vertex: its queued collapse
  CollapseQueues Waiting; // per region: the vertices whose collapse removes its triangles
  std::vector<std::int64_t> Counts;           // live triangles per region
  std::vector<std::uint8_t> Over;             // per region: Counts over its quota
  /// Per vertex: the region it lies deep in, or -1 (SimplifyOptions::DeepRegionOf); empty
  /// without that function or with one region.
  std::vector<int> DeepRegion;
  std::size_t RegionsOver = 0;                // regions over their quotas
  std::int64_t Total = 0;                     // live triangles in all
  const std::int64_t TotalQuota;              // while Total is over it, every region is over
  std::int64_t Excess = 0; ///< ExcessOverQuotas(), kept current
  /// Found the first time the regions over quota have no legal collapse left, which few calls
  /// reach: most never pay for the search.
  bool PiecesFound = false;
  std::vector<Piece> Pieces;
  std::vector<std::uint32_t> PieceTriangles;
  std::vector<std::uint32_t> PieceOf; // per vanished vertex: its piece
  std::size_t Vanished = 0;           // vertices removed with their pieces
  std::size_t FirstLeft = 0;          // pieces before it are all removed: a scan starts there
  double Deviation2 = 0;              // Deviation() squared, measured after MeasuredCollapses
  std::size_t MeasuredCollapses = 0;
  /// Collapses that would also remove triangles of regions within their quotas wait here, and
  /// are taken only when the over-quota regions have nothing else left (Relaxed).
  std::vector<std::uint32_t> Deferred;
  bool Relaxed = false;
  /// How a moved face is held to the moved vertex's fan normal, relaxed a stage each time the
  /// regions over quota have nothing else left.
  FacingGuard Facing = FacingGuard::NoFins;

  // Scratch, reused by every collapse: stamps make clearing unnecessary.
  FanView Fan;
  /// ShapeFan's: the cross products of the faces of Fan as they stand (twice their areas along
  /// their normals), 3 doubles per corner, and their sum, the fan normal; ShapedFan is the
  /// vertex they are of, None once GatherFan has gathered a fan since.
  std::vector<double> FanCross;
  double FanNormal[3] = { 0, 0, 0 };
  std::uint32_t ShapedFan = None;
  std::vector<std::uint32_t> Neighbors;
  std::vector<Candidate> Candidates;
  std::vector<int> MovedRegions;
  std::vector<std::int64_t> Delta;
  std::vector<int> Touched;
  /// Per vertex, together since a walk reads several of them for each neighbor it meets.
  struct VertexMarks
  {
    std::uint32_t MarkU = 0, CountU = 0, MarkV = 0, CountV = 0, SlotU = 0;
  };
  std::vector<VertexMarks> Marks;
  std::vector<int> RegionFollowing, RegionPreceding;
  /// Whether the input counts its uses (PatchMesh::CornerUses, kept in Face::Uses), and then
  /// per vertex whether its input triangles are not all here (VerticesUsedElsewhere).
  bool TracksUses = false;
  std::vector<std::uint8_t> UsedElsewhere;
  std::uint32_t StampU = 0, StampV = 0;
};

/// The number of regions, checked before anything is sized by it.
std::size_t CheckedRegionCount(int regionCount, const std::vector<std::uint32_t>& quotas)
{
  if (regionCount < 1 || quotas.size() != std::size_t(regionCount))
  {
    throw std::invalid_argument("Simplify: need one quota per region");
  }
  if (regionCount > INT16_MAX)
  {
    throw std::invalid_argument("Simplify: more regions than 16 bits hold");
  }
  return std::size_t(regionCount);
}

Simplifier::Simplifier(const PatchMesh& mesh, int regionCount, const RegionFunction& regionOf,
  const std::vector<std::uint32_t>& quotas, const SimplifyOptions& options)
  : Mesh(mesh)
  , RegionCount(regionCount)
  , RegionFn(regionOf)
  , DeepRegionFn(options.DeepRegionOf)
  , Quotas(quotas)
  , VertexCount(mesh.VertexCount())
  , TriangleCount(mesh.TriangleCount())
  , Waiting(CheckedRegionCount(regionCount, quotas), VertexCount)
  , TotalQuota(std::int64_t(std::min<std::uint64_t>(options.TotalQuota, INT64_MAX)))
{
  if (TriangleCount >= MaxTriangles)
  {
    throw std::invalid_argument("Simplify: a mesh of 2^30 triangles or more");
  }
  if (!mesh.UsesSized())
  {
    throw std::invalid_argument("Simplify: input uses not sized per vertex and corner");
  }
  Faces.resize(TriangleCount);
  for (std::size_t t = 0; t < TriangleCount; ++t)
  {
    std::copy_n(&mesh.Indices[3 * t], 3, Faces[t].V);
    Faces[t].Bits = t < mesh.BoundaryEdges.size() ? mesh.BoundaryEdges[t] : 0;
  }
  TracksUses = !mesh.CornerUses.empty();
  for (std::size_t t = 0; t < TriangleCount && TracksUses; ++t)
  {
    std::copy_n(&mesh.CornerUses[3 * t], 3, Faces[t].Uses);
  }
  UsedElsewhere = VerticesUsedElsewhere(mesh);

  double lo[3] = { 1e300, 1e300, 1e300 };
  double hi[3] = { -1e300, -1e300, -1e300 };
  for (std::size_t v = 0; v < VertexCount; ++v)
  {
    for (std::size_t a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], double(mesh.Positions[3 * v + a]));
      hi[a] = std::max(hi[a], double(mesh.Positions[3 * v + a]));
    }
  }
  if (VertexCount > 0)
  {
    const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) +
      (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
    Scale = diagonal > 0 ? diagonal : 1;
    std::copy(lo, lo + 3, Origin);
  }
  const bool normals = options.NormalWeight > 0 && mesh.Normals.size() == 3 * VertexCount;
  const bool colors = options.ColorWeight > 0 && mesh.Colors.size() == 4 * VertexCount;
  NormalAttributes = normals;
  Attributes = (normals ? 3 : 0) + (colors ? 4 : 0);
  PointSize = 3 + std::size_t(Attributes);
  Point.resize(PointSize * VertexCount);
  for (std::size_t v = 0; v < VertexCount; ++v)
  {
    double* s = &Point[PointSize * v];
    for (std::size_t a = 0; a < 3; ++a)
    {
      *s++ = (mesh.Positions[3 * v + a] - Origin[a]) / Scale;
    }
    if (normals)
    {
      for (int j = 0; j < 3; ++j)
      {
        *s++ = options.NormalWeight * mesh.Normals[3 * v + std::size_t(j)];
      }
    }
    if (colors)
    {
      for (int j = 0; j < 4; ++j)
      {
        *s++ = options.ColorWeight * mesh.Colors[4 * v + std::size_t(j)] / 255.0;
      }
    }
  }

  Kind.assign(VertexCount, VertexKind::Locked);
  Best.assign(VertexCount, Candidate());
  Into.assign(VertexCount, None);
  Marks.assign(VertexCount, VertexMarks());
  if (regionCount > 1)
  {
    RegionFollowing.assign(VertexCount, 0);
    RegionPreceding.assign(VertexCount, 0);
  }
  Counts.assign(std::size_t(regionCount), 0);
  Over.assign(std::size_t(regionCount), 0);
  Delta.assign(std::size_t(regionCount), 0);
}

int Simplifier::RegionOf(const double point[3], int likely) const
{
  const int r = RegionFn(point, likely);
  if (r < 0 || r >= RegionCount)
  {
    throw std::invalid_argument("Simplify: the region function returned a region out of range");
  }
  return r;
}

int Simplifier::EdgeBit(std::uint32_t t, std::uint32_t a, std::uint32_t b) const
{
  const std::uint32_t* tri = Faces[t].V;
  const int ka = tri[0] == a ? 0 : (tri[1] == a ? 1 : 2);
  return tri[NextCorner(ka)] == b ? ka : PrevCorner(ka);
}

void Simplifier::LinkCorners()
{
  // Triangles with a repeated corner are degenerate: they take no part.
  Fans.assign(VertexCount, FanSlice());
  for (std::size_t t = 0; t < TriangleCount; ++t)
  {
    const std::uint32_t* tri = Faces[t].V;
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0])
    {
      Faces[t].Removed = 1;
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      ++Fans[tri[k]].Count;
    }
  }
  const std::uint32_t start = StartRuns(Fans);
  // Collapses append fans: room for about as many corners again.
  Corners.reserve(2 * std::size_t(start));
  Corners.resize(start);
  for (std::uint32_t t = 0; t < TriangleCount; ++t)
  {
    for (int k = 0; k < 3 && !Faces[t].Removed; ++k)
    {
      FanSlice& fan = Fans[Faces[t].V[k]];
      Corners[fan.Start + fan.Count++] = CornerOf(t, k);
    }
  }
}

void Simplifier::AssignRegions()
{
  if (RegionCount > 1 && DeepRegionFn)
  {
    DeepRegion.resize(VertexCount);
    int likely = 0; // vertices come patch by patch too
    for (std::size_t v = 0; v < VertexCount; ++v)
    {
      const double p[3] = { double(Mesh.Positions[3 * v]), double(Mesh.Positions[3 * v + 1]),
        double(Mesh.Positions[3 * v + 2]) };
      const int r = DeepRegionFn(p, likely);
      if (r < -1 || r >= RegionCount)
      {
        throw std::invalid_argument("Simplify: the deep region function returned a region out of range");
      }
      DeepRegion[v] = r;
      likely = r >= 0 ? r : likely;
    }
  }
  for (std::size_t t = 0; t < TriangleCount; ++t)
  {
    if (Faces[t].Removed)
    {
      continue;
    }
    if (RegionCount == 1)
    {
      CountTriangles(0, 1);
      continue;
    }
    const int deep = SharedDeepRegion(Faces[t].V[0], Faces[t].V[1], Faces[t].V[2]);
    if (deep >= 0)
    {
      Faces[t].Region = deep;
      CountTriangles(deep, 1);
      continue;
    }
    double centroid[3] = { 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      for (int a = 0; a < 3; ++a)
      {
        centroid[a] += double(Mesh.Positions[3 * std::size_t(Faces[t].V[k]) + std::size_t(a)]);
      }
    }
    for (double& x : centroid)
    {
      x /= 3;
    }
    // Triangles come patch by patch: mostly in the previous one's region.
    Faces[t].Region = RegionOf(centroid, t > 0 ? Faces[t - 1].Region : 0);
    CountTriangles(Faces[t].Region, 1);
  }
  Excess = ExcessOverQuotas();
}

std::int64_t Simplifier::ExcessOverQuotas() const
{
  std::int64_t excess = std::max<std::int64_t>(0, Total - TotalQuota);
  for (int r = 0; r < RegionCount; ++r)
  {
    excess += std::max<std::int64_t>(0, Counts[std::size_t(r)] - std::int64_t(Quotas[std::size_t(r)]));
  }
  return excess;
}

void Simplifier::GatherFan(std::uint32_t u)
{
  FanSlice& run = Fans[u];
  std::uint32_t* corners = Corners.data() + run.Start;
  // Every corner is written and only live ones are kept: whether a corner's triangle is gone
  // follows no pattern a branch predictor could learn.
  std::uint32_t live = 0;
  for (std::uint32_t i = 0; i < run.Count; ++i)
  {
    const std::uint32_t c = corners[i];
    corners[live] = c;
    live += std::uint32_t(!Faces[TriangleOf(c)].Removed);
  }
  run.Count = live;
  Fan = FanView{ corners, live };
  ShapedFan = None;
}

// A vertex may move only if its fan is one consistently oriented disk (Free) or half-disk whose
// two open edges are original boundary (Boundary). It also clears stale bits on interior edges
// (a boundary edge of one input patch can be interior once patches are welded).
void Simplifier::Classify(std::uint32_t u)
{
  GatherFan(u);
  if (Fan.empty())
  {
    return; // unused vertex: stays Locked
  }
  ++StampU;
  // CountU: times a neighbor is the next corner (edge u->x), CountV: the previous (edge x->u);
  // SlotU: the fan index of the triangle where it is the next corner.
  auto touch = [&](std::uint32_t x) {
    const std::uint32_t keep = Restamp(Marks[x].MarkU, StampU);
    Marks[x].CountU &= keep;
    Marks[x].CountV &= keep;
  };
  for (std::size_t i = 0; i < Fan.size(); ++i)
  {
    const std::uint32_t t = TriangleOf(Fan[i]);
    const int k = CornerSlot(Fan[i]);
    const std::uint32_t x = Faces[t].V[NextCorner(k)];
    const std::uint32_t y = Faces[t].V[PrevCorner(k)];
    touch(x);
    touch(y);
    ++Marks[x].CountU;
    ++Marks[y].CountV;
    Marks[x].SlotU = std::uint32_t(i);
  }
  bool locked = false;
  int open = 0;
  std::size_t start = 0;
  for (std::size_t i = 0; i < Fan.size(); ++i)
  {
    const std::uint32_t t = TriangleOf(Fan[i]);
    const int k = CornerSlot(Fan[i]);
    const std::uint32_t x = Faces[t].V[NextCorner(k)];
    const std::uint32_t y = Faces[t].V[PrevCorner(k)];
    locked = locked || Marks[x].CountU > 1 || Marks[x].CountV > 1 ||
      (Faces[t].Bits & ((8u << k) | (8u << PrevCorner(k))));
    MisorientedEdges += std::size_t(int(Marks[x].CountU == 2) & int(Marks[x].CountV == 0));
    if (Marks[x].CountV == 0)
    {
      ++open;
      start = i;
      locked = locked || !(Faces[t].Bits & (1u << k));
    }
    else
    {
      Faces[t].Bits &= std::uint8_t(~(1u << k));
    }
    if (Marks[y].CountU == 0)
    {
      ++open;
      locked = locked || !(Faces[t].Bits & (1u << PrevCorner(k)));
    }
    else
    {
      Faces[t].Bits &= std::uint8_t(~(1u << PrevCorner(k)));
    }
  }
  // More sheets elsewhere on one of its edges, which looks inner here: it stays.
  locked = locked || (!UsedElsewhere.empty() && UsedElsewhere[u]);
  if (locked || (open != 0 && open != 2))
  {
    return;
  }
  // Walk around u from the start of the half-disk (or anywhere on a disk): one fan visits all.
  std::size_t visited = 1;
  for (std::size_t i = start; visited <= Fan.size(); ++visited)
  {
    const std::uint32_t t = TriangleOf(Fan[i]);
    const std::uint32_t y = Faces[t].V[PrevCorner(CornerSlot(Fan[i]))];
    if (Marks[y].CountU == 0 || Marks[y].SlotU == start)
    {
      break;
    }
    i = Marks[y].SlotU;
  }
  if (visited == Fan.size())
  {
    Kind[u] = open ? VertexKind::Boundary : VertexKind::Free;
  }
}

bool Simplifier::OrientConsistently()
{
  Flipped.assign(TriangleCount, 0);
  std::vector<std::uint8_t> reached(TriangleCount, 0);
  // Breadth first: on a piece that cannot be oriented (a Moebius strip), the edges left running
  // one way form a seam across it where the two fronts meet, not one along its whole length,
  // which a walk that goes deep first left (their ends stay locked).
  std::vector<std::uint32_t> queue;
  bool flipped = false;
  for (std::uint32_t seed = 0; seed < TriangleCount; ++seed)
  {
    if (reached[seed] || Faces[seed].Removed)
    {
      continue;
    }
    reached[seed] = 1;
    queue.assign(1, seed);
    for (std::size_t next = 0; next < queue.size(); ++next)
    {
      const std::uint32_t t = queue[next];
      for (int k = 0; k < 3; ++k)
      {
        const std::uint32_t a = Faces[t].V[k], b = Faces[t].V[NextCorner(k)];
        // The one other triangle on a-b, if one: the fans' corner slots predate the flips, so
        // triangles are matched by their vertices.
        std::uint32_t other = None;
        int sharing = 0;
        ForEachCorner(a, [&](std::uint32_t t2, int) {
          if (t2 != t && Contains(t2, b))
          {
            other = t2;
            ++sharing;
          }
        });
        if (sharing != 1 || reached[other])
        {
          continue; // the input's boundary, a non-manifold edge, or settled already
        }
        reached[other] = 1;
        queue.push_back(other);
        Face& face = Faces[other];
        const int ka = face.V[0] == a ? 0 : (face.V[1] == a ? 1 : 2);
        if (face.V[NextCorner(ka)] == b) // a to b, as in t: the wrong way
        {
          std::swap(face.V[1], face.V[2]);
          face.Bits = FlippedBits(face.Bits);
          std::swap(face.Uses[1], face.Uses[2]);
          Flipped[other] = 1;
          flipped = true;
        }
      }
    }
  }
  if (!flipped)
  {
    Flipped.clear();
  }
  return flipped;
}

void Simplifier::BuildQuadrics()
{
  RecordSize = Quadric::Size(Attributes) + 1;
  Records.assign(RecordSize * VertexCount, 0.0);
  Quadric::WithAttributeCount(Attributes, [this](auto fixed) { BuildQuadricsWith<decltype(fixed)::value>(); });
}

template <int Fixed>
void Simplifier::BuildQuadricsWith()
{
  const int attributes = Fixed >= 0 ? Fixed : Attributes;
  const std::size_t size = Quadric::Size(attributes);
  const std::size_t recordSize = size + 1;
  double q[Quadric::Size(MaxAttributes) + 1];
  for (std::size_t t = 0; t < TriangleCount; ++t)
  {
    if (Faces[t].Removed)
    {
      continue;
    }
    const std::uint32_t* tri = Faces[t].V;
    const double* p0 = Position(tri[0]);
    double e1[3], e2[3], n[3];
    Sub(Position(tri[1]), p0, e1);
    Sub(Position(tri[2]), p0, e2);
    Cross(e1, e2, n);
    const double length = std::sqrt(Dot(n, n));
    if (length == 0)
    {
      continue; // no plane to speak of
    }
    for (double& x : n)
    {
      x /= length;
    }
    const double d = -Dot(n, p0);
    const double area = 0.5 * length;

    // Hoppe's linear attribute field over the triangle: g.p + d equals the attribute at the
    // corners, with g in the triangle's plane.
    double g[3 * MaxAttributes], offset[MaxAttributes];
    if (attributes > 0)
    {
      double c1[3], c2[3];
      Cross(e2, n, c1);
      Cross(n, e1, c2);
      const double* s0 = AttributesOf(tri[0]);
      const double* s1 = AttributesOf(tri[1]);
      const double* s2 = AttributesOf(tri[2]);
      for (int j = 0; j < attributes; ++j)
      {
        const double d1 = (s1[j] - s0[j]) / length;
        const double d2 = (s2[j] - s0[j]) / length;
        for (int a = 0; a < 3; ++a)
        {
          g[3 * j + a] = d1 * c1[a] + d2 * c2[a];
        }
        offset[j] = s0[j] - Dot(g + 3 * j, p0);
      }
    }
    Quadric::SetTriangleWith<Fixed>(q, n, d, attributes, g, offset, area);
    q[size] = area;
    Quadric::AddToCorners(Record(tri[0]), Record(tri[1]), Record(tri[2]), q, recordSize);

    for (int k = 0; k < 3; ++k)
    {
      if (!(Faces[t].Bits & (1u << k)))
      {
        continue;
      }
      const std::uint32_t a = tri[k], b = tri[NextCorner(k)];
      double edge[3], m[3];
      Sub(Position(b), Position(a), edge);
      Cross(edge, n, m);
      const double mLength = std::sqrt(Dot(m, m));
      if (mLength == 0)
      {
        continue;
      }
      for (double& x : m)
      {
        x /= mLength;
      }
      const double md = -Dot(m, Position(a));
      const double w = BoundaryPlaneWeight * Dot(edge, edge);
      for (std::uint32_t v : { a, b })
      {
        Quadric::AddPlane(Record(v), m, md, w);
        Record(v)[size] += w;
      }
    }
  }
}

void Simplifier::ShapeFan(std::uint32_t u)
{
  if (ShapedFan == u)
  {
    return;
  }
  ShapedFan = u;
  const double* pu = Position(u);
  FanCross.resize(3 * Fan.size());
  std::fill_n(FanNormal, 3, 0.0);
  double* n = FanCross.data();
  for (std::uint32_t c : Fan)
  {
    const std::uint32_t t = TriangleOf(c);
    const int k = CornerSlot(c);
    double a[3], b[3];
    Sub(Position(Faces[t].V[NextCorner(k)]), pu, a);
    Sub(Position(Faces[t].V[PrevCorner(k)]), pu, b);
    Cross(a, b, n);
    for (int i = 0; i < 3; ++i)
    {
      FanNormal[i] += n[i];
    }
    n += 3;
  }
}

// u -> v is legal when: the edge is manifold (1 or 2 triangles), the link condition holds (the
// only common neighbors are the opposite corners), no edge from v to an opposite corner is
// non-manifold, no triangle is removed with both other edges open (an isolated triangle would
// vanish), u and v do not share all their triangles (two triangles back to back would vanish,
// leaving v none to measure its error against), the mesh is not a tetrahedron-like pocket (a
// moved triangle would duplicate one of v), and no moved triangle flips or degenerates. Nor may a
// moved triangle face within 10 degrees of edge-on to u's fan normal (before the regions over
// quota run out of other collapses) or against it (before they run out of those too).
// Fan must hold u's fan. The geometric tests come first: they reject most candidates (flips and
// facing, 4 in 10 on the brain) and need no walk around v.
bool Simplifier::CanCollapse(std::uint32_t u, std::uint32_t v)
{
  std::uint32_t opposite[2] = { None, None };
  int opposites = 0;
  const double* pv = Position(v);
  const double minFacing2 = Facing == FacingGuard::NoFins ? FinCosine * FinCosine : 0;
  ShapeFan(u);
  const double fanNormal2 = Dot(FanNormal, FanNormal);
  const double* before = FanCross.data() - 3;
  for (std::uint32_t c : Fan)
  {
    before += 3;
    const std::uint32_t t = TriangleOf(c);
    const int k = CornerSlot(c);
    const std::uint32_t x = Faces[t].V[NextCorner(k)];
    const std::uint32_t y = Faces[t].V[PrevCorner(k)];
    if (x == v || y == v)
    {
      if (opposites == 2)
      {
        return false;
      }
      opposite[opposites++] = x == v ? y : x;
      continue;
    }
    const double* px = Position(x);
    const double* py = Position(y);
    double a[3], b[3], after[3];
    Sub(px, pv, a);
    Sub(py, pv, b);
    Cross(a, b, after);
    const double area2 = Dot(after, after);
    if (Dot(before, after) <= 0 || area2 <= DegenerateSine2 * Dot(a, a) * Dot(b, b))
    {
      return false;
    }
    // Small turns, each allowed, add up to folds: the face must also agree with the surface
    // around u.
    if (Facing != FacingGuard::Off)
    {
      const double facing = Dot(after, FanNormal);
      if (facing <= 0 || facing * facing <= minFacing2 * area2 * fanNormal2)
      {
        return false;
      }
    }
  }
  if (opposites == 0)
  {
    return false;
  }

  ++StampV;
  std::size_t vTriangles = 0;
  ForEachCorner(v, [&](std::uint32_t t, int k) {
    ++vTriangles;
    for (std::uint32_t x : { Faces[t].V[NextCorner(k)], Faces[t].V[PrevCorner(k)] })
    {
      Marks[x].CountV = (Marks[x].CountV & Restamp(Marks[x].MarkV, StampV)) + 1;
    }
  });
  if (Fan.size() == std::size_t(opposites) && vTriangles == std::size_t(opposites))
  {
    return false; // u and v share all their triangles: v would be left with none
  }
  ++StampU;
  bool movesPocket = false;
  for (std::uint32_t c : Fan)
  {
    const std::uint32_t t = TriangleOf(c);
    const int k = CornerSlot(c);
    const std::uint32_t x = Faces[t].V[NextCorner(k)];
    const std::uint32_t y = Faces[t].V[PrevCorner(k)];
    const bool moves = x != v && y != v;
    for (std::uint32_t z : { x, y })
    {
      Marks[z].CountU = (Marks[z].CountU & Restamp(Marks[z].MarkU, StampU)) + 1;
      if (moves && Marks[z].MarkV == StampV && z != opposite[0] && z != opposite[1])
      {
        return false;
      }
    }
    movesPocket = movesPocket || (moves && opposites == 2 && Marks[x].MarkV == StampV && Marks[y].MarkV == StampV);
  }
  for (int i = 0; i < opposites; ++i)
  {
    const std::uint32_t w = opposite[i];
    if (Marks[w].CountV > 2 || (Marks[w].CountV == 1 && Marks[w].CountU == 1))
    {
      return false;
    }
  }
  if (movesPocket)
  {
    // A moved triangle becomes (v, a, b) with a, b the opposite corners: it must not exist yet.
    bool exists = false;
    ForEachCorner(v, [&](std::uint32_t t, int) {
      exists = exists || (!Contains(t, u) && Contains(t, opposite[0]) && Contains(t, opposite[1]));
    });
    if (exists)
    {
      return false;
    }
  }
  return true;
}

void Simplifier::Queue(std::uint32_t u, const Candidate& candidate)
{
  Best[u] = candidate;
  Waiting.Set(u, std::size_t(candidate.Region), candidate.Cost);
}

template <typename Consider>
void Simplifier::ForEachCollapse(std::uint32_t u, Consider consider)
{
  if (Kind[u] == VertexKind::Free)
  {
    // Each neighbor is the next corner of one triangle and the previous corner of another:
    // the two triangles the collapse removes. The second's region matters only with several
    // regions, not all over their quotas: otherwise every collapse ranks first and waits in
    // the first triangle's region (Ranked), whatever the second's.
    ++StampU;
    const bool ranksDiffer = RegionCount > 1 && Total <= TotalQuota && RegionsOver < std::size_t(RegionCount);
    for (std::size_t i = 0; ranksDiffer && i < Fan.size(); ++i)
    {
      const std::uint32_t t = TriangleOf(Fan[i]);
      VertexMarks& previous = Marks[Faces[t].V[PrevCorner(CornerSlot(Fan[i]))]];
      previous.MarkU = StampU;
      previous.SlotU = t;
    }
    for (std::uint32_t c : Fan)
    {
      const std::uint32_t t = TriangleOf(c);
      const std::uint32_t x = Faces[t].V[NextCorner(CornerSlot(c))];
      const int other = ranksDiffer && Marks[x].MarkU == StampU ? Faces[Marks[x].SlotU].Region : Faces[t].Region;
      consider(x, Faces[t].Region, other);
    }
    return;
  }
  for (std::uint32_t c : Fan)
  {
    const std::uint32_t t = TriangleOf(c);
    const int k = CornerSlot(c);
    if (Faces[t].Bits & (1u << k))
    {
      consider(Faces[t].V[NextCorner(k)], Faces[t].Region, Faces[t].Region);
    }
    if (Faces[t].Bits & (1u << PrevCorner(k)))
    {
      consider(Faces[t].V[PrevCorner(k)], Faces[t].Region, Faces[t].Region);
    }
  }
}

// Finds u's cheapest collapse, preferring those that remove triangles of regions over their
// quotas only, and queues it in such a region's queue.
template <int Fixed>
void Simplifier::EvaluateWith(std::uint32_t u, bool checkLegal, std::uint32_t refused)
{
  if (Kind[u] != VertexKind::Free && Kind[u] != VertexKind::Boundary)
  {
    return;
  }
  Best[u] = Candidate();
  if (!checkLegal)
  {
    GatherFan(u);
  }
  const double* record = Record(u);
  Candidate cheapest;
  if (checkLegal)
  {
    Candidates.clear();
    ForEachCollapse(u, [&](std::uint32_t target, int regionA, int regionB) {
      if (target != refused)
      {
        Candidates.push_back(Ranked(Cost<Fixed>(record, target), target, regionA, regionB));
      }
    });
    // A lambda rather than Before itself: a function pointer is called, not inlined.
    std::sort(Candidates.begin(), Candidates.end(),
      [](const Candidate& a, const Candidate& b) { return Before(a, b); });
    for (const Candidate& candidate : Candidates)
    {
      if (CanCollapse(u, candidate.Target))
      {
        cheapest = candidate;
        break;
      }
    }
  }
  else
  {
    // Only the cheapest matters: a target of a worse rank than the best so far is not priced,
    // and the others are compared in Before's order on loose fields (building a candidate for
    // each and calling Before measured 2.8% more instructions per simplification), by their
    // quadric error: all costs of u divide it by the same weight, once for the cheapest.
    int rank = 3;
    double error = 0;
    std::uint32_t target = None;
    int regions[2] = { 0, 0 };
    ForEachCollapse(u, [&](std::uint32_t x, int regionA, int regionB) {
      const int xRank = RankOf(regionA, regionB);
      if (xRank > rank)
      {
        return;
      }
      const double xError = QuadricError<Fixed>(record, x);
      if (xRank < rank || xError < error || (xError == error && x < target))
      {
        rank = xRank;
        error = xError;
        target = x;
        regions[0] = regionA;
        regions[1] = regionB;
      }
    });
    if (target != None)
    {
      cheapest = Ranked(error / Weight(record), target, regions[0], regions[1]);
    }
  }
  if (cheapest.Target != None)
  {
    Queue(u, cheapest);
  }
  else
  {
    Waiting.Remove(u);
  }
}

void Simplifier::NoteRegionsAround(std::uint32_t v)
{
  ++StampV;
  ForEachCorner(v, [&](std::uint32_t t, int k) {
    const std::uint32_t before = Faces[t].V[PrevCorner(k)];
    const std::uint32_t after = Faces[t].V[NextCorner(k)];
    for (std::uint32_t x : { before, after })
    {
      const int keep = int(Restamp(Marks[x].MarkV, StampV));
      RegionFollowing[x] &= keep;
      RegionPreceding[x] &= keep;
    }
    RegionFollowing[before] = Faces[t].Region;
    RegionPreceding[after] = Faces[t].Region;
  });
}

void Simplifier::Offer(std::uint32_t x, std::uint32_t v)
{
  if (Kind[x] != VertexKind::Free || Best[x].Target == None || Kind[Best[x].Target] == VertexKind::Removed)
  {
    Evaluate(x, false);
    return;
  }
  const bool noted = RegionCount > 1 && Marks[x].MarkV == StampV;
  const Candidate candidate =
    Price(x, v, noted ? RegionFollowing[x] : 0, noted ? RegionPreceding[x] : 0);
  if (Before(candidate, Best[x]))
  {
    Queue(x, candidate);
  }
}

int Simplifier::MovedRegionOf(std::uint32_t t, std::uint32_t u, std::uint32_t v) const
{
  const float* pv = &Mesh.Positions[3 * std::size_t(v)];
  double centroid[3];
  for (int a = 0; a < 3; ++a)
  {
    double sum = double(pv[a]);
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t x = Faces[t].V[k];
      sum += x == u ? 0.0 : double(Mesh.Positions[3 * std::size_t(x) + std::size_t(a)]);
    }
    centroid[a] = sum / 3;
  }
  return RegionOf(centroid, Faces[t].Region);
}

std::int64_t Simplifier::ExcessChange(std::uint32_t u, std::uint32_t v)
{
  Touched.clear();
  MovedRegions.clear();
  std::int64_t totalDelta = 0;
  auto change = [&](int r, std::int64_t d) {
    if (Delta[std::size_t(r)] == 0 && std::find(Touched.begin(), Touched.end(), r) == Touched.end())
    {
      Touched.push_back(r);
    }
    Delta[std::size_t(r)] += d;
    totalDelta += d;
  };
  for (std::uint32_t c : Fan)
  {
    const std::uint32_t t = TriangleOf(c);
    if (Contains(t, v))
    {
      change(Faces[t].Region, -1);
      MovedRegions.push_back(-1);
      continue;
    }
    if (RegionCount == 1)
    {
      MovedRegions.push_back(0); // nothing to ask
      continue;
    }
    const std::uint32_t* tri = Faces[t].V;
    int r = SharedDeepRegion(tri[0] == u ? v : tri[0], tri[1] == u ? v : tri[1], tri[2] == u ? v : tri[2]);
    if (r < 0)
    {
      r = MovedRegionOf(t, u, v);
    }
    MovedRegions.push_back(r);
    if (r != Faces[t].Region)
    {
      change(Faces[t].Region, -1);
      change(r, +1);
    }
  }
  std::int64_t result = std::max<std::int64_t>(0, Total + totalDelta - TotalQuota) -
    std::max<std::int64_t>(0, Total - TotalQuota);
  for (int r : Touched)
  {
    const std::int64_t count = Counts[std::size_t(r)];
    const std::int64_t quota = std::int64_t(Quotas[std::size_t(r)]);
    result += std::max<std::int64_t>(0, count + Delta[std::size_t(r)] - quota) -
      std::max<std::int64_t>(0, count - quota);
  }
  return result;
}

// The removed triangle t = (u, v, w): its edges v-w and w-u become one. When exactly one of them
// was open, the survivor carries that edge's boundary bit. An input edge of three or more
// triangles on v-w (u moves, so w-u is none) stays marked on the triangle across w-u, which
// takes its place, or else on the one across v-w: another patch may still hold the edge, and
// the next level must lock it too.
void Simplifier::FixOpenEdge(std::uint32_t t, std::uint32_t u, std::uint32_t v, std::uint32_t w)
{
  const bool openVW = Faces[t].Bits & (1u << EdgeBit(t, v, w));
  const bool openWU = Faces[t].Bits & (1u << EdgeBit(t, w, u));
  const bool manySheetsVW = Faces[t].Bits & (8u << EdgeBit(t, v, w));
  if (!openVW && !openWU && !manySheetsVW)
  {
    return; // the usual interior case: nothing to carry
  }
  const std::uint32_t acrossWU = TriangleAcrossWU(t, v, w);
  const std::uint32_t acrossVW = TriangleAcrossVW(t, u, v, w);
  if (acrossWU != None && acrossVW == None && openVW)
  {
    Faces[acrossWU].Bits |= std::uint8_t(1u << EdgeBit(acrossWU, u, w));
  }
  if (manySheetsVW && acrossWU != None)
  {
    Faces[acrossWU].Bits |= std::uint8_t(8u << EdgeBit(acrossWU, u, w));
  }
  else if (manySheetsVW && acrossVW != None)
  {
    Faces[acrossVW].Bits |= std::uint8_t(8u << EdgeBit(acrossVW, v, w)); // the edge's other side
  }
  if (acrossVW != None && acrossWU == None && openWU)
  {
    Faces[acrossVW].Bits |= std::uint8_t(1u << EdgeBit(acrossVW, v, w));
  }
}

std::uint32_t Simplifier::TriangleAcrossWU(std::uint32_t t, std::uint32_t v, std::uint32_t w) const
{
  std::uint32_t across = None;
  for (std::uint32_t c : Fan)
  {
    const std::uint32_t s = TriangleOf(c);
    if (s != t && !Contains(s, v) && Contains(s, w))
    {
      across = s;
    }
  }
  return across;
}

std::uint32_t Simplifier::TriangleAcrossVW(
  std::uint32_t t, std::uint32_t u, std::uint32_t v, std::uint32_t w) const
{
  std::uint32_t across = None;
  ForEachCorner(v, [&](std::uint32_t s, int) {
    if (s != t && !Contains(s, u) && Contains(s, w))
    {
      across = s;
    }
  });
  return across;
}

void Simplifier::HandOverUses(std::uint32_t t, std::uint32_t v, std::uint32_t w, std::uint32_t heir)
{
  for (const std::uint32_t x : { v, w })
  {
    const int from = Faces[t].V[0] == x ? 0 : (Faces[t].V[1] == x ? 1 : 2);
    const int to = Faces[heir].V[0] == x ? 0 : (Faces[heir].V[1] == x ? 1 : 2);
    std::uint8_t& uses = Faces[heir].Uses[to];
    uses = std::uint8_t(std::min<unsigned>(ManyInputUses, uses + Faces[t].Uses[from]));
  }
}

void Simplifier::CompactCorners(std::size_t extra)
{
  std::size_t held = extra;
  for (const FanSlice& fan : Fans)
  {
    held += fan.Count;
  }
  std::vector<std::uint32_t> compact;
  compact.reserve(2 * held);
  for (FanSlice& fan : Fans)
  {
    const std::uint32_t start = std::uint32_t(compact.size());
    AppendLiveCorners(fan, compact);
    fan = FanSlice{ start, std::uint32_t(compact.size()) - start };
  }
  Corners.swap(compact);
}

// Moves u onto v; Fan holds u's fan and MovedRegions the new region of each of its triangles.
void Simplifier::Collapse(std::uint32_t u, std::uint32_t v)
{
  // The removed triangles (u, v, w): two, or one on the boundary, since u's fan is a disk or a
  // half-disk. Noted without a branch (which ones they are follows no pattern); w is what is
  // left of the corners once u and v are taken out.
  std::uint32_t removed[3] = { None, None, None }, third[3] = { None, None, None };
  int removedCount = 0;
  for (std::size_t i = 0; i < Fan.size(); ++i)
  {
    const std::uint32_t t = TriangleOf(Fan[i]);
    const std::uint32_t* tri = Faces[t].V;
    const std::uint32_t w = tri[0] ^ tri[1] ^ tri[2] ^ u ^ v;
    const bool gone = MovedRegions[i] < 0;
    // Only a removed triangle with an open edge has one to carry; most have none, which is
    // asked first.
    if (Faces[t].Bits != 0 && gone)
    {
      FixOpenEdge(t, u, v, w);
    }
    removed[removedCount] = t;
    third[removedCount] = w;
    removedCount = std::min(removedCount + int(gone), 2);
  }
  // The heir of a removed triangle (u, v, w): the moved one across w-u, which takes the edge
  // v-w over (w lies on two triangles of u's fan); found as the corners move.
  std::uint32_t heir[2] = { None, None };
  for (std::size_t i = 0; i < Fan.size(); ++i)
  {
    // Removed or moved, without a branch: a removed triangle keeps its corner and region and
    // adds nothing back.
    const std::uint32_t c = Fan[i];
    const std::uint32_t t = TriangleOf(c);
    const bool gone = MovedRegions[i] < 0;
    for (int k = 0; k < 2 && TracksUses; ++k)
    {
      // Without a branch: which triangle it is follows no pattern.
      const std::uint32_t* tri = Faces[t].V;
      const bool holds = (tri[0] == third[k]) | (tri[1] == third[k]) | (tri[2] == third[k]);
      heir[k] = holds & !gone ? t : heir[k];
    }
    CountTriangles(Faces[t].Region, -1);
    Faces[t].Removed = std::uint8_t(gone);
    VertexAt(c) = gone ? u : v;
    Faces[t].Uses[CornerSlot(c)] = 0; // it stood for u's, and u is gone
    Faces[t].Region = gone ? Faces[t].Region : std::int16_t(MovedRegions[i]);
    CountTriangles(Faces[t].Region, std::int64_t(!gone));
  }
  for (int k = 0; k < removedCount && TracksUses; ++k)
  {
    if (heir[k] == None) // w-u is open: the triangle across v-w takes it
    {
      heir[k] = TriangleAcrossVW(removed[k], u, v, third[k]);
    }
    if (heir[k] != None)
    {
      HandOverUses(removed[k], v, third[k], heir[k]);
    }
  }
  // v's new fan: u's moved corners, then v's own. Compacting moves u's run: Fan is not read
  // after it.
  if (Corners.size() + Fans[u].Count + Fans[v].Count > Corners.capacity())
  {
    CompactCorners(Fans[u].Count + Fans[v].Count);
  }
  const std::uint32_t start = std::uint32_t(Corners.size());
  AppendLiveCorners(Fans[u], Corners);
  AppendLiveCorners(Fans[v], Corners);
  Fans[v] = FanSlice{ start, std::uint32_t(Corners.size()) - start };
  Fans[u] = FanSlice();
  Kind[u] = VertexKind::Removed;
  Best[u] = Candidate();

  Into[u] = v;
  CollapseOrder.push_back(u);
  Quadric::Add(Record(v), Record(u), RecordSize);
}

void Simplifier::FindPieces()
{
  PiecesFound = true;
  // Union-find over the vertices of the live triangles.
  std::vector<std::uint32_t> root(VertexCount);
  std::iota(root.begin(), root.end(), 0u);
  const auto find = [&](std::uint32_t x) {
    while (root[x] != x)
    {
      root[x] = root[root[x]];
      x = root[x];
    }
    return x;
  };
  const auto live = [&](std::uint32_t t) { return !Faces[t].Removed; };
  for (std::uint32_t t = 0; t < TriangleCount; ++t)
  {
    for (int k = 1; k < 3 && live(t); ++k)
    {
      const std::uint32_t a = find(Faces[t].V[0]);
      const std::uint32_t b = find(Faces[t].V[k]);
      root[std::max(a, b)] = std::min(a, b);
    }
  }
  // A component none of whose vertices is locked (on the diamond's external border, or on a
  // non-manifold edge or fan) lies wholly inside the diamond: closed, or open only along the
  // input's own boundary.
  std::vector<std::uint8_t> closed(VertexCount, 1);
  for (std::uint32_t t = 0; t < TriangleCount; ++t)
  {
    for (int k = 0; k < 3 && live(t); ++k)
    {
      const VertexKind kind = Kind[Faces[t].V[k]];
      closed[find(Faces[t].V[k])] &= std::uint8_t(kind == VertexKind::Free || kind == VertexKind::Boundary);
    }
  }
  std::vector<std::uint32_t> pieceOfRoot(VertexCount, None);
  std::vector<std::uint32_t> pieceOfTriangle(TriangleCount, None);
  for (std::uint32_t t = 0; t < TriangleCount; ++t)
  {
    const std::uint32_t r = live(t) ? find(Faces[t].V[0]) : None;
    if (r == None || !closed[r])
    {
      continue;
    }
    if (pieceOfRoot[r] == None)
    {
      pieceOfRoot[r] = std::uint32_t(Pieces.size());
      Pieces.emplace_back();
      Pieces.back().Smallest = r; // a root is the smallest vertex of its set
    }
    pieceOfTriangle[t] = pieceOfRoot[r];
    ++Pieces[pieceOfRoot[r]].Count;
  }
  PieceTriangles.resize(StartRuns(Pieces));
  for (std::uint32_t t = 0; t < TriangleCount; ++t)
  {
    if (pieceOfTriangle[t] != None)
    {
      Piece& piece = Pieces[pieceOfTriangle[t]];
      PieceTriangles[piece.Start + piece.Count++] = t;
    }
  }
  // Centered on its box, in input coordinates as the error is measured.
  for (Piece& piece : Pieces)
  {
    double lo[3] = { 1e300, 1e300, 1e300 };
    double hi[3] = { -1e300, -1e300, -1e300 };
    for (std::uint32_t i = piece.Start; i < piece.Start + piece.Count; ++i)
    {
      for (std::uint32_t v : Faces[PieceTriangles[i]].V)
      {
        for (std::size_t a = 0; a < 3; ++a)
        {
          lo[a] = std::min(lo[a], double(Mesh.Positions[3 * std::size_t(v) + a]));
          hi[a] = std::max(hi[a], double(Mesh.Positions[3 * std::size_t(v) + a]));
        }
      }
    }
    for (std::size_t a = 0; a < 3; ++a)
    {
      piece.Center[a] = (lo[a] + hi[a]) / 2;
      piece.Radius2 += (hi[a] - lo[a]) * (hi[a] - lo[a]) / 4;
    }
  }
  std::sort(Pieces.begin(), Pieces.end(), [](const Piece& a, const Piece& b) {
    return a.Radius2 < b.Radius2 || (a.Radius2 == b.Radius2 && a.Smallest < b.Smallest);
  });
}

bool Simplifier::RemoveSmallestPiece(bool anySize)
{
  if (!PiecesFound)
  {
    FindPieces();
  }
  const std::size_t collapses = CollapseOrder.size() - Vanished;
  if (!anySize && collapses != MeasuredCollapses)
  {
    const double deviation = Deviation();
    Deviation2 = deviation * deviation;
    MeasuredCollapses = collapses;
  }
  while (FirstLeft < Pieces.size() && Pieces[FirstLeft].Removed)
  {
    ++FirstLeft;
  }
  for (std::size_t i = FirstLeft; i < Pieces.size(); ++i)
  {
    Piece& piece = Pieces[i];
    const std::uint32_t* first = PieceTriangles.data() + piece.Start;
    const std::uint32_t* last = first + piece.Count;
    if (!anySize && piece.Radius2 > Deviation2)
    {
      return false; // and so are all after it
    }
    if (piece.Removed || std::none_of(first, last, [&](std::uint32_t t) {
          return !Faces[t].Removed && OverQuota(Faces[t].Region);
        }))
    {
      continue;
    }
    piece.Removed = true;
    PieceOf.resize(VertexCount, None);
    for (const std::uint32_t* t = first; t != last; ++t)
    {
      Face& face = Faces[*t];
      if (face.Removed)
      {
        continue; // collapsed away since the pieces were found
      }
      face.Removed = 1;
      CountTriangles(face.Region, -1);
      for (std::uint32_t v : face.V)
      {
        if (Kind[v] != VertexKind::Removed)
        {
          Kind[v] = VertexKind::Removed;
          Best[v] = Candidate();
          Waiting.Remove(v);
          Fans[v] = FanSlice();
          Into[v] = v;
          PieceOf[v] = std::uint32_t(i);
          CollapseOrder.push_back(v);
          ++Vanished;
        }
      }
    }
    Excess = ExcessOverQuotas();
    return true;
  }
  return false;
}

SimplifyResult Simplifier::Run()
{
  const auto classifyAll = [this] {
    for (std::uint32_t v = 0; v < VertexCount; ++v)
    {
      Classify(v);
    }
  };
  LinkCorners();
  AssignRegions();
  classifyAll();
  // Counted at both triangles of an edge: edges two triangles run the same way, as a share
  // (SimplifyResult::FacingAtRandom).
  FacingAtRandom = MisorientedEdges > TriangleCount / 2;
  if (MisorientedEdges > 0 && OrientConsistently())
  {
    // Where faces turn every which way, the input's vertex normals were summed over faces of
    // both facings: noise that would order the collapses (the coarsest error of a sphere with
    // half its faces turned at random was 7 times that of the sphere), so shading is left out
    // of the pricing. A few such edges (sheets that touch, a seam between two consistent
    // parts) spoil only the normals along them.
    if (NormalAttributes && FacingAtRandom)
    {
      for (std::size_t v = 0; v < VertexCount; ++v)
      {
        std::fill_n(&Point[PointSize * v + 3], 3, 0.0);
      }
    }
    LinkCorners();
    Kind.assign(VertexCount, VertexKind::Locked);
    classifyAll();
  }
  BuildQuadrics();
  if (Excess > 0)
  {
    for (std::uint32_t v = 0; v < VertexCount; ++v)
    {
      Evaluate(v, false);
    }
  }
  Waiting.Order();

  while (Excess > 0)
  {
    // The cheapest collapse waiting for any region over its quota.
    int best = -1;
    for (int r = 0; r < RegionCount; ++r)
    {
      if (OverQuota(r) && !Waiting.Empty(std::size_t(r)) &&
        (best < 0 ||
          CollapseQueues::Before(Waiting.Front(std::size_t(r)), Waiting.Front(std::size_t(best)))))
      {
        best = r;
      }
    }
    if (best < 0)
    {
      if (!Relaxed && !Deferred.empty())
      {
        Relaxed = true;
        for (std::uint32_t u : Deferred)
        {
          Evaluate(u, false);
        }
        continue;
      }
      // A piece within the error made so far goes before the guard relaxes: it costs no
      // error, where a fin or a face against the surface shows and is not measured. Larger ones
      // go only when nothing else is left: their removal enters the error, so the cut refines
      // before it can show.
      if (RemoveSmallestPiece(Facing == FacingGuard::Off))
      {
        continue;
      }
      if (Facing == FacingGuard::Off) // the guards are off already: nothing legal is left at all
      {
        break;
      }
      // Still over quota with no legal collapse left: a fin, and then a face against the
      // surface it replaces, are lesser evils than a patch over its budget. Every vertex is
      // priced again with the guard relaxed.
      Facing = FacingGuard(int(Facing) + 1);
      for (std::uint32_t v = 0; v < VertexCount; ++v)
      {
        Evaluate(v, false);
      }
      continue;
    }
    const std::uint32_t u = Waiting.Front(std::size_t(best)).Vertex;
    Waiting.Remove(u);
    const std::uint32_t v = Best[u].Target;
    GatherFan(u);
    if (!CanCollapse(u, v))
    {
      Evaluate(u, true, v);
      continue;
    }
    const std::int64_t change = ExcessChange(u, v);
    bool takesFromSatisfied = false;
    for (int r : Touched)
    {
      takesFromSatisfied = takesFromSatisfied || (Delta[std::size_t(r)] < 0 && !OverQuota(r));
      Delta[std::size_t(r)] = 0;
    }
    if (change >= 0 || (takesFromSatisfied && !Relaxed))
    {
      // It would only shift triangles between regions, or eat into a region that already
      // meets its quota (allowed only when nothing else is left): u waits for new neighbors.
      Best[u] = Candidate();
      if (change < 0)
      {
        Deferred.push_back(u);
      }
      continue;
    }
    // The costs are u's quadric at its targets' positions: only u's neighbors lose a target (u)
    // and gain one (v), and only v's quadric changes. Legality is checked when popped.
    ++StampV;
    Marks[u].MarkV = StampV; // not a neighbor of its own
    Neighbors.resize(3 * Fan.size());
    std::size_t neighbors = 0;
    for (std::uint32_t c : Fan)
    {
      const std::uint32_t t = TriangleOf(c);
      for (int k = 0; k < 3; ++k)
      {
        const std::uint32_t x = Faces[t].V[k];
        Neighbors[neighbors] = x;
        neighbors += ~Restamp(Marks[x].MarkV, StampV) & 1;
      }
    }
    Neighbors.resize(neighbors);
    // The offers below read each neighbor's record and queued collapse: start the loads now,
    // so that they overlap (large diamonds do not fit the cache, and the offers are serial).
    for (std::uint32_t x : Neighbors)
    {
      __builtin_prefetch(Record(x));
      __builtin_prefetch(&Best[x]);
    }
    Collapse(u, v);
    Excess += change;
    if (RegionCount > 1)
    {
      NoteRegionsAround(v);
    }
    for (std::uint32_t x : Neighbors)
    {
      if (x == v)
      {
        Evaluate(x, false);
      }
      else
      {
        Offer(x, v);
      }
    }
  }

  SimplifyResult result;
  result.Error = Deviation();
  result.Collapses = CollapseOrder.size() - Vanished;
  result.PiecesRemoved =
    std::size_t(std::count_if(Pieces.begin(), Pieces.end(), [](const Piece& p) { return p.Removed; }));
  result.TrianglesOverQuotas = std::uint64_t(Excess);
  result.FacingAtRandom = FacingAtRandom;
  std::vector<std::vector<std::uint32_t>> byRegion(static_cast<std::size_t>(RegionCount));
  for (std::uint32_t t = 0; t < TriangleCount; ++t)
  {
    if (!Faces[t].Removed)
    {
      byRegion[std::size_t(Faces[t].Region)].push_back(t);
    }
  }
  for (int r = 0; r < RegionCount; ++r)
  {
    result.Regions.push_back(Extract(byRegion[std::size_t(r)]));
  }
  return result;
}

/// Squared distance from p to the triangle (a, b, c).
double DistanceToTriangle2(const double* p, const double* a, const double* b, const double* c)
{
  const TrianglePoint nearest = ClosestOnTriangle(p, a, b, c);
  double e[3];
  Sub(p, nearest.Point, e);
  return Dot(e, e);
}

// Each removed vertex is measured against the output triangles around the vertex it ended in,
// then walks to a corner of its closest triangle while that corner's fan comes closer. Not
// stopping where the closest point is interior to a face: on a tilted face that is no nearest
// point of the surface (on a bumpy grid, stopping there reported 4 times the distance). Any set
// of output triangles gives an upper bound of the distance to the whole output surface; the walk
// makes it (nearly always) the exact distance. Only the largest distance is wanted: a vertex is
// done as soon as one triangle lies within the largest found so far (its own distance cannot
// exceed that), and the last collapses, the costly ones, are measured first so that the bound is
// large early. The result is the same as measuring every vertex in full.
double Simplifier::Deviation()
{
  const auto at = [&](std::uint32_t v, double* p) {
    for (int a = 0; a < 3; ++a)
    {
      p[a] = double(Mesh.Positions[3 * std::size_t(v) + std::size_t(a)]);
    }
  };
  double p[3];
  double max2 = 0;
  // The squared distance from p to the fan of v and its closest triangle; or, as soon as one
  // triangle is within max2, that triangle's.
  const auto fanDistance2 = [&](std::uint32_t v, std::uint32_t& closest) {
    GatherFan(v);
    double nearest2 = 1e300;
    for (std::uint32_t c : Fan)
    {
      const std::uint32_t t = TriangleOf(c);
      double corners[3][3];
      for (int k = 0; k < 3; ++k)
      {
        at(Faces[t].V[k], corners[k]);
      }
      const double d2 = DistanceToTriangle2(p, corners[0], corners[1], corners[2]);
      if (d2 < nearest2)
      {
        nearest2 = d2;
        closest = t;
      }
      if (d2 <= max2)
      {
        break;
      }
    }
    return nearest2;
  };
  for (auto removed = CollapseOrder.rbegin(); removed != CollapseOrder.rend(); ++removed)
  {
    const std::uint32_t u = *removed;
    std::uint32_t v = Into[u];
    while (Kind[v] == VertexKind::Removed && Into[v] != v)
    {
      v = Into[v];
    }
    Into[u] = v; // earlier collapses that ended here find it at once
    at(u, p);
    if (Kind[v] == VertexKind::Removed)
    {
      // Vanished with its piece: counted as moved to the piece's center.
      double e[3];
      Sub(p, Pieces[PieceOf[v]].Center, e);
      max2 = std::max(max2, Dot(e, e));
      continue;
    }
    std::uint32_t closest = None;
    double nearest2 = fanDistance2(v, closest);
    for (bool moved = closest != None; moved && nearest2 > max2;)
    {
      moved = false;
      const std::uint32_t* tri = Faces[closest].V;
      const std::uint32_t corners[3] = { tri[0], tri[1], tri[2] };
      for (std::uint32_t x : corners)
      {
        std::uint32_t t = None;
        const double d2 = x == v ? 1e300 : fanDistance2(x, t);
        if (d2 < nearest2)
        {
          nearest2 = d2;
          closest = t;
          v = x;
          moved = true;
          break;
        }
      }
    }
    max2 = std::max(max2, nearest2);
  }
  return std::sqrt(max2);
}

PatchMesh Simplifier::Extract(const std::vector<std::uint32_t>& triangles)
{
  PatchMesh out;
  const bool normals = Mesh.Normals.size() == 3 * VertexCount;
  const bool colors = Mesh.Colors.size() == 4 * VertexCount;
  // MarkU/SlotU map input vertices to output ones, stamped per region; the vertices are
  // numbered first, then copied into arrays sized once.
  ++StampU;
  std::vector<std::uint32_t> used; // input vertex of each output vertex
  out.Indices.resize(3 * triangles.size());
  out.BoundaryEdges.resize(triangles.size());
  out.CornerUses.reserve(TracksUses ? 3 * triangles.size() : 0);
  for (std::size_t i = 0; i < triangles.size(); ++i)
  {
    const Face& face = Faces[triangles[i]];
    // A triangle OrientConsistently flipped goes out as it came in: corners 1 and 2 and edge
    // bits 0 and 2 (3 and 5) traded back.
    const bool flip = !Flipped.empty() && Flipped[triangles[i]];
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t v = face.V[flip && k > 0 ? 3 - k : k];
      if (Marks[v].MarkU != StampU)
      {
        Marks[v].MarkU = StampU;
        Marks[v].SlotU = std::uint32_t(used.size());
        used.push_back(v);
      }
      out.Indices[3 * i + std::size_t(k)] = Marks[v].SlotU;
    }
    for (int k = 0; k < 3 && TracksUses; ++k)
    {
      out.CornerUses.push_back(face.Uses[flip && k > 0 ? 3 - k : k]);
    }
    out.BoundaryEdges[i] = flip ? FlippedBits(face.Bits) : face.Bits;
  }
  out.Positions.resize(3 * used.size());
  out.Normals.resize(normals ? 3 * used.size() : 0);
  out.Colors.resize(colors ? 4 * used.size() : 0);
  out.InputUses.resize(TracksUses ? used.size() : 0);
  for (std::size_t i = 0; i < used.size(); ++i)
  {
    const std::size_t v = used[i];
    std::copy_n(&Mesh.Positions[3 * v], 3, &out.Positions[3 * i]);
    if (normals)
    {
      std::copy_n(&Mesh.Normals[3 * v], 3, &out.Normals[3 * i]);
    }
    if (colors)
    {
      std::copy_n(&Mesh.Colors[4 * v], 4, &out.Colors[4 * i]);
    }
    if (TracksUses)
    {
      out.InputUses[i] = Mesh.InputUses[v];
    }
  }
  return out;
}

} // namespace

SimplifyResult Simplify(const PatchMesh& mesh, int regionCount, const RegionFunction& regionOf,
  const std::vector<std::uint32_t>& quotas, const SimplifyOptions& options)
{
  return Simplifier(mesh, regionCount, regionOf, quotas, options).Run();
}

} // namespace atp
