#include "atpConstruction.h"

#include "atpBounds.h"
#include "atpCpuTime.h"
#include "atpModelFormat.h"
#include "atpModelWriter.h"
#include "atpPatchJobRunner.h"
#include "atpPatchStore.h"
#include "atpQuantizationGrid.h"
#include "atpScratchArray.h"
#include "atpScratchFile.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <utility>

namespace atp
{
namespace
{
using NodeIndex = TetraForest::NodeIndex;

/// What construction knows about one tetrahedron once its patch is made. Kept while its level
/// or its parent's is being made, then written out as its node record (`ModelConstruction::Spill`):
/// the build holds two levels of these, not the whole forest's, and those in scratch arrays.
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

/// The members of one diamond: a run of DiamondGroups::Nodes.
struct NodeRange
{
  const NodeIndex* First;
  const NodeIndex* Last;
  const NodeIndex* begin() const { return First; }
  const NodeIndex* end() const { return Last; }
  std::size_t size() const { return std::size_t(Last - First); }
  NodeIndex operator[](std::size_t i) const { return First[i]; }
};

/// Nodes of one level grouped by diamond, in two flat arrays (a level can hold millions):
/// group i is Nodes[Start[i]] up to Nodes[Start[i + 1]].
struct DiamondGroups
{
  std::vector<NodeIndex> Nodes;
  std::vector<std::size_t> Start{ 0 };
  std::size_t size() const { return Start.size() - 1; }
  NodeRange operator[](std::size_t i) const
  {
    return { Nodes.data() + Start[i], Nodes.data() + Start[i + 1] };
  }
};

/// One level's nodes: FileOrder[FirstFileIndex, FirstFileIndex + Count), in file order (by the
/// Morton code of their centroid, then by id, so that the tetrahedra a cut visits together lie
/// together in the file), and where their records and encoded patches wait for the model file.
struct Level
{
  std::int32_t FirstFileIndex = 0;
  std::size_t Count = 0;
  std::uint64_t SpillOffset = 0;                  ///< of its node records in the node scratch
  std::uint64_t EncodedFirst = ~std::uint64_t(0); ///< its encoded patches in their scratch
  std::uint64_t EncodedEnd = 0;
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
    , Context(bounds, options.PatchBudget, input.HasColors, options.Order)
    , OwnRunner(options.Runner ? nullptr : MakeThreadJobRunner(options.Threads))
    , Runner(options.Runner ? *options.Runner : *OwnRunner)
    , Intermediate(options.ScratchDirectory)
    , Encoded(options.ScratchDirectory)
    , NodeSpill(options.ScratchDirectory)
    , FileOrder(options.ScratchDirectory)
    , FileIndex(options.ScratchDirectory)
    , Current(options.ScratchDirectory)
    , Below(options.ScratchDirectory)
  {
  }

