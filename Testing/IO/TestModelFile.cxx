// The .atp container: round trip, one failing file per validation rule, random corruption and
// truncation never crash, and the writer never leaves a partial or damaged file behind.
#include "ModelRewrite.h"
#include "atpChecksum.h"
#include "atpModelFile.h"
#include "atpModelFormat.h"
#include "atpModelWriter.h"
#include "atpPatchCodec.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <utility>
#include <vector>

using atp::test::Edit;
using atp::test::ReadAll;
using atp::test::Rewrite;
using atp::test::Seal;
using atp::test::WriteAll;

namespace
{
namespace fs = std::filesystem;
using namespace atp;

std::uint64_t AlignUp16(std::uint64_t bytes)
{
  return (bytes + 15) / 16 * 16;
}

// The offsets docs/atp-format.md documents.
static_assert(offsetof(ModelHeader, FileBytes) == 24, "docs/atp-format.md");
static_assert(offsetof(ModelHeader, PatchSectionChecksum) == 80, "docs/atp-format.md");
static_assert(offsetof(ModelHeader, BoxMin) == 88, "docs/atp-format.md");
static_assert(offsetof(ModelHeader, QuantizationStep) == 192, "docs/atp-format.md");
static_assert(offsetof(ModelHeader, StoredTriangles) == 216, "docs/atp-format.md");
static_assert(offsetof(ModelHeader, Flags) == 236, "docs/atp-format.md");
static_assert(offsetof(ModelHeader, ErrorScale) == 240, "docs/atp-format.md");
static_assert(offsetof(ModelHeader, Reserved) == 244, "docs/atp-format.md");
static_assert(offsetof(ModelHeader, HeaderChecksum) == 408, "docs/atp-format.md");
static_assert(offsetof(ModelNode, PatchBytes) == 24, "docs/atp-format.md");
static_assert(offsetof(ModelNode, Parent) == 36, "docs/atp-format.md");
static_assert(offsetof(ModelNode, Sphere) == 48, "docs/atp-format.md");
static_assert(offsetof(ModelNode, ConeCos) == 76, "docs/atp-format.md");
static_assert(offsetof(ModelNode, SaturatedSphere) == 88, "docs/atp-format.md");
static_assert(offsetof(ModelNode, Reserved) == 104, "docs/atp-format.md");

class TempDirectory
{
public:
  TempDirectory()
  {
    std::string name = (fs::temp_directory_path() / "atp-model-test-XXXXXX").string();
    if (!::mkdtemp(name.data()))
    {
      throw std::runtime_error("cannot create a test directory");
    }
    Path = name;
  }
  ~TempDirectory() { fs::remove_all(Path); }
  std::string operator/(const std::string& name) const { return (Path / name).string(); }
  std::vector<std::string> Entries() const
  {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(Path))
    {
      names.push_back(entry.path().filename().string());
    }
    return names;
  }

private:
  fs::path Path;
};

bool SameBytes(const std::uint8_t* data, const std::vector<std::uint8_t>& expected)
{
  return expected.empty() || std::memcmp(data, expected.data(), expected.size()) == 0;
}

struct Model
{
  ModelHeader Header;
  std::vector<ModelNode> Nodes;
  std::vector<std::vector<std::uint8_t>> Patches;
};

ModelNode MakeNode(std::uint64_t tet, std::int32_t parent, int level)
{
  ModelNode n{};
  n.Tet = tet;
  n.Parent = parent;
  n.Children[0] = n.Children[1] = -1;
  const float size = std::ldexp(1.0f, -level);
  n.Sphere[0] = 0.25f * float(tet % 5);
  n.Sphere[1] = 0.5f;
  n.Sphere[2] = -0.75f;
  n.Sphere[3] = size;
  n.ConeAxis[2] = 1;
  n.ConeCos = level == 0 ? -1.0f : 0.5f;
  n.SaturatedError = 8.0f * size;
  n.Error = 0.5f * n.SaturatedError;
  std::copy(std::begin(n.Sphere), std::end(n.Sphere), std::begin(n.SaturatedSphere));
  n.SaturatedSphere[3] = 2 * size;
  return n;
}

// The 6 roots, then `splits` applied in order (each splits the node of that index, appending its
// two children). The default splits root 2, then its first child: 10 nodes over 3 levels.
Model Synthetic(const std::vector<int>& splits = { 2, 6 })
{
  Model m;
  for (int r = 0; r < 6; ++r)
  {
    m.Nodes.push_back(MakeNode(8u | std::uint64_t(r), -1, 0));
  }
  std::vector<int> levels(6, 0);
  for (int s : splits)
  {
    for (int which = 0; which < 2; ++which)
    {
      m.Nodes[s].Children[which] = std::int32_t(m.Nodes.size());
      m.Nodes.push_back(MakeNode((m.Nodes[s].Tet << 1) | std::uint64_t(which), s, levels[s] + 1));
      levels.push_back(levels[s] + 1);
    }
  }

  std::mt19937 random(42);
  std::uint64_t triangles = 0;
  for (std::size_t i = 0; i < m.Nodes.size(); ++i)
  {
    // Odd sizes and an empty patch (the patch header alone) exercise the alignment padding.
    const std::size_t bytes = PatchHeaderBytes + (i == 3 ? 0 : random() % 3000);
    std::vector<std::uint8_t> patch(bytes);
    for (auto& b : patch)
    {
      b = std::uint8_t(random());
    }
    m.Patches.push_back(patch);
    m.Nodes[i].TriangleCount = i == 3 ? 0 : std::uint32_t(bytes / 7);
    m.Nodes[i].VertexCount = m.Nodes[i].TriangleCount == 0 ? 0 : m.Nodes[i].TriangleCount / 2 + 3;
    triangles += m.Nodes[i].TriangleCount;
    if (m.Nodes[i].TriangleCount == 0)
    {
      std::fill(std::begin(m.Nodes[i].Sphere), std::end(m.Nodes[i].Sphere), 0.0f); // the empty sphere
    }
  }

  ModelHeader& h = m.Header;
  h = ModelHeader{};
  for (int a = 0; a < 3; ++a)
  {
    h.BoxMin[a] = -1.5 + a;
    h.BoxMax[a] = 2.0 + 3 * a;
    h.LatticeOrigin[a] = h.BoxMin[a];
    h.QuantizationOrigin[a] = h.BoxMin[a] - 0.125;
  }
  h.LatticeScale = 1048576.0 / 9.0;
  h.QuantizationStep = 1.0 / 4096;
  for (const ModelNode& n : m.Nodes)
  {
    h.InputTriangles += n.Children[0] == -1 ? n.TriangleCount : 0; // what the leaves hold
  }
  h.InputBoundaryEdges = 321;
  h.StoredTriangles = triangles;
  h.LeafCapacity = 4000;
  h.PatchBudget = 8000;
  h.Depth = std::uint32_t(*std::max_element(levels.begin(), levels.end()));
  h.Flags = ModelFlagColors;
  h.ErrorScale = 1.25f;
  return m;
}

