// What the view-dependent cut needs beyond the file's node records, derived once per model:
// - the diamond of every node (its group of member nodes) and, for every diamond, the diamonds
//   holding its members' parents, so that a refinement decision can be made for whole diamonds
//   and only after every diamond above it was refined (the diamond DAG): the cut stays
//   conforming even when refinement waits for patches that are not loaded yet;
// - a saturated normal cone per node, enclosing the normals of its patch and of every
//   descendant's, so that backface culling may drop a whole branch.
// Plain C++: no VTK, no OpenGL. Immutable once built, so threads may share it.
#ifndef atpCutIndex_h
#define atpCutIndex_h

#include "atpModelFile.h"
#include "vtkATPFiltersModule.h"

#include <cstdint>
#include <vector>

namespace atp
{

/// The cut's cone of normals, from the file's floats: unit axis and the cosine of its half angle.
/// Cos -1: every direction; Cos above 1: no direction at all (the cone of an empty patch).
/// Named apart from construction's NormalCone (atpBounds.h, in double): one name for two
/// layouts in one library broke the one-definition rule (GCC's -Wodr under LTO).
struct CullingCone
{
  float Axis[3] = { 0, 0, 1 };
  float Cos = 2;

  bool IsEmpty() const { return Cos > 1; }
};

/// The smallest cone holding both cones (exact for two cones on the sphere of directions).
VTKATPFILTERS_EXPORT CullingCone MergeCones(const CullingCone& a, const CullingCone& b);

class VTKATPFILTERS_EXPORT CutIndex
{
public:
  /// Throws ModelError when a diamond is split only in part (a member missing from the file or
  /// left unsplit while another is split).
  explicit CutIndex(const ModelFile& model);

  std::size_t NodeCount() const { return DiamondOfNode.size(); }
  std::size_t DiamondCount() const { return MemberStart.size() - 1; }
  std::uint32_t DiamondOf(std::uint32_t node) const { return DiamondOfNode[node]; }
  /// Member nodes of diamond d in the file: [MembersBegin(d), MembersEnd(d)). All its members
  /// when d is split; an unsplit diamond lacks those whose parents were not split.
  const std::uint32_t* MembersBegin(std::uint32_t d) const { return &Members[MemberStart[d]]; }
  const std::uint32_t* MembersEnd(std::uint32_t d) const { return &Members[MemberStart[d + 1]]; }
  /// Diamonds holding the parents of d's members (none for the roots' diamond).
  const std::uint32_t* ParentsBegin(std::uint32_t d) const { return &Parents[ParentStart[d]]; }
  const std::uint32_t* ParentsEnd(std::uint32_t d) const { return &Parents[ParentStart[d + 1]]; }
  /// Encloses the normals of node n's patch and of all its descendants' patches.
  const CullingCone& SaturatedCone(std::uint32_t node) const { return Cones[node]; }

private:
  std::vector<std::uint32_t> DiamondOfNode;
  std::vector<std::uint32_t> MemberStart, Members;
  std::vector<std::uint32_t> ParentStart, Parents;
  std::vector<CullingCone> Cones;
};

} // namespace atp

#endif