  ConstructionStats Run(const std::string& outputPath)
  {
    Runner.Begin(Context);
    Partition.StopInserting();
    NumberNodes();
    // The intermediate patches of the level below, all read by this level's diamonds, go back
    // to the file system at once when the level is done: one hole punched per level, not one
    // per patch (a punch can wait on the file system's journal).
    std::uint64_t levelBelowStart = Intermediate.BytesWritten();
    for (int level = Forest.Depth(); level >= 0; --level)
    {
      const std::uint64_t levelStart = Intermediate.BytesWritten();
      CurrentLevel = level;
      const Level& made = Levels[std::size_t(level)];
      Current.Assign(made.Count, NodeResult());
      // Made in node order, as the forest grew: the order the buckets were filled in.
      std::vector<NodeIndex> leaves, inner;
      for (std::size_t i = 0; i < made.Count; ++i)
      {
        const NodeIndex n = NodeAt(made, i);
        (Forest[n].IsLeaf() ? leaves : inner).push_back(n);
        Visited();
      }
      std::sort(leaves.begin(), leaves.end());
      std::sort(inner.begin(), inner.end());
      MakeLeafPatches(leaves, level > 0);
      SaturateLeafDiamonds(leaves);
      SimplifyDiamonds(inner, level > 0);
      Intermediate.Release({ levelBelowStart, levelStart - levelBelowStart });
      levelBelowStart = levelStart;
      if (level < Forest.Depth())
      {
        Spill(level + 1, Below);
      }
      std::swap(Below, Current);
    }
    // Below now holds level 0: the roots.
    Stats.CoarsestError = 0;
    for (std::size_t i = 0; i < Levels[0].Count; ++i)
    {
      Stats.CoarsestError = std::max(Stats.CoarsestError, Below[i].SaturatedError);
    }
    Spill(0, Below);
    ThreadCpuLap lap;
    Write(outputPath);
    lap.Lap(Stats.Cpu.WriteModel);
    return Stats;
  }

private:
  /// Groups the nodes by level in file order and gives each its index in the file.
  void NumberNodes()
  {
    Levels.assign(std::size_t(Forest.Depth()) + 1, Level());
    for (NodeIndex n = 0; n < NodeIndex(Forest.Size()); ++n)
    {
      ++Levels[std::size_t(Forest[n].Id.Level())].Count;
      Visited();
    }
    std::vector<std::size_t> placed(Levels.size());
    for (std::size_t l = 1; l < Levels.size(); ++l)
    {
      Levels[l].FirstFileIndex = Levels[l - 1].FirstFileIndex + std::int32_t(Levels[l - 1].Count);
      placed[l] = std::size_t(Levels[l].FirstFileIndex);
    }
    FileOrder.Resize(Forest.Size());
    FileIndex.Resize(Forest.Size());
    for (NodeIndex n = 0; n < NodeIndex(Forest.Size()); ++n)
    {
      FileOrder[placed[std::size_t(Forest[n].Id.Level())]++] = n;
      Visited();
    }
    for (const Level& level : Levels)
    {
      const std::size_t first = std::size_t(level.FirstFileIndex);
      std::vector<std::pair<std::pair<std::uint64_t, std::uint64_t>, NodeIndex>> keys;
      keys.reserve(level.Count);
      for (std::size_t i = first; i < first + level.Count; ++i)
      {
        const NodeIndex n = FileOrder[i];
        keys.push_back({ { CentroidMorton(Forest.Geometry(n)), Forest[n].Id.Bits }, n });
        Visited();
      }
      std::sort(keys.begin(), keys.end());
      for (std::size_t i = 0; i < keys.size(); ++i)
      {
        FileOrder[first + i] = keys[i].second;
        FileIndex[std::size_t(keys[i].second)] = std::int32_t(first + i);
        Visited();
      }
    }
  }

  /// The i-th node of a level in file order.
  NodeIndex NodeAt(const Level& level, std::size_t i) const
  {
    return FileOrder[std::size_t(level.FirstFileIndex) + i];
  }

  /// The result of a node of the level being made or of the one below it.
  const NodeResult& Result(NodeIndex n) const
  {
    const int level = Forest[n].Id.Level();
    const std::size_t slot =
      std::size_t(FileIndex[std::size_t(n)] - Levels[std::size_t(level)].FirstFileIndex);
    return level == CurrentLevel ? Current[slot] : Below[slot];
  }
  NodeResult& Result(NodeIndex n)
  {
    return const_cast<NodeResult&>(std::as_const(*this).Result(n));
  }

  /// The scratch files grow as patches and node records are stored: keeps their largest total.
  void NoteScratchPeak()
  {
    Stats.PeakScratchBytes =
      std::max(Stats.PeakScratchBytes, EncodedEnd + Intermediate.PeakBytes() + NodeSpillEnd);
  }

  /// Gives back the pages of everything that has a record per node (the forest, the bucket
  /// table, the numbering, the two levels of results): they come back as they are used, so
  /// resident memory follows the diamonds at work rather than the number of nodes.
  void ReleaseResident() const
  {
    Partition.ReleaseResident();
    FileOrder.ReleaseResident();
    FileIndex.ReleaseResident();
    Current.ReleaseResident();
    Below.ReleaseResident();
  }

  /// Every loop over nodes counts them here: every ReleaseInterval of them, the records per
  /// node go back (ReleaseResident), whichever loop touched them.
  void Visited(std::size_t nodes = 1)
  {
    NodesVisited += nodes;
    if (NodesVisited >= NextRelease)
    {
      ReleaseResident();
      NextRelease = NodesVisited + ReleaseInterval;
    }
  }

