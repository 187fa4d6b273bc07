// The tetrahedron hierarchy on an integer lattice: ids, geometry, bisection, diamonds, Morton codes.
//
// The root cube is [0, 2^LatticeBits]^3, split into 6 tetrahedra around its major diagonal
// (0,0,0)-(S,S,S). Every bisection splits the unique longest edge at its midpoint, which stays on
// the lattice down to MaxLevel, so two tetrahedra reached by different paths agree bit for bit on
// shared vertices. Plain C++: no VTK types.
#ifndef atpTetra_h
#define atpTetra_h

#include "vtkATPFiltersModule.h"

#include <array>
#include <cstdint>
#include <vector>

namespace atp
{

constexpr int LatticeBits = 20;
constexpr std::int32_t LatticeSize = std::int32_t(1) << LatticeBits;
/// Deepest level: 3 levels halve the edge length, and the lattice spacing is 1.
constexpr int MaxLevel = 3 * LatticeBits;
constexpr int RootCount = 6;

using LatticePoint = std::array<std::int32_t, 3>;

/// A tetrahedron as a root and a bisection path: a leading 1 bit, 3 bits of root index, then one
/// bit per bisection (0: the child keeping the split edge's first endpoint). Fits in 64 bits.
struct TetId
{
  std::uint64_t Bits = 0;

  static TetId Root(int root) { return TetId{ 8u | std::uint64_t(root) }; }
  int Level() const { return 60 - __builtin_clzll(Bits); }
  int RootIndex() const { return int((Bits >> Level()) & 7u); }
  TetId Child(int which) const { return TetId{ (Bits << 1) | std::uint64_t(which & 1) }; }
  TetId Parent() const { return TetId{ Bits >> 1 }; }
  /// Which child of its parent this is (meaningless for a root).
  int ChildIndex() const { return int(Bits & 1u); }
  bool IsRoot() const { return Level() == 0; }
  bool IsValid() const { return Bits >= 8 && (Bits >> Level()) >= 8 && RootIndex() < RootCount; }
  bool operator==(TetId o) const { return Bits == o.Bits; }
  bool operator!=(TetId o) const { return Bits != o.Bits; }
  bool operator<(TetId o) const { return Bits < o.Bits; }
};

/// A diamond: the tetrahedra sharing one split edge, named by the edge's midpoint (its center),
/// packed as three 21-bit lattice coordinates. The center alone determines the edge.
struct DiamondId
{
  std::uint64_t Bits = 0;
  bool operator==(DiamondId o) const { return Bits == o.Bits; }
  bool operator!=(DiamondId o) const { return Bits != o.Bits; }
  bool operator<(DiamondId o) const { return Bits < o.Bits; }
};

/// The plane that bisects a tetrahedron (through the split point and the opposite edge),
/// oriented so that child 0 is on the non-negative side. One formula decides sides everywhere
/// (point location, partitioning, tests), so a point never lands in two places.
///
/// Longest-edge bisection of the Kuhn tetrahedra only ever cuts along x_i = c or
/// x_i +- x_j = c, so the normal has components -1, 0, 1 and the offset is a lattice integer:
/// 8 bytes, not 48, for the forest's millions of nodes, and an exact test.
struct SplitPlane
{
  std::int8_t Normal[3];
  std::int32_t Offset;

  int ChildContaining(const double p[3]) const
  {
    const double s = Normal[0] * p[0] + Normal[1] * p[1] + Normal[2] * p[2] - Offset;
    return s >= 0 ? 0 : 1;
  }
};

/// The geometry of a tetrahedron in canonical order: V[0], V[1] are the endpoints of the longest
/// (split) edge, V[0] lexicographically first; V[2], V[3] the opposite edge, also ordered.
struct Tetra
{
  std::array<LatticePoint, 4> V;