// Writes `m` and returns the nodes as the file holds them (patch fields filled in).
std::vector<ModelNode> Write(const Model& m, const std::string& path)
{
  ModelWriter writer(path, m.Nodes.size());
  for (std::size_t i = 0; i < m.Nodes.size(); ++i)
  {
    writer.Add(m.Nodes[i], m.Patches[i].data(), m.Patches[i].size());
  }
  writer.Commit(m.Header);
  const std::vector<std::uint8_t> bytes = ReadAll(path);
  std::vector<ModelNode> nodes(m.Nodes.size());
  std::memcpy(nodes.data(), bytes.data() + ModelWriter::NodeSectionOffset(),
    nodes.size() * sizeof(ModelNode));
  return nodes;
}

std::string OpenError(const std::string& path)
{
  try
  {
    ModelFile::Open(path);
  }
  catch (const ModelError& e)
  {
    return e.what();
  }
  return "";
}

void ExpectOpenError(const std::string& path, const std::string& fragment)
{
  const std::string message = OpenError(path);
  EXPECT_NE(message.find(fragment), std::string::npos)
    << "expected \"" << fragment << "\", got \"" << message << "\"";
  EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << "the message names the file: " << message;
}

TEST(ModelFile, RoundTrip)
{
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  const Model m = Synthetic();
  const std::vector<ModelNode> written = Write(m, path);
  EXPECT_EQ(dir.Entries(), std::vector<std::string>{ "model.atp" });

  const ModelFile file = ModelFile::Open(path);
  const ModelHeader& h = file.Header();
  EXPECT_EQ(std::memcmp(h.Magic, ModelMagic, sizeof(ModelMagic)), 0);
  EXPECT_EQ(h.Version, ModelVersion);
  EXPECT_EQ(h.ByteOrder, ModelByteOrderMark);
  EXPECT_EQ(h.HeaderBytes, sizeof(ModelHeader));
  EXPECT_EQ(h.NodeBytes, sizeof(ModelNode));
  EXPECT_EQ(h.FileBytes, fs::file_size(path));
  EXPECT_EQ(h.NodeCount, m.Nodes.size());
  EXPECT_EQ(h.NodeSectionOffset, 448u);
  EXPECT_EQ(h.NodeSectionBytes, m.Nodes.size() * sizeof(ModelNode));
  EXPECT_EQ(h.PatchSectionOffset % 64, 0u);
  EXPECT_EQ(h.PatchSectionOffset + h.PatchSectionBytes, h.FileBytes);
  // Every model field as the caller gave it, bit for bit.
  const std::size_t modelFrom = offsetof(ModelHeader, BoxMin);
  const std::size_t modelTo = offsetof(ModelHeader, Reserved);
  EXPECT_EQ(std::memcmp(reinterpret_cast<const char*>(&h) + modelFrom,
              reinterpret_cast<const char*>(&m.Header) + modelFrom, modelTo - modelFrom),
    0);
  EXPECT_EQ(h.Depth, 2u);
  EXPECT_EQ(h.ErrorScale, 1.25f);

  ASSERT_EQ(file.NodeCount(), m.Nodes.size());
  EXPECT_EQ(std::memcmp(file.Nodes(), written.data(), written.size() * sizeof(ModelNode)), 0);
  for (std::size_t i = 0; i < file.NodeCount(); ++i)
  {
    SCOPED_TRACE("node " + std::to_string(i));
    const ModelNode& n = file.Node(i);
    const ModelNode& given = m.Nodes[i];
    EXPECT_EQ(n.Tet, given.Tet);
    EXPECT_EQ(n.Parent, given.Parent);
    EXPECT_EQ(n.Children[0], given.Children[0]);
    EXPECT_EQ(n.Children[1], given.Children[1]);
    EXPECT_EQ(n.TriangleCount, given.TriangleCount);
    EXPECT_EQ(n.VertexCount, given.VertexCount);
    EXPECT_EQ(std::memcmp(n.Sphere, given.Sphere, offsetof(ModelNode, Reserved) -
                offsetof(ModelNode, Sphere)),
      0);
    EXPECT_EQ(n.PatchBytes, m.Patches[i].size());
    EXPECT_EQ(n.PatchChecksum, Checksum(m.Patches[i].data(), m.Patches[i].size()));
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(file.PatchData(i)) % ModelWriter::PatchAlignment,
      0u);
    EXPECT_TRUE(SameBytes(file.PatchData(i), m.Patches[i]));
    EXPECT_NO_THROW(file.CheckPatch(i));
  }
  EXPECT_EQ(file.Verify(), std::vector<std::string>{});
  EXPECT_EQ(file.Path(), path);
}

TEST(ModelFile, MovesKeepTheMap)
{
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  Write(Synthetic(), path);
  ModelFile first = ModelFile::Open(path);
  ModelFile second = std::move(first);
  EXPECT_EQ(first.NodeCount(), 0u);
  EXPECT_EQ(second.NodeCount(), 10u);
  first = std::move(second);
  EXPECT_EQ(first.Node(9).Tet, 41u);
  EXPECT_TRUE(first.Verify().empty());
}

