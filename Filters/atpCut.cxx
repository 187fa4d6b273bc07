#include "atpCut.h"

#include "atpMergePatches.h"
#include "atpTetra.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace atp
{

namespace
{
/// Pixels per object unit at distance one (perspective) or anywhere (parallel).
double PixelsPerUnit(const ViewPoint& view)
{
  return view.Parallel ? view.ViewportHeight / (2 * view.ParallelScale)
                       : view.ViewportHeight / (2 * std::tan(view.ViewAngleDegrees * M_PI / 360));
}

/// Pixels that the saturated error covers on screen at the nearest point of the saturated
/// sphere, with `factor` = error scale * PixelsPerUnit(view); infinite when the eye is inside
/// the sphere, so nodes around the viewer always refine.
double ScreenError(const ModelNode& node, const ViewPoint& view, double factor)
{
  // In the camera's units: an error grows by at most Stretch, and so does the sphere's radius.
  const double error = view.Stretch * node.SaturatedError;
  if (view.Parallel)
  {
    return factor * error;
  }
  const float* s = node.SaturatedSphere;
  const double offset[3] = { s[0] - view.Eye[0], s[1] - view.Eye[1], s[2] - view.Eye[2] };
  const double* l = view.Linear;
  double squared = 0;
  for (int row = 0; row < 3; ++row)
  {
    const double c = l[3 * row] * offset[0] + l[3 * row + 1] * offset[1] + l[3 * row + 2] * offset[2];
    squared += c * c;
  }
  const double distance = std::sqrt(squared) - view.Stretch * s[3];
  return distance <= 0 ? std::numeric_limits<double>::infinity() : factor * error / distance;
}
} // namespace

bool SameView(const ViewPoint& a, const ViewPoint& b)
{
  return std::equal(a.Eye, a.Eye + 3, b.Eye) && a.TolerancePixels == b.TolerancePixels &&
    a.ViewportHeight == b.ViewportHeight && a.ViewAngleDegrees == b.ViewAngleDegrees &&
    a.Parallel == b.Parallel && a.ParallelScale == b.ParallelScale &&
    std::equal(a.Direction, a.Direction + 3, b.Direction) && a.PlaneCount == b.PlaneCount &&
    a.BackfaceCulling == b.BackfaceCulling && a.Stretch == b.Stretch &&
    std::equal(a.Linear, a.Linear + 9, b.Linear) &&
    std::equal(&a.Planes[0][0], &a.Planes[0][0] + 4 * a.PlaneCount, &b.Planes[0][0]);
}

bool OutsideFrustum(const float sphere[4], const ViewPoint& view)
{
  for (int p = 0; p < view.PlaneCount; ++p)
  {
    const double* plane = view.Planes[p];
    if (plane[0] * sphere[0] + plane[1] * sphere[1] + plane[2] * sphere[2] + plane[3] < -sphere[3])
    {
      return true;
    }
  }
  return false;
}

bool FacesAway(const CullingCone& cone, const float sphere[4], const ViewPoint& view)
{
  if (cone.IsEmpty())
  {
    return true;
  }
  if (cone.Cos <= 0)
  {
    return false; // a half angle of 90 degrees or more always holds a normal facing the eye
  }
  // Every normal n of the cone and every direction v from the eye to a point of the sphere
  // must satisfy n.v > 0: the angle between the axis and v's central direction, plus the
  // cone's half angle, plus the sphere's apparent half angle, must stay below 90 degrees.
  double toCenter[3];
  double spread = 0;
  if (view.Parallel)
  {
    std::copy(view.Direction, view.Direction + 3, toCenter);
  }
  else
  {
    double length = 0;
    for (int a = 0; a < 3; ++a)
    {
      toCenter[a] = sphere[a] - view.Eye[a];
      length += toCenter[a] * toCenter[a];
    }
    length = std::sqrt(length);
    if (length <= sphere[3])
    {
      return false; // the eye is inside the sphere
    }
    for (double& c : toCenter)
    {
      c /= length;
    }
    spread = std::asin(sphere[3] / length);
  }
  const double cosAxis = std::max(-1.0, std::min(1.0, cone.Axis[0] * toCenter[0] +
                                                        cone.Axis[1] * toCenter[1] + cone.Axis[2] * toCenter[2]));
  return std::acos(cosAxis) + std::acos(double(cone.Cos)) + spread < 0.5 * M_PI - 1e-6;
}

CutSelector::CutSelector(const ModelFile& model, std::shared_ptr<const CutIndex> index)
  : Model(model)
  , IndexRef(std::move(index))
  , DecisionStamp(IndexRef->DiamondCount(), 0)
  , Decision(IndexRef->DiamondCount(), 0)
  , NeedStamp(Model.NodeCount(), 0)
{
}

bool CutSelector::Need(std::uint32_t node)
{
  const bool resident = (*Resident)(node);
  if (NeedStamp[node] != Stamp)
  {
    NeedStamp[node] = Stamp;
    (resident ? Out->Held : Out->Missing).push_back(node);
  }
  return resident;
}

bool CutSelector::Refines(std::uint32_t diamond)
{
  if (DecisionStamp[diamond] == Stamp)
  {
    return Decision[diamond] != 0;
  }
  const CutIndex& index = *IndexRef;
  const ModelNode& first = Model.Node(*index.MembersBegin(diamond));
  // Saturated errors and spheres are equal over the diamond: one member decides for all.
  bool refines = first.Children[0] >= 0 && ScreenError(first, *View, ErrorFactor) > View->TolerancePixels;
  if (refines && *Resident)
  {
    // The view wants this diamond refined: everything its refinement needs is asked for here,
    // for members outside the view too, or a diamond below could wait on them forever.
    for (const std::uint32_t* m = index.MembersBegin(diamond); m != index.MembersEnd(diamond); ++m)
    {
      for (const std::int32_t child : Model.Node(*m).Children)
      {
        refines = Need(std::uint32_t(child)) && refines;
      }
    }
    // Every diamond above must refine too, or some member of this one is not in the cut.
    for (const std::uint32_t* p = index.ParentsBegin(diamond); p != index.ParentsEnd(diamond); ++p)
    {
      refines = Refines(*p) && refines;
    }
  }
  DecisionStamp[diamond] = Stamp;
  Decision[diamond] = refines ? 1 : 0;
  return refines;
}

void CutSelector::Select(const ViewPoint& view, double errorScale, const ResidentFunction& resident,
  CutResult& out)
{
  out.Drawn.clear();
  out.Missing.clear();
  out.Held.clear();
  out.Visited = 0;
  View = &view;
  ErrorFactor = errorScale * PixelsPerUnit(view);
  Resident = &resident;
  Out = &out;
  if (++Stamp == 0)
  {
    std::fill(DecisionStamp.begin(), DecisionStamp.end(), 0);
    std::fill(NeedStamp.begin(), NeedStamp.end(), 0);
    Stamp = 1;
  }
  const CutIndex& index = *IndexRef;

  Stack.clear();
  for (std::uint32_t root = RootCount; root-- > 0;)
  {
    Stack.push_back(root);
  }
  while (!Stack.empty())
  {
    const std::uint32_t n = Stack.back();
    Stack.pop_back();
    ++out.Visited;
    const ModelNode& node = Model.Node(n);
    if (OutsideFrustum(node.SaturatedSphere, view) ||
      (view.BackfaceCulling && FacesAway(index.SaturatedCone(n), node.SaturatedSphere, view)))
    {
      continue; // nothing of this branch can show
    }
    const std::uint32_t diamond = index.DiamondOf(n);
    if (Refines(diamond))
    {
      Stack.push_back(std::uint32_t(node.Children[1]));
      Stack.push_back(std::uint32_t(node.Children[0]));
      continue;
    }
    if (node.TriangleCount == 0 || OutsideFrustum(node.Sphere, view))
    {
      continue;
    }
    if (view.BackfaceCulling)
    {
      CullingCone own;
      std::copy(node.ConeAxis, node.ConeAxis + 3, own.Axis);
      own.Cos = node.ConeCos;
      if (FacesAway(own, node.Sphere, view))
      {
        continue;
      }
    }
    if (resident && !resident(n))
    {
      Need(n); // only roots get here: below them, nodes are reached through ready diamonds
      continue;
    }
    out.Drawn.push_back(n);
  }
}

std::vector<std::uint32_t> SelectCut(const ModelFile& model, const ViewPoint& view)
{
  CutSelector selector(model, std::make_shared<const CutIndex>(model));
  CutResult result;
  selector.Select(view, model.Header().ErrorScale, ResidentFunction(), result);
  return std::move(result.Drawn);
}

std::vector<std::uint32_t> SelectLevel(const ModelFile& model, int level)
{
  std::vector<std::uint32_t> cut, stack;
  for (std::uint32_t root = RootCount; root-- > 0;)
  {
    stack.push_back(root);
  }
  while (!stack.empty())
  {
    const std::uint32_t n = stack.back();
    stack.pop_back();
    const ModelNode& node = model.Node(n);
    if (node.Children[0] >= 0 && TetId{ node.Tet }.Level() < level)
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

PatchMesh ExtractCut(const ModelFile& model, const std::vector<std::uint32_t>& nodes,
  std::vector<std::uint32_t>* trianglePatch)
{
  std::vector<PatchMesh> patches(nodes.size());
  std::vector<const PatchMesh*> parts;
  for (std::size_t i = 0; i < nodes.size(); ++i)
  {
    model.DecodePatch(nodes[i], patches[i]);
    patches[i].BoundaryEdges.assign(patches[i].TriangleCount(), 0);
    parts.push_back(&patches[i]);
  }
  return MergePatches(parts, trianglePatch);
}

} // namespace atp
