#include "atpPatchJob.h"

#include "atpCpuTime.h"
#include "atpMemberLocator.h"
#include "atpMergePatches.h"
#include "atpNormalEncoding.h"
#include "atpPatchCodec.h"
#include "atpSimplifier.h"

#include <algorithm>
#include <cmath>

namespace atp
{
namespace
{

/// Leaves keep every position bit; a simplified patch stores its interior on the coarsest
/// power-of-two grid whose rounding stays a small fraction of its error (the border keeps the
/// full grid, see PatchPrecision).
PatchPrecision PrecisionFor(const QuantizationGrid& grid, double error)
{
  PatchPrecision precision;
  constexpr double ShareOfError = 1.0 / 32;
  PatchPrecision coarser = precision;
  while (++coarser.InteriorPositionShift < QuantizationGrid::Bits &&
    coarser.PositionError(grid) <= ShareOfError * error)
  {
    precision = coarser;
  }
  return precision;
}

/// Encodes the patch; its sphere and cone bound what a reader decodes (quantized), not the
/// mesh before encoding.
void Finish(MadePatch& made, const PatchJobContext& context, const PatchPrecision& precision)
{
  PatchMesh decoded;
  made.Encoded = EncodePatch(made.Mesh, context.Grid, precision, &decoded, context.Order);
  made.Tight = EnclosingSphere(decoded.Positions.data(), decoded.VertexCount());
  made.Cone = FaceNormalCone(decoded);
}

/// The triangles kept so far, by their corners up to rotation: a repeated triangle's copies.
/// Open addressing over the kept triangles' numbers, sized for every triangle of the soup.
class KeptTriangles
{
public:
  explicit KeptTriangles(std::size_t count)
    : Slots(std::size_t(1) << (1 + int(std::ceil(std::log2(double(std::max<std::size_t>(count, 8)))))), None)
  {
  }