// The writer streams nodes to the file a buffer at a time: a model of more nodes than one
// buffer holds (8192) reads back whole, with valid section checksums.
TEST(ModelWriter, ManyNodesAreWrittenInPieces)
{
  TempDirectory dir;
  const std::string path = dir / "many.atp";
  std::vector<int> splits(10000);
  std::iota(splits.begin(), splits.end(), 0); // breadth first: levels in order
  const Model m = Synthetic(splits);
  ASSERT_GT(m.Nodes.size(), 2 * 8192u);
  Write(m, path);
  const ModelFile file = ModelFile::Open(path);
  ASSERT_EQ(file.NodeCount(), m.Nodes.size());
  EXPECT_TRUE(file.Verify().empty());
  for (std::size_t i = 0; i < file.NodeCount(); ++i)
  {
    ASSERT_EQ(file.Node(i).Tet, m.Nodes[i].Tet) << "node " << i;
    ASSERT_EQ(file.Node(i).Parent, m.Nodes[i].Parent) << "node " << i;
    ASSERT_EQ(file.Node(i).PatchBytes, m.Patches[i].size()) << "node " << i;
    ASSERT_TRUE(SameBytes(file.PatchData(i), m.Patches[i])) << "node " << i;
  }
}

TEST(ModelFile, DeepestLevelIsValid)
{
  TempDirectory dir;
  const std::string path = dir / "deep.atp";
  // A chain of 60 splits down to the lattice spacing.
  std::vector<int> splits = { 5 };
  for (int level = 1; level < 60; ++level)
  {
    splits.push_back(6 + 2 * (level - 1) + (level & 1));
  }
  Write(Synthetic(splits), path);
  const ModelFile file = ModelFile::Open(path);
  EXPECT_EQ(file.Header().Depth, 60u);
  EXPECT_EQ(60 - __builtin_clzll(file.Node(file.NodeCount() - 1).Tet), 60);

  // A level-60 tetrahedron has no children (its TetId would need a 65th bit).
  Rewrite(path,
    [](ModelHeader&, std::vector<ModelNode>& n, std::vector<std::uint8_t>&) {
      n.back().Children[0] = std::int32_t(n.size());
      n.back().Children[1] = std::int32_t(n.size() + 1);
    },
    Seal::All);
  ExpectOpenError(path, "children below the deepest level 60");
}

struct Rule
{
  const char* Name;
  Seal Sealing;
  Edit Change;
  std::string Expected;
};

