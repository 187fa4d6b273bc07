#include "atpTetraForest.h"

#include <algorithm>
#include <stdexcept>

namespace atp
{

TetraForest::TetraForest()
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
  node.Geometry = geometry;
  node.Plane = geometry.Plane();
  node.Parent = parent;
  Nodes.push_back(node);
  DeepestLevel = std::max(DeepestLevel, id.Level());
  return NodeIndex(Nodes.size() - 1);
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
    n = Nodes[std::size_t(n)].Children[(id.Bits >> bit) & 1u];
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
      n = Nodes[std::size_t(n)].Children[(id.Bits >> bit) & 1u];
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
    const auto children = Nodes[std::size_t(m)].Geometry.Children();
    const NodeIndex first = AddNode(memberId.Child(0), children[0], m);
    const NodeIndex second = AddNode(memberId.Child(1), children[1], m);
    Nodes[std::size_t(m)].Children = { { first, second } };
    onSplit(m);
  }
  return true;
}

void TetraForest::LeavesContaining(
  const double (*points)[3], NodeIndex* leaves, std::size_t count) const
{
  constexpr std::size_t Lanes = 8;
  std::size_t first = 0;
  for (; first + Lanes <= count; first += Lanes)
  {
    NodeIndex n[Lanes];
    for (std::size_t l = 0; l < Lanes; ++l)
    {
      n[l] = RootContaining(points[first + l]);
    }
    for (bool descending = true; descending;)
    {
      descending = false;
      for (std::size_t l = 0; l < Lanes; ++l)
      {
        const Node& node = Nodes[std::size_t(n[l])];
        if (!node.IsLeaf())
        {
          n[l] = node.Children[node.Plane.ChildContaining(points[first + l])];
          descending = true;
        }
      }
    }
    std::copy(n, n + Lanes, leaves + first);
  }
  for (; first < count; ++first)
  {
    leaves[first] = LeafContaining(points[first]);
  }
}

std::vector<TetraForest::NodeIndex> TetraForest::Leaves() const
{
  std::vector<NodeIndex> leaves;
  for (std::size_t i = 0; i < Nodes.size(); ++i)
  {
    if (Nodes[i].IsLeaf())
    {
      leaves.push_back(NodeIndex(i));
    }
  }
  return leaves;
}

} // namespace atp