  /// Whether a kept triangle of `indices` has the corners of `v` in the same cyclic order; if
  /// none has, triangle `next` (v) is remembered.
  bool Repeats(const std::uint32_t v[3], const std::vector<std::uint32_t>& indices, std::uint32_t next)
  {
    const int lowest = v[0] < v[1] ? (v[0] < v[2] ? 0 : 2) : (v[1] < v[2] ? 1 : 2);
    const std::uint32_t a = v[lowest], b = v[(lowest + 1) % 3], c = v[(lowest + 2) % 3];
    std::uint64_t h = (std::uint64_t(a) * 0x9e3779b97f4a7c15ULL) ^ (std::uint64_t(b) * 0xbf58476d1ce4e5b9ULL) ^
      (std::uint64_t(c) * 0x94d049bb133111ebULL);
    const std::size_t mask = this->Slots.size() - 1;
    for (std::size_t slot = std::size_t(h ^ (h >> 29)) & mask;; slot = (slot + 1) & mask)
    {
      const std::uint32_t t = this->Slots[slot];
      if (t == None)
      {
        this->Slots[slot] = next;
        return false;
      }
      const std::uint32_t* w = &indices[3 * std::size_t(t)];
      for (int r = 0; r < 3; ++r)
      {
        if (w[r] == a && w[(r + 1) % 3] == b && w[(r + 2) % 3] == c)
        {
          return true;
        }
      }
    }
  }

private:
  static constexpr std::uint32_t None = UINT32_MAX;
  std::vector<std::uint32_t> Slots;
};

/// Without input colors the soup's (white) corner colors are left out: the model then has none.
/// Welded as MergePatches welds (the first corner at a position gives its normal and color, and
/// triangles the weld makes degenerate go), straight from the soup: a normal is decoded once per
/// vertex rather than once per corner. A triangle with the corners of a kept one in the same
/// order is a copy and goes too: a leaf holds every copy (they share a centroid, but for the
/// rounding of corners apart in magnitude by over 2^29, which can part rotated copies), and inside a
/// patch the copies hide that another patch shares their edges, whose ends would then move
/// there and not in the other patch, a crack. Their number is added to `repeated`.
PatchMesh WeldSoup(const std::vector<SoupTriangle>& soup, bool colors, std::uint64_t& repeated)
{
  const std::size_t corners = 3 * soup.size();
  PatchMesh mesh;
  mesh.Positions.resize(3 * corners);
  mesh.Normals.resize(3 * corners);
  mesh.Colors.resize(colors ? 4 * corners : 0);
  mesh.InputUses.assign(corners, 0);
  mesh.CornerUses.reserve(corners);
  mesh.Indices.reserve(corners);
  mesh.BoundaryEdges.reserve(soup.size());
  PositionWelder welder(corners, mesh.Positions.data());
  KeptTriangles kept(soup.size());
  for (const SoupTriangle& t : soup)
  {
    std::uint32_t v[3];
    for (int c = 0; c < 3; ++c)
    {
      bool added = false;
      v[c] = welder.Weld(t.V[c], added);
      if (added)
      {
        DecodeNormal(t.Normals[c], &mesh.Normals[3 * std::size_t(v[c])]);
      }
      if (added && colors)
      {
        std::copy_n(t.Colors[c], 4, &mesh.Colors[4 * std::size_t(v[c])]);
      }
      // Unwelded input gives one position several vertices, each counted alone.
      mesh.InputUses[v[c]] = std::max(mesh.InputUses[v[c]], t.InputUses[c]);
    }
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
    {
      continue;
    }
    if (kept.Repeats(v, mesh.Indices, std::uint32_t(mesh.Indices.size() / 3)))
    {
      ++repeated;
      continue;
    }
    mesh.Indices.insert(mesh.Indices.end(), v, v + 3);
    mesh.BoundaryEdges.push_back(t.BoundaryEdges);
    mesh.CornerUses.insert(mesh.CornerUses.end(), 3, 1); // each stands for itself
  }
  const std::size_t vertices = welder.Count();
  mesh.Positions.resize(3 * vertices);
  mesh.Normals.resize(3 * vertices);
  mesh.Colors.resize(colors ? 4 * vertices : 0);
  mesh.InputUses.resize(vertices);
  return mesh;
}

/// Leaves keep the input at full resolution: their bucket, welded into an indexed patch.
PatchJobResult MakeLeafPatch(const PatchJobContext& context, const PatchJob& job)
{
  ThreadCpuLap lap;
  PatchJobResult result;
  result.Patches.resize(1);
  result.Patches[0].Mesh = WeldSoup(job.Soup, context.Colors, result.RepeatedTrianglesDropped);
  lap.Lap(result.Cpu.Prepare);
  Finish(result.Patches[0], context, PrecisionFor(context.Grid, 0));
  lap.Lap(result.Cpu.Encode);
  return result;
}

/// Merges the children's patches and simplifies them with the diamond's external boundary
/// locked, one region per member, to the diamond's quotas (QuotasOf).
PatchJobResult SimplifyDiamond(const PatchJobContext& context, PatchJob& job)
{
  ThreadCpuLap lap;
  PatchJobResult result;
  std::vector<const PatchMesh*> parts;
  for (const PatchMesh& c : job.Children)
  {
    parts.push_back(&c);
  }
  const DiamondQuotas quotas = QuotasOf(job, context.PatchBudget);
  SimplifyOptions options;
  options.TotalQuota = quotas.Total;
  const PatchMesh merged = MergePatches(parts);
  job.Children.clear(); // one copy of the diamond in memory while it simplifies
  lap.Lap(result.Cpu.Prepare);
  const MemberLocator locator(job.Members, context.Frame);
  options.DeepRegionOf = [&locator](const double p[3], int likely) { return locator.DeepMemberOf(p, likely); };
  SimplifyResult simplified = Simplify(merged, int(job.Members.size()),
    [&locator](const double p[3], int likely) { return locator.MemberOf(p, likely); }, quotas.Members,
    options);
  lap.Lap(result.Cpu.Simplify);
  // The merged input was already off the original by up to its children's error; storing
  // the interior on a coarser grid adds its rounding.
  const PatchPrecision precision = PrecisionFor(context.Grid, simplified.Error + job.ChildError);
  result.Error = simplified.Error + job.ChildError + precision.PositionError(context.Grid);
  result.Collapses = simplified.Collapses;
  result.TrianglesOverQuotas = simplified.TrianglesOverQuotas;
  result.PiecesRemoved = simplified.PiecesRemoved;
  result.FacingAtRandom = simplified.FacingAtRandom;
  result.Patches.resize(job.Members.size());
  for (std::size_t i = 0; i < job.Members.size(); ++i)
  {
    result.Patches[i].Mesh = std::move(simplified.Regions[i]);
    Finish(result.Patches[i], context, precision);
  }
  lap.Lap(result.Cpu.Encode);
  return result;
}

} // namespace

// Every level halves the triangles, as one bisection halves the volume, also where the leaves
// are far below the budget: a level that kept 3/4 of its children's triangles would cost nearly
// a copy of the finer level in the file and be drawn almost never.
DiamondQuotas QuotasOf(const PatchJob& job, std::uint32_t budget)
{
  const std::size_t childrenPerMember = job.Children.size() / job.Members.size();
  DiamondQuotas quotas;
  quotas.Members.assign(job.Members.size(), budget);
  for (std::size_t m = 0; m < job.Members.size(); ++m)
  {
    std::size_t children = 0;
    for (std::size_t c = 0; c < childrenPerMember; ++c)
    {
      children += job.Children[childrenPerMember * m + c].TriangleCount();
    }
    quotas.Total += std::min<std::size_t>(budget, (children + 1) / 2);
  }
  return quotas;
}

PatchJobContext::PatchJobContext(
  const Box& bounds, std::uint32_t patchBudget, bool colors, CacheOrder order)
  : Bounds(bounds)
  , PatchBudget(patchBudget)
  , Colors(colors)
  , Order(order)
  , Grid(QuantizationGrid::ForBounds(bounds.Min.data(), bounds.Max.data()))
  , Frame(bounds.Min.data(), bounds.Max.data())
{
}

PatchJobResult MakePatches(const PatchJobContext& context, PatchJob job)
{
  return job.IsLeaf() ? MakeLeafPatch(context, job) : SimplifyDiamond(context, job);
}

} // namespace atp