TEST(ModelFile, EveryValidationRuleHasItsOwnError)
{
  using H = ModelHeader;
  using N = std::vector<ModelNode>;
  using R = std::vector<std::uint8_t>;
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  const std::vector<ModelNode> written = Write(Synthetic(), path);
  const std::vector<std::uint8_t> good = ReadAll(path);
  const std::uint64_t size = good.size();
  ASSERT_EQ(OpenError(path), "") << "the unedited file must open, or the cases prove nothing";
  ASSERT_EQ(written[3].PatchBytes, PatchHeaderBytes) << "node 3 holds an empty patch";
  ASSERT_GE(written[9].PatchBytes, PatchHeaderBytes + 16) << "node 9's patch can lose 16 bytes";

  const std::vector<Rule> rules = {
    { "magic", Seal::None, [](H& h, N&, R&) { h.Magic[0] = 'X'; }, "not an ATP model" },
    { "byte order swapped", Seal::None,
      [](H& h, N&, R&) { h.ByteOrder = __builtin_bswap32(ModelByteOrderMark); },
      "written on a machine of the other byte order" },
    { "byte order garbage", Seal::None, [](H& h, N&, R&) { h.ByteOrder = 7; },
      "bad byte-order mark 0x7" },
    { "newer version", Seal::All, [](H& h, N&, R&) { h.Version = 5; },
      "made by a newer version 5 of the format" },
    { "older version", Seal::All, [](H& h, N&, R&) { h.Version = 2; },
      "made by the older version 2 of the format (this reader reads versions 3 to 4): build it again" },
    { "version 0", Seal::All, [](H& h, N&, R&) { h.Version = 0; }, "unknown format version 0" },
    { "header size", Seal::All, [](H& h, N&, R&) { h.HeaderBytes = 400; },
      "header record of 400 bytes, expected 416" },
    { "node size", Seal::All, [](H& h, N&, R&) { h.NodeBytes = 64; },
      "node record of 64 bytes, expected 128" },
    { "header checksum", Seal::None, [](H& h, N&, R&) { h.Reserved[100] ^= 1; },
      "header checksum mismatch" },
    { "truncated", Seal::All, [](H& h, N&, R&) { h.FileBytes += 64; },
      "truncated: " + std::to_string(size) + " of " + std::to_string(size + 64) + " bytes" },
    { "trailing data", Seal::All, [](H& h, N&, R&) { h.FileBytes -= 16; }, "trailing data" },
    { "too few nodes", Seal::All, [](H& h, N&, R&) { h.NodeCount = 5; },
      "5 nodes, fewer than the 6 roots" },
    { "too many nodes", Seal::All, [](H& h, N&, R&) { h.NodeCount = std::uint64_t(1) << 61; },
      "nodes cannot fit in a file of" },
    { "node section offset", Seal::All, [](H& h, N&, R&) { h.NodeSectionOffset = 512; },
      "node section at offset 512, expected 448" },
    { "node section size", Seal::All, [](H& h, N&, R&) { h.NodeSectionBytes -= 128; },
      "node section of 1152 bytes, expected 1280" },
    { "patch section offset", Seal::All, [](H& h, N&, R&) { h.PatchSectionOffset += 64; },
      "patch section at offset" },
    { "patch section size", Seal::All, [](H& h, N&, R&) { h.PatchSectionBytes -= 16; },
      "does not end the file" },
    { "padding", Seal::All, [](H&, N&, R& raw) { raw[420] = 1; },
      "nonzero padding at byte 420" },
    { "bounding box", Seal::All, [](H& h, N&, R&) { h.BoxMin[1] = h.BoxMax[1] + 1; },
      "bounding box is not finite or is inverted" },
    { "lattice scale", Seal::All, [](H& h, N&, R&) { h.LatticeScale = 0; },
      "lattice origin or scale" },
    { "quantization step", Seal::All,
      [](H& h, N&, R&) { h.QuantizationStep = std::nan(""); }, "quantization origin or step" },
    { "quantization origin past floats", Seal::All, [](H& h, N&, R&) { h.QuantizationOrigin[2] = 1e300; },
      "quantization grid reaches beyond the range of floats" },
    { "quantization step past floats", Seal::All, [](H& h, N&, R&) { h.QuantizationStep = 1e35; },
      "quantization grid reaches beyond the range of floats" },
    { "error scale", Seal::All, [](H& h, N&, R&) { h.ErrorScale = -1; }, "error scale" },
    { "node checksum", Seal::HeaderOnly, [](H&, N& n, R&) { n[7].Error *= 0.5f; },
      "node section checksum mismatch" },
    { "tet id zero", Seal::All, [](H&, N& n, R&) { n[4].Tet = 0; },
      "node 4: invalid tetrahedron id 0x0" },
    { "tet id root 6", Seal::All, [](H&, N& n, R&) { n[4].Tet = 8 | 6; },
      "node 4: invalid tetrahedron id 0xe" },
    { "roots first", Seal::All, [](H&, N& n, R&) { n[5].Tet = 8 << 1; },
      "node 5: one of the 6 roots expected, found a level-1 tetrahedron" },
    { "root twice", Seal::All, [](H&, N& n, R&) { n[5].Tet = n[4].Tet; },
      "node 5: root 4 listed twice" },
    { "root with parent", Seal::All, [](H&, N& n, R&) { n[1].Parent = 0; },
      "node 1: a root with parent 0" },
    { "parent does not list child", Seal::All,
      [](H&, N& n, R&) { n[2].Children[0] = n[2].Children[1] = -1; },
      "node 6: parent 2 does not list it as its child" },
    { "parent is later", Seal::All,
      [](H&, N& n, R&) {
        n[2].Children[0] = n[2].Children[1] = -1;
        n[6].Parent = 7;
      },
      "node 6: parent 7 is not an earlier node" },
    { "parent is no parent", Seal::All,
      [](H&, N& n, R&) {
        n[2].Children[0] = n[2].Children[1] = -1;
        n[6].Parent = 1;
      },
      "node 6: parent 1 is not its parent tetrahedron" },
    { "one child", Seal::All, [](H&, N& n, R&) { n[9].Children[1] = 8; },
      "node 9: one child" },
    { "child is earlier", Seal::All, [](H&, N& n, R&) { n[7].Children[0] = 6, n[7].Children[1] = 8; },
      "node 7: child 6 is not a later node" },
    { "child out of range", Seal::All,
      [](H&, N& n, R&) { n[7].Children[0] = 10, n[7].Children[1] = 11; },
      "node 7: child 10 is not a later node" },
    { "children swapped", Seal::All, [](H&, N& n, R&) { std::swap(n[6].Children[0], n[6].Children[1]); },
      "node 6: child 9 is not its child tetrahedron 0" },
    { "child names another parent", Seal::All, [](H&, N& n, R&) { n[8].Parent = 7; },
      "node 6: child 8 names node 7 as its parent" },
    { "patch out of place", Seal::All, [](H&, N& n, R&) { n[7].PatchOffset += 4; },
      "node 7: patch at offset" },
    { "patch too long", Seal::All,
      [](H& h, N& n, R&) { n[9].PatchBytes = std::uint32_t(h.PatchSectionBytes); },
      "node 9: patch of" },
    { "patch beyond section", Seal::All,
      [](H& h, N& n, R&) { n[9].PatchOffset = h.PatchSectionBytes + 16; },
      "outside the patch section" },
    { "patch shared with another node", Seal::All, [](H&, N& n, R&) { n[9].PatchOffset = n[8].PatchOffset; },
      "node 9: patch at offset " + std::to_string(written[8].PatchOffset) + ", expected " +
        std::to_string(written[9].PatchOffset) },
    { "patch shorter than its header", Seal::All, [](H&, N& n, R&) { n[3].PatchBytes = 40; },
      "node 3: patch of 40 bytes, shorter than the 43-byte patch header" },
    { "bytes after the last patch", Seal::All, [](H&, N& n, R&) { n[9].PatchBytes -= 16; },
      "the patches end at byte " + std::to_string(written[9].PatchOffset + AlignUp16(written[9].PatchBytes - 16)) },
    { "triangle count", Seal::All,
      [](H& h, N& n, R&) {
        h.StoredTriangles += (1u << 24) + 1 - n[3].TriangleCount;
        n[3].TriangleCount = (1u << 24) + 1;
      },
      "node 3: 16777217 triangles, more than 16777216" },
    { "vertex count", Seal::All,
      [](H&, N& n, R&) { n[4].VertexCount = 3 * n[4].TriangleCount + 1; },
      "node 4: " + std::to_string(3 * written[4].TriangleCount + 1) + " vertices for " +
        std::to_string(written[4].TriangleCount) + " triangles" },
    { "non-finite sphere", Seal::All,
      [](H&, N& n, R&) { n[5].Sphere[1] = std::numeric_limits<float>::infinity(); },
      "node 5: bounds or errors not finite" },
    { "non-finite cone", Seal::All, [](H&, N& n, R&) { n[8].ConeAxis[0] = std::nanf(""); },
      "node 8: bounds or errors not finite" },
    { "negative radius", Seal::All, [](H&, N& n, R&) { n[8].SaturatedSphere[3] = -1; },
      "node 8: negative sphere radius" },
    { "cone cosine", Seal::All, [](H&, N& n, R&) { n[6].ConeCos = 1.5f; },
      "node 6: normal cone cosine 1.5 outside [-1, 1]" },
    { "negative error", Seal::All, [](H&, N& n, R&) { n[0].Error = -1; },
      "node 0: negative error -1" },
    { "error above saturated", Seal::All, [](H&, N& n, R&) { n[3].Error = n[3].SaturatedError + 1; },
      "node 3: saturated error 8 below its own error 9" },
    { "saturated error grows", Seal::All, [](H&, N& n, R&) { n[8].SaturatedError = 100; },
      "node 8: saturated error 100 above its parent's 4" },
    { "stored triangles", Seal::All, [](H& h, N&, R&) { h.StoredTriangles += 1; },
      "stored triangles, the nodes hold" },
    { "grid beside the box", Seal::All, [](H& h, N&, R&) { h.QuantizationOrigin[2] = 1e20; },
      "the quantization grid does not cover the bounding box" },
    { "input triangles", Seal::All, [](H& h, N&, R&) { h.InputTriangles += 1; },
      "input triangles, the leaves hold" },
    { "empty patch with a sphere", Seal::All, [](H&, N& n, R&) { n[3].Sphere[0] = 0.5f; },
      "node 3: an empty patch with a sphere that is not all zeros" },
    { "depth", Seal::All, [](H& h, N&, R&) { h.Depth = 3; },
      "header says depth 3, the deepest node is at level 2" },
    { "unknown flag", Seal::All, [](H& h, N&, R&) { h.Flags |= 4; }, "unknown flags 0x4" },
    { "header reserved", Seal::All, [](H& h, N&, R&) { h.Reserved[100] = 1; },
      "reserved header bytes are not zero" },
    { "node reserved", Seal::All, [](H&, N& n, R&) { n[7].Reserved[23] = 1; },
      "node 7: reserved bytes are not zero" },
  };
  for (const Rule& rule : rules)
  {
    SCOPED_TRACE(rule.Name);
    WriteAll(path, good);
    Rewrite(path, rule.Change, rule.Sealing);
    ExpectOpenError(path, rule.Expected);
  }
}

