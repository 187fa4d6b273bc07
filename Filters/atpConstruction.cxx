#include "atpConstruction.h"

#include "atpBounds.h"
#include "atpModelFormat.h"
#include "atpModelWriter.h"
#include "atpPatchJobRunner.h"
#include "atpPatchStore.h"
#include "atpQuantizationGrid.h"
#include "atpScratchFile.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <map>
#include <numeric>

namespace atp
{
namespace
{
using NodeIndex = TetraForest::NodeIndex;

/// What construction knows about one tetrahedron once its patch is made.
struct NodeResult
{
  PatchStore::Handle Intermediate; ///< full-precision patch, until the parent diamond reads it
  std::uint64_t EncodedOffset = 0; ///< in the encoded-patch scratch file
  std::uint32_t EncodedBytes = 0;
  std::uint32_t Triangles = 0;
  std::uint32_t Vertices = 0;
  double Error = 0;
  double SaturatedError = 0;
  float Sphere[4] = { 0, 0, 0, 0 };
  float SaturatedSphere[4] = { 0, 0, 0, 0 };
  NormalCone Cone; ///< saturated: holds the face normals of the patch and of all descendants
};

class ModelConstruction
{
public:
  ModelConstruction(Partitioner& partition, const Box& bounds, const InputStats& input,
    const ConstructionOptions& options, const ConstructionProgress& progress)
    : Partition(partition)
    , Forest(partition.Forest())
    , Bounds(bounds)
    , Input(input)
    , Options(options)
    , Progress(progress)
    , Context(bounds, options.PatchBudget, input.HasColors)
    , OwnRunner(options.Runner ? nullptr : MakeThreadJobRunner(options.Threads))
    , Runner(options.Runner ? *options.Runner : *OwnRunner)
    , Intermediate(options.ScratchDirectory)
    , Encoded(options.ScratchDirectory)
    , Results(partition.Forest().Size())
  {
  }

  ConstructionStats Run(const std::string& outputPath)
  {
    Runner.Begin(Context);
    std::vector<std::vector<NodeIndex>> levels(std::size_t(Forest.Depth()) + 1);
    for (NodeIndex n = 0; n < NodeIndex(Forest.Size()); ++n)
    {
      levels[std::size_t(Forest[n].Id.Level())].push_back(n);
    }
    // The intermediate patches of the level below, all read by this level's diamonds, go back
    // to the file system at once when the level is done: one hole punched per level, not one
    // per patch (a punch can wait on the file system's journal).
    std::uint64_t levelBelowStart = Intermediate.BytesWritten();
    for (int level = Forest.Depth(); level >= 0; --level)
    {
      const std::uint64_t levelStart = Intermediate.BytesWritten();
      std::vector<NodeIndex> leaves, inner;
      for (NodeIndex n : levels[std::size_t(level)])
      {
        (Forest[n].IsLeaf() ? leaves : inner).push_back(n);
      }
      MakeLeafPatches(leaves, level > 0);
      SaturateLeafDiamonds(leaves);
      SimplifyDiamonds(inner, level > 0);
      Intermediate.Release({ levelBelowStart, levelStart - levelBelowStart });
      levelBelowStart = levelStart;
    }
    Write(outputPath);
    return Stats;
  }

private:
  void ReportProgress(std::size_t nodesDone)
  {
    Done += nodesDone;
    if (Progress)
    {
      // The last few percent are the file write.
      Progress(0.97 * double(Done) / double(Forest.Size()));
    }
  }

