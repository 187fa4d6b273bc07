#include "atpModelBoundsCheck.h"

#include "atpBounds.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace atp
{
namespace
{
/// Room for the rounding of the distances computed here (the writer's floats already hold a
/// margin far above it: StoreSphere, StoreCone).
constexpr double RelativeSlack = 1e-9;
constexpr double AngleSlack = 1e-9;

template <typename... Parts>
std::string Problem(std::size_t node, const Parts&... parts)
{
  std::ostringstream s;
  s.precision(9);
  s << "node " << node << ": ";
  (s << ... << parts);
  return s.str();
}

double Distance(const float* a, const float* b)
{
  double sum = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double d = double(a[k]) - double(b[k]);
    sum += d * d;
  }
  return std::sqrt(sum);
}

/// Sphere `inner` (center, radius) lies within `outer`; radius 0 is the empty sphere
/// (StoreSphere).
bool Within(const float* inner, const float* outer)
{
  return inner[3] == 0 || Distance(inner, outer) + inner[3] <= double(outer[3]) * (1 + RelativeSlack);
}

double Length(const double* v)
{
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}
} // namespace

std::vector<std::string> PatchProblems(
  const ModelHeader& header, std::size_t i, const ModelNode& node, const PatchMesh& patch)
{
  std::vector<std::string> problems;
  if (node.TriangleCount != patch.TriangleCount())
  {
    problems.push_back(Problem(i, "the patch holds ", patch.TriangleCount(), " triangles, the node says ",
      node.TriangleCount));
  }
  if (node.VertexCount != patch.VertexCount())
  {
    problems.push_back(Problem(i, "the patch holds ", patch.VertexCount(), " vertices, the node says ",
      node.VertexCount));
  }
  const bool colors = (header.Flags & ModelFlagColors) != 0;
  if (patch.VertexCount() > 0 && patch.HasColors() != colors)
  {
    problems.push_back(Problem(i, colors ? "the patch has no colors, the model says patches have"
                                         : "the patch has colors, the model says patches have none"));
  }
  for (std::size_t v = 0; v < patch.VertexCount(); ++v)
  {
    const float* p = &patch.Positions[3 * v];
    const double d = Distance(p, node.Sphere);
    if (d > double(node.Sphere[3]) * (1 + RelativeSlack))
    {
      problems.push_back(Problem(i, "vertex ", v, " lies ", d, " from the center of its sphere of radius ",
        node.Sphere[3]));
      break;
    }
  }
  if (node.ConeCos > -1)
  {
    const double axis[3] = { node.ConeAxis[0], node.ConeAxis[1], node.ConeAxis[2] };
    if (std::abs(Length(axis) - 1) > 1e-5)
    {
      problems.push_back(Problem(i, "its normal cone's axis has length ", Length(axis), ", not 1"));
    }
    const double halfAngle = std::acos(std::min(1.0, double(node.ConeCos)));
    for (std::size_t t = 0; t < patch.TriangleCount(); ++t)
    {
      // The same normal FaceNormalCone gave the builder.
      const std::array<double, 3> n = FaceCross(patch, t);
      if (Length(n.data()) == 0)
      {
        continue;
      }
      // atan2 of the cross and dot products: accurate at any angle, where acos of a dot is not.
      const double c[3] = { n[1] * axis[2] - n[2] * axis[1], n[2] * axis[0] - n[0] * axis[2],
        n[0] * axis[1] - n[1] * axis[0] };
      const double angle = std::atan2(Length(c), n[0] * axis[0] + n[1] * axis[1] + n[2] * axis[2]);
      if (angle > halfAngle + AngleSlack)
      {
        problems.push_back(Problem(i, "the normal of triangle ", t, " lies outside the normal cone (",
          angle * 180 / M_PI, " degrees from its axis, half angle ", halfAngle * 180 / M_PI, ")"));
        break;
      }
    }
  }
  if (!Within(node.Sphere, node.SaturatedSphere))
  {
    problems.push_back(Problem(i, "its sphere pokes out of its saturated sphere"));
  }
  return problems;
}

std::vector<std::string> SaturationProblems(const ModelFile& model, const CutIndex& diamonds)
{
  std::vector<std::string> problems;
  for (std::uint32_t d = 0; d < diamonds.DiamondCount(); ++d)
  {
    const ModelNode& first = model.Node(*diamonds.MembersBegin(d));
    for (const std::uint32_t* m = diamonds.MembersBegin(d) + 1; m != diamonds.MembersEnd(d); ++m)
    {
      const ModelNode& member = model.Node(*m);
      if (member.SaturatedError != first.SaturatedError ||
        std::memcmp(member.SaturatedSphere, first.SaturatedSphere, sizeof(first.SaturatedSphere)) != 0)
      {
        problems.push_back(Problem(*m, "its saturated error or sphere differs from that of node ",
          *diamonds.MembersBegin(d), ", of the same diamond"));
      }
    }
  }
  for (std::size_t i = 0; i < model.NodeCount(); ++i)
  {
    const ModelNode& n = model.Node(i);
    if (n.Parent >= 0 && !Within(n.SaturatedSphere, model.Node(std::size_t(n.Parent)).SaturatedSphere))
    {
      problems.push_back(Problem(i, "its saturated sphere pokes out of its parent's"));
    }
  }
  return problems;
}

} // namespace atp