TEST(ModelFile, NodesOutOfLevelOrder)
{
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  // Root 3's children (level 1) come after node 6's (level 2); the tree itself is sound.
  Write(Synthetic({ 2, 6, 3 }), path);
  ExpectOpenError(path, "node 10: level 1 after level 2: nodes not in level order");
}

TEST(ModelFile, ASeventhRoot)
{
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  Model m = Synthetic({});
  m.Nodes.push_back(m.Nodes[1]);
  m.Patches.push_back(m.Patches[1]);
  m.Header.StoredTriangles += m.Nodes[1].TriangleCount;
  Write(m, path);
  ExpectOpenError(path, "node 6: a root after the first 6 nodes");
}

TEST(ModelFile, CorruptPatchesAreFoundOnCheckAndAllListedByVerify)
{
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  const std::vector<ModelNode> nodes = Write(Synthetic(), path);
  std::vector<std::uint8_t> bytes = ReadAll(path);
  ModelHeader h;
  std::memcpy(&h, bytes.data(), sizeof(h));
  for (std::size_t i : { 2, 8 })
  {
    bytes[h.PatchSectionOffset + nodes[i].PatchOffset + nodes[i].PatchBytes / 2] ^= 0x40;
  }
  WriteAll(path, bytes);

  const ModelFile file = ModelFile::Open(path);
  EXPECT_NO_THROW(file.CheckPatch(1));
  try
  {
    file.CheckPatch(8);
    ADD_FAILURE() << "a corrupt patch passed its check";
  }
  catch (const ModelError& e)
  {
    EXPECT_EQ(std::string(e.what()), path + ": node 8: patch checksum mismatch: the patch is corrupt");
  }
  EXPECT_THROW(file.CheckPatch(10), std::out_of_range);
  const std::vector<std::string> problems = file.Verify();
  ASSERT_EQ(problems.size(), 3u);
  EXPECT_EQ(problems[0], path + ": node 2: patch checksum mismatch");
  EXPECT_EQ(problems[1], path + ": node 8: patch checksum mismatch");
  EXPECT_EQ(problems[2], path + ": patch section checksum mismatch");
}

// Padding between patches, and after the last, must be zero: a changed byte there shows as a
// section checksum mismatch, and also when the section checksum was made to match.
TEST(ModelFile, PaddingBetweenPatchesIsVerified)
{
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  const std::vector<ModelNode> nodes = Write(Synthetic(), path);
  const std::vector<std::uint8_t> good = ReadAll(path);
  for (const std::size_t i : { std::size_t(0), nodes.size() - 1 })
  {
    SCOPED_TRACE("after node " + std::to_string(i));
    const ModelNode& n = nodes[i];
    ASSERT_NE(n.PatchBytes % 16, 0u) << "the test needs padding after the patch";
    const std::string padded = path + ": node " + std::to_string(i) + ": nonzero padding after its patch";
    for (const Seal seal : { Seal::HeaderOnly, Seal::All })
    {
      WriteAll(path, good);
      Rewrite(path,
        [&](ModelHeader& h, std::vector<ModelNode>&, std::vector<std::uint8_t>& raw) {
          raw[h.PatchSectionOffset + n.PatchOffset + n.PatchBytes] = 1;
          if (seal == Seal::All)
          {
            h.PatchSectionChecksum = Checksum(raw.data() + h.PatchSectionOffset, h.PatchSectionBytes);
          }
        },
        seal);
      const ModelFile file = ModelFile::Open(path);
      const std::vector<std::string> expected = seal == Seal::All
        ? std::vector<std::string>{ padded }
        : std::vector<std::string>{ padded, path + ": patch section checksum mismatch" };
      EXPECT_EQ(file.Verify(), expected);
    }
  }
}

// Every patch corrupt, and every padding: the first 100 problems are listed, then a count.
TEST(ModelFile, VerifyListsAHundredProblemsThenCounts)
{
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  std::vector<int> splits(100);
  std::iota(splits.begin(), splits.end(), 0);
  const std::vector<ModelNode> nodes = Write(Synthetic(splits), path);
  std::size_t paddings = 0;
  Rewrite(path,
    [&](ModelHeader& h, std::vector<ModelNode>& n, std::vector<std::uint8_t>& raw) {
      for (const ModelNode& node : n)
      {
        raw[h.PatchSectionOffset + node.PatchOffset] ^= 1;
        if (node.PatchBytes % 16 != 0)
        {
          raw[h.PatchSectionOffset + node.PatchOffset + node.PatchBytes] = 1;
          ++paddings;
        }
      }
    },
    Seal::All);
  const std::vector<std::string> problems = ModelFile::Open(path).Verify();
  ASSERT_EQ(problems.size(), 102u);
  EXPECT_EQ(problems[0], path + ": node 0: patch checksum mismatch");
  EXPECT_EQ(problems[100], path + ": " + std::to_string(nodes.size() + paddings - 100) +
    " more corrupt patches or paddings");
  EXPECT_EQ(problems[101], path + ": patch section checksum mismatch");
}