  void ReportProgress(std::size_t nodesDone)
  {
    Done += nodesDone;
    Visited(nodesDone);
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
    NodeResult& r = Result(node);
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
    NoteScratchPeak();
  }

  /// Runner.Run, with the CPU time of loading jobs (on whichever threads) and storing results
  /// counted.
  void RunJobs(std::size_t count, const PatchJobRunner::LoadJob& load,
    const PatchJobRunner::StoreResult& store)
  {
    Runner.Run(
      count,
      [&](std::size_t i, PatchJob& job) {
        ThreadCpuLap lap;
        load(i, job);
        double seconds = 0;
        lap.Lap(seconds);
        const std::lock_guard<std::mutex> lock(LoadCpuMutex);
        Stats.Cpu.LoadJobs += seconds;
      },
      [&](std::size_t i, PatchJobResult& made) {
        ThreadCpuLap lap;
        store(i, made);
        lap.Lap(Stats.Cpu.StoreResults);
      });
  }

  /// Leaves keep the input at full resolution: their bucket, welded into an indexed patch.
  void MakeLeafPatches(const std::vector<NodeIndex>& leaves, bool haveParents)
  {
    RunJobs(
      leaves.size(),
      // Buckets are read and released by several threads at once.
      [&](std::size_t i, PatchJob& job) {
        Partition.ReadLeaf(leaves[i], job.Soup);
        Partition.ReleaseLeaf(leaves[i]);
      },
      [&](std::size_t i, PatchJobResult& made) {
        Store(leaves[i], made.Patches[0], haveParents);
        Result(leaves[i]).Cone = made.Patches[0].Cone;
        Stats.RepeatedTrianglesDropped += made.RepeatedTrianglesDropped;
        Stats.Cpu.LeafWeld += made.Cpu.Prepare;
        Stats.Cpu.LeafEncode += made.Cpu.Encode;
        ReportProgress(1);
      });
  }

  /// Leaves are never refined, but their diamond still shares one saturated sphere (the
  /// invariant every diamond keeps); their error is zero.
  void SaturateLeafDiamonds(const std::vector<NodeIndex>& leaves)
  {
    const DiamondGroups diamonds = GroupByDiamond(leaves);
    for (std::size_t d = 0; d < diamonds.size(); ++d)
    {
      const NodeRange members = diamonds[d];
      std::vector<Sphere> spheres;
      for (NodeIndex m : members)
      {
        spheres.push_back(LoadSphere(Result(m).Sphere));
      }
      float saturated[4];
      StoreSphere(EnclosingSphere(spheres), saturated);
      for (NodeIndex m : members)
      {
        std::copy(saturated, saturated + 4, Result(m).SaturatedSphere);
      }
      Visited(members.size());
    }
  }

  /// Nodes of one level grouped by diamond: groups ordered by diamond id, members by TetId.
  DiamondGroups GroupByDiamond(const std::vector<NodeIndex>& nodes)
  {
    std::vector<std::pair<std::pair<std::uint64_t, std::uint64_t>, NodeIndex>> keys;
    keys.reserve(nodes.size());
    for (NodeIndex n : nodes)
    {
      keys.push_back({ { DiamondOf(Forest.Geometry(n)).Bits, Forest[n].Id.Bits }, n });
      Visited();
    }
    std::sort(keys.begin(), keys.end());
    DiamondGroups groups;
    groups.Nodes.reserve(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i)
    {
      if (i > 0 && keys[i].first.first != keys[i - 1].first.first)
      {
        groups.Start.push_back(i);
      }
      groups.Nodes.push_back(keys[i].second);
    }
    if (!keys.empty())
    {
      groups.Start.push_back(keys.size());
    }
    return groups;
  }

  void SimplifyDiamonds(const std::vector<NodeIndex>& inner, bool haveParents)
  {
    const DiamondGroups diamonds = GroupByDiamond(inner);
    RunJobs(
      diamonds.size(),
      [&](std::size_t i, PatchJob& job) { LoadDiamond(diamonds[i], job); },
      [&](std::size_t i, PatchJobResult& made) {
        SaturateDiamond(diamonds[i], made, haveParents);
        Stats.Cpu.DiamondMerge += made.Cpu.Prepare;
        Stats.Cpu.DiamondSimplify += made.Cpu.Simplify;
        Stats.Cpu.DiamondEncode += made.Cpu.Encode;
        ReportProgress(diamonds[i].size());
      });
  }