  /// Children in TetId order: child 0 keeps V[0], child 1 keeps V[1].
  std::array<Tetra, 2> Children() const { return { Child(0), Child(1) }; }
  Tetra Child(int which) const;
  LatticePoint SplitPoint() const;
  SplitPlane Plane() const;
  /// Which child contains point p (lattice coordinates); points on the split plane go to child 0.
  int ChildContaining(const double p[3]) const { return Plane().ChildContaining(p); }
  bool Contains(const double p[3]) const;
  /// The four faces as vertex numbers: three corners, then the opposite vertex.
  static constexpr int Faces[4][4] = { { 1, 2, 3, 0 }, { 0, 2, 3, 1 }, { 0, 1, 3, 2 },
    { 0, 1, 2, 3 } };
  /// Six times the signed volume is exact in 64 bits only near the leaves; volume in double.
  double Volume() const;
  std::array<double, 3> Centroid() const;
  bool operator==(const Tetra& o) const { return V == o.V; }
};

/// Puts any four lattice points in canonical order (longest edge first). The longest edge of
/// every tetrahedron of this hierarchy is unique.
VTKATPFILTERS_EXPORT Tetra MakeCanonical(const std::array<LatticePoint, 4>& points);

VTKATPFILTERS_EXPORT Tetra RootTetra(int root);
/// Geometry of any tetrahedron, computed in O(level) from its root.
VTKATPFILTERS_EXPORT Tetra TetraOf(TetId id);
/// The root whose tetrahedron holds p (p in lattice coordinates, inside the cube).
VTKATPFILTERS_EXPORT int RootContaining(const double p[3]);
/// The tetrahedron at `level` that holds p, in O(level).
VTKATPFILTERS_EXPORT TetId Locate(const double p[3], int level);

/// The three diamond shapes of the paper's figure 3(c), by split-edge direction.
enum class DiamondType
{
  CubeDiagonal = 0, ///< split edge along a cube diagonal: up to 6 members
  FaceDiagonal = 1, ///< along a face diagonal: up to 4 members
  AxisEdge = 2      ///< along a cube edge: up to 8 members
};

VTKATPFILTERS_EXPORT DiamondId DiamondOf(const Tetra& t);
VTKATPFILTERS_EXPORT LatticePoint DiamondCenter(DiamondId d);
/// Diamond type; equals the level of its members modulo 3.
VTKATPFILTERS_EXPORT DiamondType TypeOf(const Tetra& t);
/// Largest member count of a diamond of this type (fewer at the cube's boundary).
VTKATPFILTERS_EXPORT int FullMemberCount(DiamondType type);
/// Every tetrahedron sharing t's split edge as its own split edge, t included, in TetId order.
/// Members that would leave the root cube do not exist and are not listed.
VTKATPFILTERS_EXPORT std::vector<TetId> DiamondMembers(TetId id);

/// Bit-interleaved code of three 21-bit coordinates (x in the lowest bit).
VTKATPFILTERS_EXPORT std::uint64_t MortonCode(std::uint32_t x, std::uint32_t y, std::uint32_t z);
/// Morton code (bit-interleaved) of the centroid, 21 bits per axis.
VTKATPFILTERS_EXPORT std::uint64_t CentroidMorton(const Tetra& t);

/// Maps input coordinates into the lattice cube. The cube is the bounding box's largest extent
/// in every axis, anchored at the box minimum, so tetrahedra keep the well-shaped Kuhn forms at
/// every level (a stretched box would give needle-shaped cells for thin models).
class LatticeFrame
{
public:
  LatticeFrame() = default;
  LatticeFrame(const double boxMin[3], const double boxMax[3]);

  void ToLattice(const float p[3], double out[3]) const;
  void ToWorld(const LatticePoint& q, double out[3]) const;
  double Scale() const { return Scale_; } ///< lattice units per world unit
  const std::array<double, 3>& Origin() const { return Origin_; }

private:
  std::array<double, 3> Origin_{ { 0, 0, 0 } };
  double Scale_ = 1;
};

} // namespace atp

#endif