// A model's patches are of its version's format: the decoder reads both formats, but a patch of
// the other one in a model is refused, not decoded as it happens to be.
TEST(ModelFile, PatchesOfAnotherFormatThanTheModelsAreRefused)
{
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  const std::vector<std::uint8_t> format3 =
    ReadAll(std::string(ATP_TEST_DATA_DIR) + "/Format3/small-4-levels.atp");
  const auto decodeError = [&](std::size_t node) -> std::string {
    const ModelFile file = ModelFile::Open(path);
    PatchMesh mesh;
    try
    {
      file.DecodePatch(node, mesh);
    }
    catch (const ModelError& e)
    {
      return e.what();
    }
    return "";
  };
  WriteAll(path, format3);
  ASSERT_EQ(decodeError(0), "") << "the model as it is decodes";

  // Its header claims the current version: every patch is then of the wrong format.
  Rewrite(path, [](ModelHeader& h, std::vector<ModelNode>&, std::vector<std::uint8_t>&) { h.Version = 4; },
    Seal::All);
  EXPECT_EQ(decodeError(0), path + ": node 0: patch format 3 in a model of version 4, whose patches are format 4");

  // One patch claims the current format, checksums made to match.
  WriteAll(path, format3);
  Rewrite(path,
    [](ModelHeader& h, std::vector<ModelNode>& n, std::vector<std::uint8_t>& raw) {
      std::uint8_t* patch = raw.data() + h.PatchSectionOffset + n[0].PatchOffset;
      patch[0] = PatchFormatVersion;
      n[0].PatchChecksum = Checksum(patch, n[0].PatchBytes);
      h.PatchSectionChecksum = Checksum(raw.data() + h.PatchSectionOffset, h.PatchSectionBytes);
    },
    Seal::All);
  EXPECT_EQ(decodeError(0), path + ": node 0: patch format 4 in a model of version 3, whose patches are format 3");
}

TEST(ModelFile, RandomByteFlipsAreCaught)
{
  TempDirectory dir;
  const std::string good = dir / "good.atp";
  const std::string path = dir / "flipped.atp";
  const std::vector<ModelNode> nodes = Write(Synthetic(), good);
  const std::vector<std::uint8_t> bytes = ReadAll(good);
  ModelHeader h;
  std::memcpy(&h, bytes.data(), sizeof(h));

  std::mt19937_64 random(20040808);
  int refusedAtOpen = 0;
  int foundByVerify = 0;
  for (int trial = 0; trial < 400; ++trial)
  {
    std::vector<std::uint8_t> flipped = bytes;
    const std::size_t at = std::size_t(random() % flipped.size());
    flipped[at] ^= std::uint8_t(1 + random() % 255);
    WriteAll(path, flipped);
    SCOPED_TRACE("byte " + std::to_string(at));
    try
    {
      const ModelFile file = ModelFile::Open(path);
      // Patch bytes are not read at open; everything else is.
      ASSERT_GE(at, h.PatchSectionOffset);
      EXPECT_FALSE(file.Verify().empty());
      const std::uint64_t offset = at - h.PatchSectionOffset;
      for (std::size_t i = 0; i < file.NodeCount(); ++i)
      {
        const bool inside =
          offset >= nodes[i].PatchOffset && offset < nodes[i].PatchOffset + nodes[i].PatchBytes;
        if (inside)
        {
          EXPECT_THROW(file.CheckPatch(i), ModelError);
        }
        else
        {
          EXPECT_NO_THROW(file.CheckPatch(i));
        }
      }
      ++foundByVerify;
    }
    catch (const ModelError&)
    {
      ++refusedAtOpen;
    }
  }
  // Both kinds happened, so both paths were exercised.
  EXPECT_GT(refusedAtOpen, 20);
  EXPECT_GT(foundByVerify, 20);
}

TEST(ModelFile, TruncationIsReported)
{
  TempDirectory dir;
  const std::string good = dir / "good.atp";
  const std::string path = dir / "cut.atp";
  Write(Synthetic(), good);
  const std::vector<std::uint8_t> bytes = ReadAll(good);
  std::vector<std::size_t> lengths = { 0, 1, 7, 8, 415, 416, 447, 448, bytes.size() - 1 };
  std::mt19937 random(7);
  for (int i = 0; i < 200; ++i)
  {
    lengths.push_back(random() % bytes.size());
  }
  for (std::size_t length : lengths)
  {
    SCOPED_TRACE("length " + std::to_string(length));
    WriteAll(path, std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + std::ptrdiff_t(length)));
    ExpectOpenError(path, "truncated: " + std::to_string(length));
  }
}

// A viewer's model cut short by another program while mapped: reading a page past the new end
// raises SIGBUS, which must become an error on the read, not the end of the process.
TEST(ModelFile, ShrinkingWhileOpenIsAnErrorNotACrash)
{
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  const Model m = Synthetic();
  Write(m, path);
  const ModelFile file = ModelFile::Open(path);
  PatchMesh patch;
  std::vector<std::uint8_t> bytes;
  ASSERT_NO_THROW(file.ReadPatch(1, bytes));
  ASSERT_TRUE(file.Verify().empty());
  const std::vector<std::uint8_t> whole = ReadAll(path);

  fs::resize_file(path, 0);
  const std::string shrank = "the file shrank while open (truncated or rewritten by another program)";
  for (std::size_t i : { 1, 8 })
  {
    try
    {
      file.ReadPatch(i, bytes);
      ADD_FAILURE() << "node " << i << " read from a file cut to nothing";
    }
    catch (const ModelError& e)
    {
      EXPECT_EQ(std::string(e.what()), path + ": " + shrank);
    }
    EXPECT_THROW(file.DecodePatch(i, patch), ModelError);
  }
  EXPECT_EQ(file.Verify(), std::vector<std::string>{ path + ": " + shrank });
  // What was read at open stays usable.
  EXPECT_EQ(file.Header().NodeCount, m.Nodes.size());
  EXPECT_EQ(file.Node(8).TriangleCount, m.Nodes[8].TriangleCount);

  // Once the file is whole again, so are the reads.
  WriteAll(path, whole);
  EXPECT_NO_THROW(file.ReadPatch(8, bytes));
}