  /// Stores a finished patch for `node`: encoded bytes for the file, and the full-precision mesh
  /// for the parent diamond when there is one.
  void Store(NodeIndex node, const MadePatch& made, bool hasParent)
  {
    NodeResult& r = Results[std::size_t(node)];
    r.EncodedOffset = EncodedEnd;
    r.EncodedBytes = std::uint32_t(made.Encoded.size());
    Encoded.WriteAt(EncodedEnd, made.Encoded.data(), made.Encoded.size());
    EncodedEnd += made.Encoded.size();
    r.Triangles = std::uint32_t(made.Mesh.TriangleCount());
    r.Vertices = std::uint32_t(made.Mesh.VertexCount());
    StoreSphere(made.Tight, r.Sphere);
    if (hasParent)
    {
      r.Intermediate = Intermediate.Put(made.Mesh);
    }
    Stats.StoredTriangles += r.Triangles;
    Stats.PatchBytes += made.Encoded.size();
    Stats.PeakScratchBytes =
      std::max(Stats.PeakScratchBytes, EncodedEnd + Intermediate.PeakBytes());
  }

  /// Leaves keep the input at full resolution: their bucket, welded into an indexed patch.
  void MakeLeafPatches(const std::vector<NodeIndex>& leaves, bool haveParents)
  {
    Runner.Run(
      leaves.size(),
      [&](std::size_t i, PatchJob& job) {
        Partition.ReadLeaf(leaves[i], job.Soup);
        Partition.ReleaseLeaf(leaves[i]);
      },
      [&](std::size_t i, PatchJobResult& made) {
        Store(leaves[i], made.Patches[0], haveParents);
        Results[std::size_t(leaves[i])].Cone = made.Patches[0].Cone;
        ReportProgress(1);
      });
  }

  /// Leaves are never refined, but their diamond still shares one saturated sphere (the
  /// invariant every diamond keeps); their error is zero.
  void SaturateLeafDiamonds(const std::vector<NodeIndex>& leaves)
  {
    for (const std::vector<NodeIndex>& members : GroupByDiamond(leaves))
    {
      std::vector<Sphere> spheres;
      for (NodeIndex m : members)
      {
        spheres.push_back(LoadSphere(Results[std::size_t(m)].Sphere));
      }
      float saturated[4];
      StoreSphere(EnclosingSphere(spheres), saturated);
      for (NodeIndex m : members)
      {
        std::copy(saturated, saturated + 4, Results[std::size_t(m)].SaturatedSphere);
      }
    }
  }

  /// Nodes of one level grouped by diamond: groups ordered by diamond id, members by TetId.
  std::vector<std::vector<NodeIndex>> GroupByDiamond(const std::vector<NodeIndex>& nodes) const
  {
    std::map<std::uint64_t, std::vector<NodeIndex>> groups;
    for (NodeIndex n : nodes)
    {
      groups[DiamondOf(Forest.Geometry(n)).Bits].push_back(n);
    }
    std::vector<std::vector<NodeIndex>> ordered;
    for (auto& [id, members] : groups)
    {
      std::sort(members.begin(), members.end(),
        [this](NodeIndex a, NodeIndex b) { return Forest[a].Id < Forest[b].Id; });
      ordered.push_back(std::move(members));
    }
    return ordered;
  }

  void SimplifyDiamonds(const std::vector<NodeIndex>& inner, bool haveParents)
  {
    const std::vector<std::vector<NodeIndex>> diamonds = GroupByDiamond(inner);
    Runner.Run(
      diamonds.size(),
      [&](std::size_t i, PatchJob& job) { LoadDiamond(diamonds[i], job); },
      [&](std::size_t i, PatchJobResult& made) {
        SaturateDiamond(diamonds[i], made, haveParents);
        ReportProgress(diamonds[i].size());
      });
  }

  /// A diamond's job: its members' shapes and their children's full-precision patches.
  void LoadDiamond(const std::vector<NodeIndex>& members, PatchJob& job) const
  {
    for (NodeIndex m : members)
    {
      job.Members.push_back(Forest.Geometry(m));
      for (NodeIndex c : Forest[m].Children())
      {
        job.Children.emplace_back();
        Intermediate.Get(Results[std::size_t(c)].Intermediate, job.Children.back());
        job.ChildError = std::max(job.ChildError, Results[std::size_t(c)].Error);
      }
    }
  }

