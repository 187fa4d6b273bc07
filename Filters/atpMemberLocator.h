// Which member tetrahedron of a diamond a point belongs to: the simplifier's regions.
#ifndef atpMemberLocator_h
#define atpMemberLocator_h

#include "atpTetra.h"
#include "vtkATPFiltersModule.h"

#include <array>
#include <vector>

namespace atp
{

class VTKATPFILTERS_EXPORT MemberLocator
{
public:
  MemberLocator(const std::vector<Tetra>& members, const LatticeFrame& frame);

  /// The member holding p (world coordinates). A point on a shared face goes to the lower
  /// index; a point outside the diamond (a simplified triangle's centroid may leave it) to the
  /// member it is least outside of. `likely` only saves time: the member tried first, whose
  /// answer stands when p is well inside it (no other member can then hold p).
  int MemberOf(const double p[3], int likely = 0) const;

  /// The member whose interior holds p deeply enough that MemberOf gives it for any convex
  /// combination of points this gives it for (members are convex, and the margin is twice
  /// MemberOf's own, far above rounding); -1 when no member holds p that deeply. A triangle whose
  /// corners all answer m then has its centroid in m without asking. `likely` as for MemberOf.
  int DeepMemberOf(const double p[3], int likely = 0) const;

private:
  /// Per member: barycentric coordinates as an affine map of the lattice point.
  struct Barycentric
  {
    std::array<std::array<double, 4>, 4> Rows;
  };
  /// The least barycentric coordinate of lattice point q in member m: > 0 inside it.
  double Inside(std::size_t m, const double q[3]) const;
  /// p in lattice coordinates, which the barycentric maps take.
  void ToLattice(const double p[3], double q[3]) const;

  std::vector<Barycentric> Members;
  LatticeFrame Frame;
};

} // namespace atp

#endif