  /// A diamond's job: its members' shapes and their children's full-precision patches. Runs on
  /// any thread: the children are the level below, finished, and the patch store reads from
  /// several threads at once.
  void LoadDiamond(NodeRange members, PatchJob& job) const
  {
    for (NodeIndex m : members)
    {
      job.Members.push_back(Forest.Geometry(m));
      for (NodeIndex c : Forest[m].Children())
      {
        job.Children.emplace_back();
        Intermediate.Get(Result(c).Intermediate, job.Children.back());
        job.ChildError = std::max(job.ChildError, Result(c).Error);
      }
    }
  }

  /// Runs on the main thread, in diamond order: stores the patches and saturates errors,
  /// spheres and cones over the diamond and its children (paper 5.2).
  void SaturateDiamond(
    NodeRange members, const PatchJobResult& made, bool haveParents)
  {
    double childSaturatedError = 0;
    std::vector<Sphere> spheres;
    for (std::size_t i = 0; i < members.size(); ++i)
    {
      const NodeIndex m = members[i];
      Store(m, made.Patches[i], haveParents);
      Stats.SimplifiedPatchesOverBudget += made.Patches[i].Mesh.TriangleCount() > Options.PatchBudget;
      spheres.push_back(LoadSphere(Result(m).Sphere));
      std::vector<NormalCone> cones{ made.Patches[i].Cone };
      for (NodeIndex c : Forest[m].Children())
      {
        const NodeResult& child = Result(c);
        childSaturatedError = std::max(childSaturatedError, child.SaturatedError);
        spheres.push_back(LoadSphere(child.SaturatedSphere));
        cones.push_back(child.Cone);
      }
      Result(m).Cone = EnclosingCone(cones);
    }
    const double error = made.Error;
    const double saturatedError = std::max(error, childSaturatedError);
    float saturatedSphere[4];
    StoreSphere(EnclosingSphere(spheres), saturatedSphere);
    for (NodeIndex m : members)
    {
      NodeResult& r = Result(m);
      r.Error = error;
      r.SaturatedError = saturatedError;
      std::copy(saturatedSphere, saturatedSphere + 4, r.SaturatedSphere);
    }
    ++Stats.Diamonds;
    Stats.Collapses += made.Collapses;
    Stats.QuotaMisses += made.TrianglesOverQuotas > 0;
    Stats.TrianglesOverQuotas += made.TrianglesOverQuotas;
    Stats.PiecesRemoved += made.PiecesRemoved;
    Stats.DiamondsFacingAtRandom += made.FacingAtRandom;
  }

  /// Writes the finished records of a level (`results` in file order) to the node scratch, each
  /// holding its encoded patch's place in PatchOffset and PatchBytes until Write copies it.
  void Spill(int levelIndex, const ScratchArray<NodeResult>& results)
  {
    Level& level = Levels[std::size_t(levelIndex)];
    level.SpillOffset = NodeSpillEnd;
    std::vector<ModelNode> records;
    records.reserve(std::min(level.Count, RecordsPerIo));
    for (std::size_t i = 0; i < level.Count; ++i)
    {
      const TetraForest::Node& tet = Forest[NodeAt(level, i)];
      const NodeResult& r = results[i];
      ModelNode node;
      std::memset(&node, 0, sizeof(node));
      node.Tet = tet.Id.Bits;
      node.PatchOffset = r.EncodedOffset;
      node.PatchBytes = r.EncodedBytes;
      node.TriangleCount = r.Triangles;
      node.VertexCount = r.Vertices;
      node.Parent = tet.Parent == TetraForest::None ? -1 : FileIndex[std::size_t(tet.Parent)];
      for (int c = 0; c < 2; ++c)
      {
        node.Children[c] = tet.IsLeaf() ? -1 : FileIndex[std::size_t(tet.Child(c))];
      }
      std::copy(r.Sphere, r.Sphere + 4, node.Sphere);
      StoreCone(r.Cone, node.ConeAxis, node.ConeCos);
      node.Error = float(r.Error);
      node.SaturatedError = float(r.SaturatedError);
      std::copy(r.SaturatedSphere, r.SaturatedSphere + 4, node.SaturatedSphere);
      level.EncodedFirst = std::min(level.EncodedFirst, r.EncodedOffset);
      level.EncodedEnd = std::max(level.EncodedEnd, r.EncodedOffset + r.EncodedBytes);
      records.push_back(node);
      Visited();
      if (records.size() == RecordsPerIo || i + 1 == level.Count)
      {
        NodeSpill.WriteAt(NodeSpillEnd, records.data(), records.size() * sizeof(ModelNode));
        NodeSpillEnd += records.size() * sizeof(ModelNode);
        records.clear();
      }
    }
    NoteScratchPeak();
  }

