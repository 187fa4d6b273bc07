// Out-of-core mesh partitioning (paper 5.1): every triangle goes to the leaf tetrahedron holding
// its centroid; a leaf holding more than the capacity splits with its whole diamond and its
// triangles move to the children. The forest stays in memory (small), the buckets on disk.
#ifndef atpPartitioner_h
#define atpPartitioner_h

#include "atpBoundaryEdgeCheck.h"
#include "atpBucketStore.h"
#include "atpTetraForest.h"
#include "atpTriangleSource.h"
#include "vtkATPFiltersModule.h"

#include <memory>
#include <string>
#include <vector>

namespace atp
{

struct PartitionOptions
{
  std::uint32_t LeafCapacity = 4000;
  /// Memory for in-memory bucket pages; the rest of the buckets live in the scratch file.
  std::size_t BucketMemoryBytes = std::size_t(256) << 20;
  std::string ScratchDirectory; ///< empty: $TMPDIR or /tmp
  /// Whether buckets keep corner colors; inputs without colors save a fifth of the bucket I/O.
  bool Colors = true;
};

struct PartitionStats
{
  std::uint64_t Triangles = 0;
  std::uint64_t TetrahedraSplit = 0;
  std::uint64_t Leaves = 0;
  std::uint64_t NonEmptyLeaves = 0;
  std::uint64_t LargestLeaf = 0;
  /// Leaves at MaxLevel that still hold more than the capacity (many triangles sharing one
  /// centroid); they are kept whole rather than failing the build.
  std::uint64_t OverfullLeaves = 0;
  int Depth = 0;
  BucketStoreStats Buckets;
};

class VTKATPFILTERS_EXPORT Partitioner
{
public:
  Partitioner(const Box& bounds, const PartitionOptions& options);

  void Insert(const SoupTriangle* triangles, std::size_t count);
  /// Insert, with each triangle's centroid (Centroid) and a node of the forest holding it given:
  /// a thread that reads the input finds them while this one inserts the batch before. That
  /// node may be a leaf of the forest as it stood some splits ago (a copy the reading thread
  /// keeps, TetraForest::SplitDiamond replaying `splits`): the descent goes on from it. Every
  /// SplitDiamond call that splits a leaf is appended to `splits`, in order.
  void Insert(const SoupTriangle* triangles, const double (*centroids)[3],
    const TetraForest::NodeIndex* located, std::size_t count, std::vector<TetraForest::NodeIndex>& splits);

  const TetraForest& Forest() const { return Tetrahedra; }
  const LatticeFrame& Frame() const { return Lattice; }
  std::uint64_t TriangleCount(TetraForest::NodeIndex leaf) const
  {
    return Buckets.Count(std::uint32_t(leaf));
  }
  /// Appends the triangles of `leaf` to `out`, their boundary bits checked by position when a
  /// check is set. Once inserting has stopped, safe from several threads at once, and beside
  /// ReleaseLeaf of other leaves.
  void ReadLeaf(TetraForest::NodeIndex leaf, std::vector<SoupTriangle>& out) const
  {
    const std::size_t first = out.size();
    Buckets.Read(std::uint32_t(leaf), out);
    if (BoundaryCheck)
    {
      BoundaryCheck->Apply(out.data() + first, out.size() - first);
    }
  }
  /// The source's check of the boundary bits (TriangleSource::BoundaryCheck), once it is read.
  void SetBoundaryCheck(std::shared_ptr<const BoundaryEdgeCheck> check) { BoundaryCheck = std::move(check); }
  /// Once every triangle is in: what only inserting needs goes back to the system (bucket
  /// memory for appending), and released leaves give back theirs from now on.
  void StopInserting()
  {
    Buckets.StopAppending();
    ReleaseResident();
  }
  /// Gives back the pages of the records that grow with the input (the forest's nodes, the
  /// bucket table, the bucket page records); they come back as they are used. Inserting does
  /// this every million triangles, and construction as it goes.
  void ReleaseResident() const
  {
    Tetrahedra.ReleaseResident();
    Buckets.ReleaseResident();
  }
  /// Empties the leaf's bucket once its triangles are read for the last time. Once inserting
  /// has stopped, safe from several threads at once, and beside ReadLeaf of other leaves.
  void ReleaseLeaf(TetraForest::NodeIndex leaf) { Buckets.Discard(std::uint32_t(leaf)); }
  PartitionStats Stats() const;
  const PartitionOptions& Options() const { return Settings; }

  /// The triangle's centroid in lattice coordinates: the one point that decides its leaf.
  /// Thread-safe.
  void Centroid(const SoupTriangle& t, double out[3]) const;

private:
  void Redistribute(TetraForest::NodeIndex splitNode);

  PartitionOptions Settings;
  LatticeFrame Lattice;
  TetraForest Tetrahedra;
  BucketStore Buckets;
  std::vector<SoupTriangle> Moving; // reused buffer for the triangles of a split leaf
  std::shared_ptr<const BoundaryEdgeCheck> BoundaryCheck;
  TetraForest::LeafHint Hint;
  std::uint64_t Inserted = 0;
  std::uint64_t NextRelease = 0;
  std::uint64_t Splits = 0;
};

} // namespace atp

#endif