// The handler takes only faults inside its own copies: any other SIGBUS still ends the process
// (by the signal, or by AddressSanitizer's report of it).
TEST(ModelFileDeathTest, OtherBusErrorsAreNotSwallowed)
{
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  Write(Synthetic(), path);
  const ModelFile file = ModelFile::Open(path);
  std::vector<std::uint8_t> bytes;
  file.ReadPatch(1, bytes); // installs the handler
  fs::resize_file(path, 0);
  EXPECT_EXIT(
    {
      volatile std::uint8_t first = *file.PatchData(1);
      (void)first;
      std::exit(0);
    },
    [](int status) { return WIFSIGNALED(status) ? WTERMSIG(status) == SIGBUS : WEXITSTATUS(status) != 0; },
    "");
}

TEST(ModelFile, ForeignFilesAreNotModels)
{
  TempDirectory dir;
  const std::string small = dir / "small.ply";
  const std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                          "property float x\nproperty float y\nproperty float z\n"
                          "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  WriteAll(small, std::vector<std::uint8_t>(ply.begin(), ply.end()));
  ExpectOpenError(small, "not an ATP model");

  const std::string large = dir / "large.ply";
  std::vector<std::uint8_t> bytes(ply.begin(), ply.end());
  bytes.resize(100000, 0x3f);
  WriteAll(large, bytes);
  ExpectOpenError(large, "not an ATP model");

  ExpectOpenError(dir / "missing.atp", "cannot open: No such file or directory");
  const std::string directory = dir / "directory.atp";
  fs::create_directory(directory);
  ExpectOpenError(directory, "not a regular file");
}

TEST(ModelWriter, AbandonedWriterLeavesNothing)
{
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  const Model m = Synthetic();
  {
    ModelWriter writer(path, m.Nodes.size());
    EXPECT_TRUE(dir.Entries().empty()) << "the temporary file has a name while writing";
    EXPECT_FALSE(fs::exists(path));
    writer.Add(m.Nodes[0], m.Patches[0].data(), m.Patches[0].size());
  }
  EXPECT_TRUE(dir.Entries().empty());

  // Wrong counts are the caller's mistake; the destructor still cleans up.
  {
    ModelWriter writer(path, 3);
    writer.Add(m.Nodes[0], "ab", 2);
    writer.Add(m.Nodes[1], "cd", 2);
    EXPECT_THROW(writer.Commit(ModelHeader{}), std::logic_error) << "a node short";
  }
  EXPECT_TRUE(dir.Entries().empty());
  {
    ModelWriter writer(path, 2);
    writer.Add(m.Nodes[0], "ab", 2);
    writer.Add(m.Nodes[1], "cd", 2);
    EXPECT_THROW(writer.Add(m.Nodes[2], "ef", 2), std::logic_error);
  }
  EXPECT_TRUE(dir.Entries().empty());
}

// SIGKILL runs no destructor: only a temporary file without a name leaves nothing behind.
TEST(ModelWriter, AKilledWriterLeavesNothingAndTheOldFileUntouched)
{
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  const Model m = Synthetic();
  Write(m, path);
  const std::vector<std::uint8_t> before = ReadAll(path);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0)
  {
    ModelWriter writer(path, m.Nodes.size());
    for (std::size_t i = 0; i < m.Nodes.size(); ++i)
    {
      writer.Add(m.Nodes[i], m.Patches[i].data(), m.Patches[i].size());
    }
    ::raise(SIGKILL);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  EXPECT_EQ(dir.Entries(), std::vector<std::string>{ "model.atp" });
  EXPECT_EQ(ReadAll(path), before);
}

TEST(ModelWriter, CommitReplacesAnExistingFile)
{
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  WriteAll(path, { 'o', 'l', 'd' });
  Write(Synthetic(), path);
  EXPECT_EQ(dir.Entries(), std::vector<std::string>{ "model.atp" });
  EXPECT_EQ(OpenError(path), "");
  // The model gets a new file's usual mode, not mkstemp's private 0600.
  const mode_t mask = ::umask(022);
  ::umask(mask);
  EXPECT_EQ(fs::status(path).permissions(), fs::perms(0666 & ~mask));
}

TEST(ModelWriter, MissingDirectoryIsAnError)
{
  try
  {
    ModelWriter writer("/nonexistent-atp-directory/model.atp", 6);
    ADD_FAILURE() << "no error for a missing directory";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_EQ(std::string(e.what()),
      "cannot write /nonexistent-atp-directory/model.atp: No such file or directory");
  }
}

// Restores the file size limit however the test ends.
class FileSizeLimit
{
public:
  explicit FileSizeLimit(rlim_t bytes)
  {
    std::signal(SIGXFSZ, SIG_IGN);
    ::getrlimit(RLIMIT_FSIZE, &Saved);
    rlimit small = Saved;
    small.rlim_cur = bytes;
    Applied = ::setrlimit(RLIMIT_FSIZE, &small) == 0;
  }
  ~FileSizeLimit() { ::setrlimit(RLIMIT_FSIZE, &Saved); }
  bool Applied = false;

private:
  rlimit Saved{};
};

TEST(ModelWriter, AFailedWriteLeavesTheOldFileUntouched)
{
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  const std::vector<std::uint8_t> old(40000, 0x5a);
  WriteAll(path, old);
  Model m = Synthetic();
  for (auto& patch : m.Patches)
  {
    patch.resize(20000, 0x11); // 200 KB in all, over the limit below
  }
  std::string message;
  {
    // Commit or an earlier flush hits the limit: EFBIG, as a full disk gives ENOSPC.
    FileSizeLimit limit(64 << 10);
    ASSERT_TRUE(limit.Applied);
    try
    {
      Write(m, path);
    }
    catch (const std::runtime_error& e)
    {
      message = e.what();
    }
  }
  EXPECT_EQ(message, "cannot write " + path + ": File too large");
  EXPECT_EQ(dir.Entries(), std::vector<std::string>{ "model.atp" });
  EXPECT_EQ(ReadAll(path), old);
}

