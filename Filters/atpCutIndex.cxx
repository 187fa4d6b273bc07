#include "atpCutIndex.h"

#include "atpTetra.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace atp
{

namespace
{
constexpr double Pi = 3.14159265358979323846;

double HalfAngle(const CullingCone& c)
{
  return std::acos(std::max(-1.0, std::min(1.0, double(c.Cos))));
}

CullingCone PatchCone(const ModelNode& node)
{
  CullingCone cone;
  if (node.TriangleCount == 0)
  {
    return cone; // empty
  }
  std::copy(node.ConeAxis, node.ConeAxis + 3, cone.Axis);
  cone.Cos = node.ConeCos;
  return cone;
}
} // namespace

CullingCone MergeCones(const CullingCone& a, const CullingCone& b)
{
  if (a.IsEmpty())
  {
    return b;
  }
  if (b.IsEmpty())
  {
    return a;
  }
  const double dot = double(a.Axis[0]) * b.Axis[0] + double(a.Axis[1]) * b.Axis[1] +
    double(a.Axis[2]) * b.Axis[2];
  const double between = std::acos(std::max(-1.0, std::min(1.0, dot)));
  const double ha = HalfAngle(a), hb = HalfAngle(b);
  if (between + hb <= ha)
  {
    return a;
  }
  if (between + ha <= hb)
  {
    return b;
  }
  CullingCone merged;
  const double half = 0.5 * (between + ha + hb);
  if (half >= Pi || between < 1e-9)
  {
    merged.Cos = -1; // opposite cones, or equal axes (then one held the other: not reached)
    return merged;
  }
  // Rotate a's axis towards b's by (half - ha) along the great circle through both.
  const double t = half - ha;
  const double sinBetween = std::sin(between);
  const double wa = std::sin(between - t) / sinBetween, wb = std::sin(t) / sinBetween;
  double axis[3], length = 0;
  for (int i = 0; i < 3; ++i)
  {
    axis[i] = wa * a.Axis[i] + wb * b.Axis[i];
    length += axis[i] * axis[i];
  }
  length = std::sqrt(length);
  for (int i = 0; i < 3; ++i)
  {
    merged.Axis[i] = float(axis[i] / length);
  }
  // Round the float cosine outwards: the cone must hold both, never miss a normal by rounding.
  merged.Cos = std::nextafter(float(std::cos(half)), -2.0f);
  return merged;
}

CutIndex::CutIndex(const ModelFile& model)
{
  const std::size_t count = model.NodeCount();
  std::unordered_map<std::uint64_t, std::uint32_t> nodeOfTet;
  nodeOfTet.reserve(count);
  for (std::uint32_t n = 0; n < count; ++n)
  {
    nodeOfTet.emplace(model.Node(n).Tet, n);
  }

  // Diamonds in order of their first member's node index: level order, like the nodes.
  DiamondOfNode.assign(count, ~0u);
  MemberStart.push_back(0);
  for (std::uint32_t n = 0; n < count; ++n)
  {
    if (DiamondOfNode[n] != ~0u)
    {
      continue;
    }
    const std::uint32_t d = std::uint32_t(MemberStart.size() - 1);
    const bool split = model.Node(n).Children[0] >= 0;
    // A diamond that was split is whole in the file; one that was not may lack the members
    // whose parents were not split.
    for (const TetId member : DiamondMembers(TetId{ model.Node(n).Tet }))
    {
      const auto found = nodeOfTet.find(member.Bits);
      const bool memberSplit = found != nodeOfTet.end() && model.Node(found->second).Children[0] >= 0;
      if (split && memberSplit != split)
      {
        throw ModelError(model.Path() + ": node " + std::to_string(n) +
          " belongs to a diamond that is split only in part");
      }
      if (found != nodeOfTet.end())
      {
        DiamondOfNode[found->second] = d;
        Members.push_back(found->second);
      }
    }
    MemberStart.push_back(std::uint32_t(Members.size()));
  }

  ParentStart.push_back(0);
  for (std::uint32_t d = 0; d + 1 < MemberStart.size(); ++d)
  {
    const std::size_t first = Parents.size();
    for (const std::uint32_t* m = MembersBegin(d); m != MembersEnd(d); ++m)
    {
      const std::int32_t parent = model.Node(*m).Parent;
      if (parent >= 0)
      {
        Parents.push_back(DiamondOfNode[std::size_t(parent)]);
      }
    }
    std::sort(Parents.begin() + std::ptrdiff_t(first), Parents.end());
    Parents.erase(std::unique(Parents.begin() + std::ptrdiff_t(first), Parents.end()), Parents.end());
    ParentStart.push_back(std::uint32_t(Parents.size()));
  }

  // Children come after their parents in the file: one backward sweep saturates the cones.
  Cones.resize(count);
  for (std::size_t n = count; n-- > 0;)
  {
    const ModelNode& node = model.Node(n);
    CullingCone cone = PatchCone(node);
    for (const std::int32_t child : node.Children)
    {
      if (child >= 0)
      {
        cone = MergeCones(cone, Cones[std::size_t(child)]);
      }
    }
    Cones[n] = cone;
  }
}

} // namespace atp