  void Write(const std::string& outputPath)
  {
    ModelWriter writer(outputPath, Forest.Size());
    std::vector<ModelNode> records;
    std::vector<std::uint8_t> bytes;
    // Each level's encoded patches lie together in the scratch file (levels were made one after
    // the other) and are copied out together (the file is ordered by level): the model grows as
    // the scratch shrinks, one level, and one hole punch, at a time.
    for (const Level& level : Levels)
    {
      for (std::size_t first = 0; first < level.Count; first += RecordsPerIo)
      {
        records.resize(std::min(RecordsPerIo, level.Count - first));
        NodeSpill.ReadAt(level.SpillOffset + first * sizeof(ModelNode), records.data(),
          records.size() * sizeof(ModelNode));
        for (const ModelNode& node : records)
        {
          bytes.resize(node.PatchBytes);
          Encoded.ReadAt(node.PatchOffset, bytes.data(), bytes.size());
          writer.Add(node, bytes.data(), bytes.size());
        }
      }
      if (level.EncodedFirst < level.EncodedEnd)
      {
        Encoded.Release(level.EncodedFirst, level.EncodedEnd - level.EncodedFirst);
      }
      NodeSpill.Release(level.SpillOffset, level.Count * sizeof(ModelNode));
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
    header.InputTriangles = Input.TrianglesEmitted - Stats.RepeatedTrianglesDropped;
    header.InputBoundaryEdges = Input.BoundaryEdges;
    header.StoredTriangles = Stats.StoredTriangles;
    header.LeafCapacity = Partition.Options().LeafCapacity;
    header.PatchBudget = Options.PatchBudget;
    header.Depth = std::uint32_t(Forest.Depth());
    header.ErrorScale = Options.ErrorScale;
    header.Flags = (Input.HasColors ? ModelFlagColors : 0) |
      (Options.Order == CacheOrder::Fast ? ModelFlagFastCacheOrder : 0);
    // The last report before the file replaces any old one: a report may cancel the build,
    // and a cancelled build must leave the old file as it was.
    if (Progress)
    {
      Progress(1);
    }
    writer.Commit(header);

    Stats.Nodes = Forest.Size();
    Stats.Depth = Forest.Depth();
    Stats.FileBytes = std::filesystem::file_size(outputPath);
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
  /// Node records of finished levels, deepest first, until Write copies them in file order.
  ScratchFile NodeSpill;
  std::uint64_t NodeSpillEnd = 0;
  static constexpr std::size_t RecordsPerIo = 8192;
  /// Nodes visited between two ReleaseResident: a few thousand nodes touch at most a few
  /// thousand pages, which come back in milliseconds.
  static constexpr std::size_t ReleaseInterval = 4096;
  std::vector<Level> Levels;
  ScratchArray<NodeIndex> FileOrder;   ///< per file index: the node
  ScratchArray<std::int32_t> FileIndex; ///< per node
  int CurrentLevel = -1;
  ScratchArray<NodeResult> Current; ///< the level being made, in file order
  ScratchArray<NodeResult> Below;   ///< the level below it, read by its diamonds
  std::size_t Done = 0;
  std::size_t NodesVisited = 0;
  std::size_t NextRelease = ReleaseInterval;
  ConstructionStats Stats;
  /// Guards Stats.Cpu.LoadJobs, which jobs loaded on other threads add to.
  std::mutex LoadCpuMutex;
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