TEST(ModelWriter, LargePatchesBypassTheBuffer)
{
  TempDirectory dir;
  const std::string path = dir / "model.atp";
  Model m = Synthetic();
  std::mt19937 random(3);
  // Larger than the writer's 8 MiB buffer, between small ones.
  m.Patches[7].resize((9u << 20) + 5);
  for (auto& b : m.Patches[7])
  {
    b = std::uint8_t(random());
  }
  Write(m, path);
  const ModelFile file = ModelFile::Open(path);
  EXPECT_TRUE(file.Verify().empty());
  for (std::size_t i = 0; i < file.NodeCount(); ++i)
  {
    ASSERT_EQ(file.Node(i).PatchBytes, m.Patches[i].size());
    EXPECT_TRUE(SameBytes(file.PatchData(i), m.Patches[i]));
  }
}

} // namespace

// Models of format 3 (built before normals were predicted) still open and decode: every patch
// decodes to the counts its node records, inside the sphere and face-normal cone construction
// took from what the format-3 decoder gave back, and re-encoded in the current format it decodes to
// the same positions and normals bit for bit.
TEST(ModelFile, Format3ModelsStillRead)
{
  for (const char* name : { "small-4-levels.atp", "colors.atp" })
  {
    SCOPED_TRACE(name);
    const ModelFile model = ModelFile::Open(std::string(ATP_TEST_DATA_DIR) + "/Format3/" + name);
    ASSERT_EQ(model.Header().Version, 3u);
    EXPECT_TRUE(model.Verify().empty());
    const QuantizationGrid grid = model.PatchGrid();
    PatchMesh mesh, again;
    std::size_t decoded = 0, vertices = 0, alongSurface = 0;
    for (std::size_t i = 0; i < model.Header().NodeCount; ++i)
    {
      const ModelNode& node = model.Node(i);
      model.DecodePatch(i, mesh);
      ASSERT_EQ(mesh.TriangleCount(), node.TriangleCount);
      ASSERT_EQ(mesh.VertexCount(), node.VertexCount);
      if (mesh.TriangleCount() == 0)
      {
        continue;
      }
      ++decoded;
      for (std::size_t v = 0; v < mesh.VertexCount(); ++v)
      {
        const float* p = &mesh.Positions[3 * v];
        const double distance = std::sqrt(double(p[0] - node.Sphere[0]) * (p[0] - node.Sphere[0]) +
          double(p[1] - node.Sphere[1]) * (p[1] - node.Sphere[1]) +
          double(p[2] - node.Sphere[2]) * (p[2] - node.Sphere[2]));
        EXPECT_LE(distance, node.Sphere[3] * (1 + 1e-5) + 1e-6) << "node " << i << " vertex " << v;
      }
      std::vector<double> sums(mesh.Positions.size(), 0.0); // area-weighted, per vertex
      for (std::size_t t = 0; t < mesh.TriangleCount(); ++t) // the cone holds face normals
      {
        const float* a = &mesh.Positions[3 * mesh.Indices[3 * t]];
        const float* b = &mesh.Positions[3 * mesh.Indices[3 * t + 1]];
        const float* c = &mesh.Positions[3 * mesh.Indices[3 * t + 2]];
        const double u[3] = { double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2] };
        const double w[3] = { double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2] };
        const double n[3] = { u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0] };
        const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        const double along =
          (n[0] * node.ConeAxis[0] + n[1] * node.ConeAxis[1] + n[2] * node.ConeAxis[2]) / length;
        EXPECT_GE(along, double(node.ConeCos) - 1e-5) << "node " << i << " triangle " << t;
        for (int k = 0; k < 3; ++k)
        {
          for (int x = 0; x < 3; ++x)
          {
            sums[3 * mesh.Indices[3 * t + k] + x] += n[x];
          }
        }
      }
      // Vertex normals follow the surface the patch's triangles make (simplified patches carry
      // the finer surface's, so only roughly).
      for (std::size_t v = 0; v < mesh.VertexCount(); ++v)
      {
        const double* n = &sums[3 * v];
        const float* stored = &mesh.Normals[3 * v];
        const double along = (n[0] * stored[0] + n[1] * stored[1] + n[2] * stored[2]) /
          std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        ++vertices;
        alongSurface += along > 0.5;
      }
      // Interior shift as stored (header byte 26), so the current encoder rounds nothing more.
      PatchPrecision precision;
      precision.InteriorPositionShift = model.PatchData(i)[26];
      const std::vector<std::uint8_t> bytes = EncodePatch(mesh, grid, precision);
      ASSERT_EQ(bytes[0], PatchFormatVersion);
      atp::DecodePatch(bytes.data(), bytes.size(), grid, again);
      // The encoder orders vertices afresh; compare each triangle's corners.
      ASSERT_EQ(again.TriangleCount(), mesh.TriangleCount());
      std::vector<std::vector<float>> before, after;
      for (const auto* m : { &mesh, &again })
      {
        auto& corners = m == &mesh ? before : after;
        for (const std::uint32_t v : m->Indices)
        {
          std::vector<float> corner(m->Positions.begin() + 3 * v, m->Positions.begin() + 3 * v + 3);
          corner.insert(corner.end(), m->Normals.begin() + 3 * v, m->Normals.begin() + 3 * v + 3);
          corner.insert(corner.end(), m->Colors.begin() + (m->HasColors() ? 4 * v : 0),
            m->Colors.begin() + (m->HasColors() ? 4 * v + 4 : 0));
          corners.push_back(corner);
        }
      }
      std::sort(before.begin(), before.end());
      std::sort(after.begin(), after.end());
      EXPECT_EQ(before, after) << "node " << i;
    }
    EXPECT_GT(decoded, 0u);
    EXPECT_GE(alongSurface, vertices * 9 / 10);
    std::printf("%s: %zu of %zu vertex normals within 60 degrees of their faces\n", name,
      alongSurface, vertices);
  }
}
