#include "atpPatchJob.h"

#include "atpCpuTime.h"
#include "atpMemberLocator.h"
#include "atpMergePatches.h"
#include "atpNormalEncoding.h"
#include "atpPatchCodec.h"
#include "atpSimplifier.h"

#include <algorithm>
#include <numeric>

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
void Finish(MadePatch& made, const QuantizationGrid& grid, const PatchPrecision& precision)
{
  PatchMesh decoded;
  made.Encoded = EncodePatch(made.Mesh, grid, precision, &decoded);
  made.Tight = EnclosingSphere(decoded.Positions.data(), decoded.VertexCount());
  made.Cone = FaceNormalCone(decoded);
}

/// Without input colors the soup's (white) corner colors are left out: the model then has none.
PatchMesh WeldSoup(const std::vector<SoupTriangle>& soup, bool colors)
{
  PatchMesh corners;
  corners.Positions.reserve(9 * soup.size());
  corners.Normals.reserve(9 * soup.size());
  corners.Colors.reserve(colors ? 12 * soup.size() : 0);
  for (const SoupTriangle& t : soup)
  {
    for (int c = 0; c < 3; ++c)
    {
      float n[3];
      DecodeNormal(t.Normals[c], n);
      corners.Positions.insert(corners.Positions.end(), t.V[c], t.V[c] + 3);
      corners.Normals.insert(corners.Normals.end(), n, n + 3);
      if (colors)
      {
        corners.Colors.insert(corners.Colors.end(), t.Colors[c], t.Colors[c] + 4);
      }
    }
    corners.BoundaryEdges.push_back(t.BoundaryEdges);
  }
  corners.Indices.resize(3 * soup.size());
  std::iota(corners.Indices.begin(), corners.Indices.end(), 0u);
  return MergePatches({ &corners });
}

/// Leaves keep the input at full resolution: their bucket, welded into an indexed patch.
PatchJobResult MakeLeafPatch(const PatchJobContext& context, const PatchJob& job)
{
  ThreadCpuLap lap;
  PatchJobResult result;
  result.Patches.resize(1);
  result.Patches[0].Mesh = WeldSoup(job.Soup, context.Colors);
  lap.Lap(result.Cpu.Prepare);
  Finish(result.Patches[0], context.Grid, PrecisionFor(context.Grid, 0));
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
  result.Patches.resize(job.Members.size());
  for (std::size_t i = 0; i < job.Members.size(); ++i)
  {
    result.Patches[i].Mesh = std::move(simplified.Regions[i]);
    Finish(result.Patches[i], context.Grid, precision);
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

PatchJobContext::PatchJobContext(const Box& bounds, std::uint32_t patchBudget, bool colors)
  : Bounds(bounds)
  , PatchBudget(patchBudget)
  , Colors(colors)
  , Grid(QuantizationGrid::ForBounds(bounds.Min.data(), bounds.Max.data()))
  , Frame(bounds.Min.data(), bounds.Max.data())
{
}

PatchJobResult MakePatches(const PatchJobContext& context, PatchJob job)
{
  return job.IsLeaf() ? MakeLeafPatch(context, job) : SimplifyDiamond(context, job);
}

} // namespace atp