  /// Runs on the main thread, in diamond order: stores the patches and saturates errors,
  /// spheres and cones over the diamond and its children (paper 5.2).
  void SaturateDiamond(
    const std::vector<NodeIndex>& members, const PatchJobResult& made, bool haveParents)
  {
    double childSaturatedError = 0;
    std::vector<Sphere> spheres;
    for (std::size_t i = 0; i < members.size(); ++i)
    {
      const NodeIndex m = members[i];
      Store(m, made.Patches[i], haveParents);
      spheres.push_back(LoadSphere(Results[std::size_t(m)].Sphere));
      std::vector<NormalCone> cones{ made.Patches[i].Cone };
      for (NodeIndex c : Forest[m].Children())
      {
        NodeResult& child = Results[std::size_t(c)];
        childSaturatedError = std::max(childSaturatedError, child.SaturatedError);
        spheres.push_back(LoadSphere(child.SaturatedSphere));
        cones.push_back(child.Cone);
      }
      Results[std::size_t(m)].Cone = EnclosingCone(cones);
    }
    const double error = made.Error;
    const double saturatedError = std::max(error, childSaturatedError);
    float saturatedSphere[4];
    StoreSphere(EnclosingSphere(spheres), saturatedSphere);
    for (NodeIndex m : members)
    {
      NodeResult& r = Results[std::size_t(m)];
      r.Error = error;
      r.SaturatedError = saturatedError;
      std::copy(saturatedSphere, saturatedSphere + 4, r.SaturatedSphere);
    }
    ++Stats.Diamonds;
    Stats.Collapses += made.Collapses;
    Stats.QuotaMisses += !made.QuotasMet;
  }

  /// Nodes in file order: by level, then by the Morton code of their centroid, so the
  /// tetrahedra a cut visits together lie together in the file.
  std::vector<NodeIndex> FileOrder() const
  {
    std::vector<std::pair<std::pair<int, std::uint64_t>, std::uint64_t>> keys(Forest.Size());
    for (NodeIndex n = 0; n < NodeIndex(Forest.Size()); ++n)
    {
      keys[std::size_t(n)] = { { Forest[n].Id.Level(), CentroidMorton(Forest.Geometry(n)) },
        Forest[n].Id.Bits };
    }
    std::vector<NodeIndex> order(Forest.Size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
      [&keys](NodeIndex a, NodeIndex b) { return keys[std::size_t(a)] < keys[std::size_t(b)]; });
    return order;
  }

