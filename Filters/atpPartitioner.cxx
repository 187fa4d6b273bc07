#include "atpPartitioner.h"

#include <algorithm>

namespace atp
{
namespace
{
/// Triangles located together (interleaved descents), and centroids computed at a time, by
/// Insert without centroids.
constexpr std::size_t Group = 256;
/// Triangles inserted between two releases of the forest's and the bucket table's pages: a
/// stream touches few leaves and the top of the forest in that time, whatever the forest's
/// size, and takes those pages back in well under a millisecond.
constexpr std::uint64_t ReleaseInterval = std::uint64_t(1) << 20;
/// Appends ahead of the current one whose memory is prefetched (a leaf located for the group
/// may split before its turn: then the hint is wasted, nothing else).
constexpr std::size_t PrefetchDistance = 16;
/// Nodes Stats reads between two releases.
constexpr std::size_t StatsNodesPerRelease = std::size_t(1) << 16;
}

Partitioner::Partitioner(const Box& bounds, const PartitionOptions& options)
  : Settings(options)
  , Lattice(bounds.Min.data(), bounds.Max.data())
  , Tetrahedra(options.ScratchDirectory)
  , Buckets(options.ScratchDirectory, options.BucketMemoryBytes, options.Colors)
{
  Settings.LeafCapacity = std::max<std::uint32_t>(1, Settings.LeafCapacity);
}

void Partitioner::Centroid(const SoupTriangle& t, double out[3]) const
{
  const float c[3] = { float((double(t.V[0][0]) + t.V[1][0] + t.V[2][0]) / 3),
    float((double(t.V[0][1]) + t.V[1][1] + t.V[2][1]) / 3),
    float((double(t.V[0][2]) + t.V[1][2] + t.V[2][2]) / 3) };
  Lattice.ToLattice(c, out);
}

void Partitioner::Redistribute(TetraForest::NodeIndex splitNode)
{
  ++Splits;
  const auto bucket = std::uint32_t(splitNode);
  if (Buckets.Count(bucket) == 0)
  {
    return;
  }
  Moving.clear();
  Buckets.Read(bucket, Moving);
  Buckets.Clear(bucket);
  const TetraForest::Node& node = Tetrahedra[splitNode];
  for (const SoupTriangle& t : Moving)
  {
    double p[3];
    Centroid(t, p);
    Buckets.Append(std::uint32_t(node.Child(node.Plane.ChildContaining(p))), t);
  }
}

void Partitioner::Insert(const SoupTriangle* triangles, std::size_t count)
{
  double centroids[Group][3];
  TetraForest::NodeIndex leaves[Group];
  std::vector<TetraForest::NodeIndex> splits;
  for (std::size_t first = 0; first < count; first += Group)
  {
    const std::size_t n = std::min(Group, count - first);
    for (std::size_t i = 0; i < n; ++i)
    {
      Centroid(triangles[first + i], centroids[i]);
    }
    // Located against the forest as it stands; a leaf split by an earlier triangle of the
    // group is finished by the descent in the Insert below, so the result is the same as one
    // at a time.
    Tetrahedra.LeavesContaining(centroids, leaves, n, Hint);
    Insert(triangles + first, centroids, leaves, n, splits);
    splits.clear();
  }
}

void Partitioner::Insert(const SoupTriangle* triangles, const double (*centroids)[3],
  const TetraForest::NodeIndex* located, std::size_t count, std::vector<TetraForest::NodeIndex>& splits)
{
  const auto redistribute = [this](TetraForest::NodeIndex n) { Redistribute(n); };
  for (std::size_t i = 0; i < count; ++i)
  {
    if (i + PrefetchDistance < count)
    {
      Buckets.Prefetch(std::uint32_t(located[i + PrefetchDistance]), triangles[i + PrefetchDistance]);
    }
    const double* centroid = centroids[i];
    TetraForest::NodeIndex leaf = Tetrahedra.Descend(located[i], centroid);
    Buckets.Append(std::uint32_t(leaf), triangles[i]);
    ++Inserted;
    // Only the leaf that just grew can exceed the capacity; its children may too (all
    // triangles on one side), hence the loop.
    while (Buckets.Count(std::uint32_t(leaf)) > Settings.LeafCapacity &&
      Tetrahedra.SplitDiamond(leaf, redistribute))
    {
      splits.push_back(leaf);
      leaf = Tetrahedra.Descend(leaf, centroid);
    }
  }
  if (Inserted >= NextRelease)
  {
    ReleaseResident();
    NextRelease = Inserted + ReleaseInterval;
  }
}

PartitionStats Partitioner::Stats() const
{
  PartitionStats s;
  s.Triangles = Inserted;
  s.TetrahedraSplit = Splits;
  s.Depth = Tetrahedra.Depth();
  s.Buckets = Buckets.Stats();
  // Node by node, giving the pages back as it goes: a list of the leaves, or every node's
  // page at once, would grow with the input.
  for (std::size_t node = 0; node < Tetrahedra.Size(); ++node)
  {
    const auto leaf = TetraForest::NodeIndex(node);
    if (Tetrahedra[leaf].IsLeaf())
    {
      const std::uint64_t n = TriangleCount(leaf);
      ++s.Leaves;
      s.NonEmptyLeaves += n > 0;
      s.LargestLeaf = std::max(s.LargestLeaf, n);
      s.OverfullLeaves += n > Settings.LeafCapacity;
    }
    if ((node + 1) % StatsNodesPerRelease == 0)
    {
      ReleaseResident();
    }
  }
  return s;
}

} // namespace atp
