#include "atpTetraForest.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace atp
{
static_assert(sizeof(TetraForest::Node) == 24, "a forest node stays small: they are millions");

TetraForest::TetraForest(const std::string& scratchDirectory)
  : Nodes(scratchDirectory)
{
  for (int r = 0; r < RootCount; ++r)
  {
    AddNode(TetId::Root(r), RootTetra(r), None);
  }
}

TetraForest::NodeIndex TetraForest::AddNode(TetId id, const Tetra& geometry, NodeIndex parent)
{
  Node node;
  node.Id = id;
  node.Plane = id.Level() < MaxLevel ? geometry.Plane() : SplitPlane{}; // the deepest never split
  node.Parent = parent;
  Nodes.PushBack(node);
  DeepestLevel = std::max(DeepestLevel, id.Level());
  return NodeIndex(Nodes.Size() - 1);
}

TetraForest::NodeIndex TetraForest::Find(TetId id) const
{
  NodeIndex n = id.RootIndex();
  for (int bit = id.Level() - 1; bit >= 0; --bit)
  {
    if (Nodes[std::size_t(n)].IsLeaf())
    {
      return None;
    }
    n = Nodes[std::size_t(n)].Child(int((id.Bits >> bit) & 1u));
  }
  return n;
}

TetraForest::NodeIndex TetraForest::Materialize(
  TetId id, const std::function<void(NodeIndex)>& onSplit)
{
  for (;;)
  {
    NodeIndex n = id.RootIndex();
    int bit = id.Level() - 1;
    for (; bit >= 0 && !Nodes[std::size_t(n)].IsLeaf(); --bit)
    {
      n = Nodes[std::size_t(n)].Child(int((id.Bits >> bit) & 1u));
    }
    if (bit < 0)
    {
      return n;
    }
    // A coarser leaf stands where `id` should be: its diamond must split first.
    SplitDiamond(n, onSplit);
  }
}

bool TetraForest::SplitDiamond(NodeIndex node, const std::function<void(NodeIndex)>& onSplit)
{
  const TetId id = Nodes[std::size_t(node)].Id;
  if (id.Level() >= MaxLevel)
  {
    return false;
  }
  if (!Nodes[std::size_t(node)].IsLeaf())
  {
    return true; // already split together with its diamond
  }
  std::vector<NodeIndex> members;
  for (const TetId member : DiamondMembers(id))
  {
    members.push_back(Materialize(member, onSplit));
  }
  for (const NodeIndex m : members)
  {
    if (!Nodes[std::size_t(m)].IsLeaf())
    {
      // Diamonds split whole, so one split member with another unsplit breaks the invariant.
      throw std::logic_error("atp::TetraForest: diamond found half split");
    }
    const TetId memberId = Nodes[std::size_t(m)].Id;
    const Tetra geometry = TetraOf(memberId);
    const NodeIndex first = AddNode(memberId.Child(0), geometry.Child(0), m);
    AddNode(memberId.Child(1), geometry.Child(1), m);
    Nodes[std::size_t(m)].FirstChild = first;
    onSplit(m);
  }
  return true;
}

void TetraForest::LeafHint::Set(const TetraForest& forest, NodeIndex leaf)
{
  this->Leaf = leaf;
  FacePlanes& faces = this->Recent[std::size_t(leaf) % RecentSlots];
  if (faces.Node == leaf)
  {
    return; // a node's geometry never changes
  }
  faces.Node = leaf;
  const Tetra t = forest.Geometry(leaf);
  for (int f = 0; f < 4; ++f)
  {
    // Lattice coordinates below 2^20: the edge vectors and their cross product are exact.
    double a[3], e1[3], e2[3], inside[3];
    for (int i = 0; i < 3; ++i)
    {
      a[i] = t.V[std::size_t(Tetra::Faces[f][0])][std::size_t(i)];
      e1[i] = t.V[std::size_t(Tetra::Faces[f][1])][std::size_t(i)] - a[i];
      e2[i] = t.V[std::size_t(Tetra::Faces[f][2])][std::size_t(i)] - a[i];
      inside[i] = t.V[std::size_t(Tetra::Faces[f][3])][std::size_t(i)] - a[i];
    }
    double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
      e1[0] * e2[1] - e1[1] * e2[0] };
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double toward = n[0] * inside[0] + n[1] * inside[1] + n[2] * inside[2] > 0 ? 1 : -1;
    double* plane = faces.Planes[f];
    for (int i = 0; i < 3; ++i)
    {
      plane[i] = toward * n[i] / length;
    }
    plane[3] = -(plane[0] * a[0] + plane[1] * a[1] + plane[2] * a[2]);
  }
}

void TetraForest::LeavesContaining(
  const double (*points)[3], NodeIndex* leaves, std::size_t count, LeafHint& hint) const
{
  // The points the hint does not hold, descended 8 at a time.
  constexpr std::size_t Lanes = 8;
  std::size_t pending[Lanes];
  std::size_t waiting = 0;
  const auto descend = [&]() {
    NodeIndex n[Lanes];
    for (std::size_t l = 0; l < waiting; ++l)
    {
      n[l] = RootContaining(points[pending[l]]);
    }
    for (bool descending = true; descending;)
    {
      descending = false;
      for (std::size_t l = 0; l < waiting; ++l)
      {
        const Node& node = Nodes[std::size_t(n[l])];
        if (!node.IsLeaf())
        {
          n[l] = node.Child(node.Plane.ChildContaining(points[pending[l]]));
          descending = true;
        }
      }
    }
    for (std::size_t l = 0; l < waiting; ++l)
    {
      leaves[pending[l]] = n[l];
    }
    if (waiting > 0 && n[waiting - 1] != hint.Leaf)
    {
      hint.Set(*this, n[waiting - 1]);
    }
    waiting = 0;
  };
  bool lastHeld = true;
  for (std::size_t i = 0; i < count; ++i)
  {
    if (waiting == 0 && hint.Holds(*this, points[i]))
    {
      leaves[i] = hint.Leaf;
      lastHeld = true;
      continue;
    }
    pending[waiting++] = i;
    // A miss after a hit mostly starts a run in another leaf: found at once, the hint follows
    // it. Misses in a row (a stream without order) are descended together.
    if (lastHeld || waiting == Lanes)
    {
      descend();
    }
    lastHeld = false;
  }
  descend();
}

std::vector<TetraForest::NodeIndex> TetraForest::Leaves() const
{
  std::vector<NodeIndex> leaves;
  for (std::size_t i = 0; i < Nodes.Size(); ++i)
  {
    if (Nodes[i].IsLeaf())
    {
      leaves.push_back(NodeIndex(i));
    }
  }
  return leaves;
}

} // namespace atp
