// The binary forest of tetrahedra (6 roots), refined diamond by diamond. Small by design: one
// node per tetrahedron, a few thousand triangles per leaf (paper, 5.1). Still, a billion-triangle
// surface has millions of nodes: they live in a scratch file's mapping, and the process keeps
// only the pages it has touched since the last ReleaseResident.
#ifndef atpTetraForest_h
#define atpTetraForest_h

#include "atpScratchArray.h"
#include "atpTetra.h"
#include "vtkATPFiltersModule.h"

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace atp
{

class VTKATPFILTERS_EXPORT TetraForest
{
public:
  using NodeIndex = std::int32_t;
  static constexpr NodeIndex None = -1;

  /// 24 bytes: a forest of a billion triangles has millions of nodes. The geometry is not
  /// kept: Geometry() recomputes it from the id where it is needed, which is rarely.
  struct Node
  {
    TetId Id;
    SplitPlane Plane;
    NodeIndex Parent = None;
    /// The children are made together, so the second is always the one after the first.
    NodeIndex FirstChild = None;

    bool IsLeaf() const { return FirstChild == None; }
    NodeIndex Child(int which) const { return FirstChild + which; }
    std::array<NodeIndex, 2> Children() const { return { { FirstChild, FirstChild + 1 } }; }
  };

  /// The six roots, as nodes 0 to 5. The nodes live in a scratch file in `scratchDirectory`
  /// (empty: $TMPDIR or /tmp).
  explicit TetraForest(const std::string& scratchDirectory = std::string());

  std::size_t Size() const { return Nodes.Size(); }
  const Node& operator[](NodeIndex i) const { return Nodes[std::size_t(i)]; }
  /// The node's tetrahedron, in O(level).
  Tetra Geometry(NodeIndex i) const { return TetraOf(Nodes[std::size_t(i)].Id); }

  /// The node of a tetrahedron, or None when it does not exist (an ancestor is a leaf).
  NodeIndex Find(TetId id) const;
  /// The leaf below `start` that holds p (lattice coordinates).
  NodeIndex Descend(NodeIndex start, const double p[3]) const
  {
    NodeIndex n = start;
    while (!Nodes[std::size_t(n)].IsLeaf())
    {
      const Node& node = Nodes[std::size_t(n)];
      n = node.Child(node.Plane.ChildContaining(p));
    }
    return n;
  }
  NodeIndex LeafContaining(const double p[3]) const { return Descend(RootContaining(p), p); }

  /// The last leaf found and its face planes: a point of a streamed mesh is mostly in the
  /// leaf of the point before it, and telling that takes four plane tests, not a descent.
  /// A hint serves one forest.
  class LeafHint
  {
  public:
    LeafHint()
      : Recent(RecentSlots)
    {
    }
    /// Whether p is inside `leaf` (still a leaf) by far more than the rounding of any plane
    /// test: then every descent from the roots ends in it, whatever side points on a split
    /// plane take.
    bool Holds(const TetraForest& forest, const double p[3]) const
    {
      if (this->Leaf == None || !forest[this->Leaf].IsLeaf())
      {
        return false;
      }
      for (const auto& plane : this->Recent[std::size_t(this->Leaf) % RecentSlots].Planes)
      {
        if (plane[0] * p[0] + plane[1] * p[1] + plane[2] * p[2] + plane[3] <= Margin)
        {
          return false;
        }
      }
      return true;
    }
    void Set(const TetraForest& forest, NodeIndex leaf);
    NodeIndex Leaf = None;

  private:
    /// In lattice units (the lattice spans 2^20): plane tests round by about 2^-31.
    static constexpr double Margin = 1e-6;
    /// A node's face planes: unit normals pointing inside, and offsets (distance from each
    /// face). Nodes keep no geometry, and a stream goes back and forth between a few leaves
    /// (a row of a scan crosses the leaves the row before crossed): the planes of recent
    /// leaves are kept, by node number.
    struct FacePlanes
    {
      NodeIndex Node = None;
      double Planes[4][4] = {};
    };
    /// Enough for the leaves a row of the 50M torus crosses: 1 in 10 settings computes planes.
    static constexpr std::size_t RecentSlots = 1024;
    std::vector<FacePlanes> Recent;
  };

  /// LeafContaining for many points at once: points that `hint` holds need no descent, the
  /// other descents are interleaved so the processor overlaps their dependent plane tests
  /// (several times faster than one after the other). The hint moves to the last leaf found.
  void LeavesContaining(
    const double (*points)[3], NodeIndex* leaves, std::size_t count, LeafHint& hint) const;

  /// Splits the whole diamond of the leaf `node`. Members that do not exist yet are created
  /// first by splitting the coarser diamonds they need (recursively, parents before children),
  /// so the leaves always form a conforming mesh. `onSplit` is called for every tetrahedron
  /// split, in order, right after its children are created. Returns false at MaxLevel.
  bool SplitDiamond(NodeIndex node, const std::function<void(NodeIndex)>& onSplit);

  std::vector<NodeIndex> Leaves() const;
  int Depth() const { return DeepestLevel; }

  /// Gives the nodes' pages back to the system; they come back as they are read. Callers do
  /// this every so often, so that resident memory follows their working set, not the forest.
  void ReleaseResident() const { Nodes.ReleaseResident(); }

private:
  NodeIndex AddNode(TetId id, const Tetra& geometry, NodeIndex parent);
  /// Finds the node of `id`, splitting coarser diamonds until it exists.
  NodeIndex Materialize(TetId id, const std::function<void(NodeIndex)>& onSplit);

  ScratchArray<Node> Nodes;
  int DeepestLevel = 0;
};

} // namespace atp

#endif