  void Write(const std::string& outputPath)
  {
    const std::vector<NodeIndex> order = FileOrder();
    std::vector<std::int32_t> fileIndex(Forest.Size());
    for (std::size_t i = 0; i < order.size(); ++i)
    {
      fileIndex[std::size_t(order[i])] = std::int32_t(i);
    }
    ModelWriter writer(outputPath, order.size());
    std::vector<std::uint8_t> bytes;
    // Each level's encoded patches lie together in the scratch file (levels were made one after
    // the other) and are copied out together (the file is ordered by level): the model grows as
    // the scratch shrinks, one level, and one hole punch, at a time.
    std::vector<std::uint64_t> levelFirst(std::size_t(Forest.Depth()) + 1, ~std::uint64_t(0));
    std::vector<std::uint64_t> levelEnd(levelFirst.size(), 0);
    for (NodeIndex n = 0; n < NodeIndex(Forest.Size()); ++n)
    {
      const std::size_t level = std::size_t(Forest[n].Id.Level());
      const NodeResult& r = Results[std::size_t(n)];
      levelFirst[level] = std::min(levelFirst[level], r.EncodedOffset);
      levelEnd[level] = std::max(levelEnd[level], r.EncodedOffset + r.EncodedBytes);
    }
    for (std::size_t i = 0; i < order.size(); ++i)
    {
      const TetraForest::Node& tet = Forest[order[i]];
      const NodeResult& r = Results[std::size_t(order[i])];
      ModelNode node;
      std::memset(&node, 0, sizeof(node));
      node.Tet = tet.Id.Bits;
      node.TriangleCount = r.Triangles;
      node.VertexCount = r.Vertices;
      node.Parent = tet.Parent == TetraForest::None ? -1 : fileIndex[std::size_t(tet.Parent)];
      for (int c = 0; c < 2; ++c)
      {
        node.Children[c] = tet.IsLeaf() ? -1 : fileIndex[std::size_t(tet.Child(c))];
      }
      std::copy(r.Sphere, r.Sphere + 4, node.Sphere);
      StoreCone(r.Cone, node.ConeAxis, node.ConeCos);
      node.Error = float(r.Error);
      node.SaturatedError = float(r.SaturatedError);
      std::copy(r.SaturatedSphere, r.SaturatedSphere + 4, node.SaturatedSphere);
      bytes.resize(r.EncodedBytes);
      Encoded.ReadAt(r.EncodedOffset, bytes.data(), bytes.size());
      writer.Add(node, bytes.data(), bytes.size());
      const std::size_t level = std::size_t(tet.Id.Level());
      if ((i + 1 == order.size() || Forest[order[i + 1]].Id.Level() != tet.Id.Level()) &&
        levelFirst[level] < levelEnd[level])
      {
        Encoded.Release(levelFirst[level], levelEnd[level] - levelFirst[level]);
      }
    }
    ModelHeader header;
    std::memset(&header, 0, sizeof(header));
    for (int a = 0; a < 3; ++a)
    {
      header.BoxMin[a] = Bounds.Min[a];
      header.BoxMax[a] = Bounds.Max[a];
      header.LatticeOrigin[a] = Partition.Frame().Origin()[a];
      header.QuantizationOrigin[a] = Context.Grid.Origin[a];
    }
    header.LatticeScale = Partition.Frame().Scale();
    header.QuantizationStep = Context.Grid.Step;
    header.InputTriangles = Input.TrianglesEmitted;
    header.InputBoundaryEdges = Input.BoundaryEdges;
    header.StoredTriangles = Stats.StoredTriangles;
    header.LeafCapacity = Partition.Options().LeafCapacity;
    header.PatchBudget = Options.PatchBudget;
    header.Depth = std::uint32_t(Forest.Depth());
    header.ErrorScale = Options.ErrorScale;
    header.Flags = Input.HasColors ? ModelFlagColors : 0;
    writer.Commit(header);

    Stats.Nodes = order.size();
    Stats.Depth = Forest.Depth();
    Stats.FileBytes = std::filesystem::file_size(outputPath);
    Stats.CoarsestError = 0;
    for (NodeIndex root = 0; root < RootCount; ++root)
    {
      Stats.CoarsestError = std::max(Stats.CoarsestError, Results[std::size_t(root)].SaturatedError);
    }
    if (Progress)
    {
      Progress(1);
    }
  }

  Partitioner& Partition;
  const TetraForest& Forest;
  const Box Bounds;
  const InputStats Input;
  const ConstructionOptions Options;
  const ConstructionProgress& Progress;
  const PatchJobContext Context;
  const std::unique_ptr<PatchJobRunner> OwnRunner;
  PatchJobRunner& Runner;
  PatchStore Intermediate;
  ScratchFile Encoded;
  std::uint64_t EncodedEnd = 0;
  std::vector<NodeResult> Results;
  std::size_t Done = 0;
  ConstructionStats Stats;
};

} // namespace

ConstructionStats BuildModel(Partitioner& partition, const Box& bounds, const InputStats& input,
  const ConstructionOptions& options, const std::string& outputPath,
  const ConstructionProgress& progress)
{
  ModelConstruction construction(partition, bounds, input, options, progress);
  return construction.Run(outputPath);
}

} // namespace atp
