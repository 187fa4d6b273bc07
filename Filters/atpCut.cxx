#include "atpCut.h"

#include "atpMergePatches.h"
#include "atpPatchCodec.h"
#include "atpQuantizationGrid.h"
#include "atpTetra.h"

#include <cmath>
#include <limits>

namespace atp
{

double ProjectedError(const ModelNode& node, const ViewPoint& view, double errorScale)
{
  const float* s = node.SaturatedSphere;
  const double distance = std::sqrt((s[0] - view.Eye[0]) * (s[0] - view.Eye[0]) +
                            (s[1] - view.Eye[1]) * (s[1] - view.Eye[1]) +
                            (s[2] - view.Eye[2]) * (s[2] - view.Eye[2])) - s[3];
  if (distance <= 0)
  {
    return std::numeric_limits<double>::infinity();
  }
  const double pixelsPerUnitAtDistanceOne =
    view.ViewportHeight / (2 * std::tan(view.ViewAngleDegrees * M_PI / 360));
  return errorScale * node.SaturatedError * pixelsPerUnitAtDistanceOne / distance;
}

namespace
{
template<typename Refine>
std::vector<std::uint32_t> TopDown(const ModelFile& model, const Refine& refine)
{
  std::vector<std::uint32_t> cut, stack;
  for (std::uint32_t root = 6; root-- > 0;)
  {
    stack.push_back(root);
  }
  while (!stack.empty())
  {
    const std::uint32_t n = stack.back();
    stack.pop_back();
    const ModelNode& node = model.Node(n);
    if (node.Children[0] >= 0 && refine(node))
    {
      stack.push_back(std::uint32_t(node.Children[1]));
      stack.push_back(std::uint32_t(node.Children[0]));
    }
    else
    {
      cut.push_back(n);
    }
  }
  return cut;
}
} // namespace

std::vector<std::uint32_t> SelectCut(const ModelFile& model, const ViewPoint& view)
{
  return SelectCut(model, view, model.Header().ErrorScale);
}

std::vector<std::uint32_t> SelectCut(
  const ModelFile& model, const ViewPoint& view, double errorScale)
{
  return TopDown(model, [&](const ModelNode& node) {
    return ProjectedError(node, view, errorScale) > view.TolerancePixels;
  });
}

std::vector<std::uint32_t> SelectLevel(const ModelFile& model, int level)
{
  return TopDown(model, [level](const ModelNode& node) {
    return TetId{ node.Tet }.Level() < level;
  });
}

PatchMesh ExtractCut(const ModelFile& model, const std::vector<std::uint32_t>& nodes)
{
  const ModelHeader& h = model.Header();
  QuantizationGrid grid;
  for (int a = 0; a < 3; ++a)
  {
    grid.Origin[a] = h.QuantizationOrigin[a];
  }
  grid.Step = h.QuantizationStep;
  std::vector<PatchMesh> patches(nodes.size());
  std::vector<const PatchMesh*> parts;
  for (std::size_t i = 0; i < nodes.size(); ++i)
  {
    model.CheckPatch(nodes[i]);
    DecodePatch(model.PatchData(nodes[i]), model.Node(nodes[i]).PatchBytes, grid, patches[i]);
    patches[i].BoundaryEdges.assign(patches[i].TriangleCount(), 0);
    parts.push_back(&patches[i]);
  }
  return MergePatches(parts);
}

} // namespace atp
