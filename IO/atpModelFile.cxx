#include "atpModelFile.h"

#include "atpFileDescriptor.h"

#include "atpChecksum.h"
#include "atpMappedCopy.h"
#include "atpPatchCodec.h"
#include "atpResidentPages.h"

#include <xxhash.h>

#include <algorithm>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <fcntl.h>
#include <memory>
#include <new>
#include <sstream>
#include <stdexcept>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace atp
{
namespace
{
constexpr std::uint64_t SectionAlignment = 64;
constexpr std::uint64_t PatchAlignment = 16;
constexpr std::size_t RootCount = 6;
constexpr std::uint32_t MaxTrianglesPerPatch = 1u << 24;
constexpr std::size_t MaxListedPatches = 100;
constexpr char ShrankWhileOpen[] =
  "the file shrank while open (truncated or rewritten by another program)";

std::uint64_t AlignUp(std::uint64_t value, std::uint64_t alignment)
{
  return (value + alignment - 1) / alignment * alignment;
}

// TetId arithmetic (Filters/atpTetra.h; IO cannot depend on Filters): a leading 1 bit, 3 bits of
// root index, one bit per bisection.
int TetLevel(std::uint64_t bits)
{
  return 60 - __builtin_clzll(bits);
}

bool TetValid(std::uint64_t bits)
{
  if (bits < 8)
  {
    return false;
  }
  const std::uint64_t root = bits >> TetLevel(bits);
  return root >= 8 && root < 8 + RootCount;
}

template <typename... Parts>
std::string Cat(const Parts&... parts)
{
  std::ostringstream s;
  (s << ... << parts);
  return s.str();
}

std::string Hex(std::uint64_t value)
{
  std::ostringstream s;
  s << "0x" << std::hex << value;
  return s.str();
}

bool AllFinite(const float* values, std::size_t count)
{
  return std::all_of(values, values + count, [](float v) { return std::isfinite(v); });
}

bool AllFinite(const double* values, std::size_t count)
{
  return std::all_of(values, values + count, [](double v) { return std::isfinite(v); });
}

/// Reserved bytes: zero in every version that reads them, so a later one may give them meaning.
template <std::size_t Size>
bool AllZero(const std::uint8_t (&bytes)[Size])
{
  return std::all_of(bytes, bytes + Size, [](std::uint8_t b) { return b == 0; });
}

} // namespace

ModelFile ModelFile::Open(const std::string& path)
{
  ModelFile file;
  file.FilePath = path;
  // Non-blocking: opening a FIFO would wait for a writer before the check below refuses it.
  const FileDescriptor fd{ ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK) };
  struct stat info;
  if (fd.Fd < 0 || ::fstat(fd.Fd, &info) != 0)
  {
    file.Throw(Cat("cannot open: ", std::strerror(errno)));
  }
  if (!S_ISREG(info.st_mode))
  {
    file.Throw("not a regular file");
  }
  const std::uint64_t size = std::uint64_t(info.st_size);
  if (size < sizeof(ModelHeader))
  {
    // Too short to hold a header: tell a cut-off model from some other small file.
    char head[sizeof(ModelMagic)] = {};
    const std::size_t want = std::size_t(std::min<std::uint64_t>(size, sizeof(head)));
    ssize_t got;
    do
    {
      got = ::pread(fd.Fd, head, want, 0);
    } while (got < 0 && errno == EINTR);
    if (got != ssize_t(want) || std::memcmp(head, ModelMagic, want) != 0)
    {
      file.Throw("not an ATP model");
    }
    file.Throw(Cat("truncated: ", size, " bytes, smaller than the ", sizeof(ModelHeader),
      "-byte header"));
  }
  file.MapBytes = std::size_t(size);
  file.ReadHead(fd.Fd);
  file.ValidateNodes();
  void* map = ::mmap(nullptr, std::size_t(size), PROT_READ, MAP_SHARED, fd.Fd, 0);
  if (map == MAP_FAILED)
  {
    file.Throw(Cat("cannot map: ", std::strerror(errno)));
  }
  file.Map = static_cast<const std::uint8_t*>(map);
  file.PatchSection = file.Map + file.Header().PatchSectionOffset;

  // Patches are read where the view goes, not in file order: no read-ahead.
  const std::uint64_t page = std::uint64_t(::sysconf(_SC_PAGESIZE));
  const std::uint64_t randomFrom = AlignUp(file.Header().PatchSectionOffset, page);
  if (randomFrom < size)
  {
    ::madvise(const_cast<std::uint8_t*>(file.Map) + randomFrom, std::size_t(size - randomFrom),
      MADV_RANDOM);
  }
  return file;
}

ModelFile::ModelFile(ModelFile&& other) noexcept
{
  *this = std::move(other);
}

ModelFile& ModelFile::operator=(ModelFile&& other) noexcept
{
  if (this != &other)
  {
    Release();
    FilePath = std::move(other.FilePath);
    Head = std::move(other.Head);
    Map = other.Map;
    MapBytes = other.MapBytes;
    NodeArray = other.NodeArray;
    Count = other.Count;
    PatchSection = other.PatchSection;
    other.Map = nullptr;
    other.MapBytes = 0;
    other.NodeArray = nullptr;
    other.Count = 0;
    other.PatchSection = nullptr;
  }
  return *this;
}

ModelFile::~ModelFile()
{
  Release();
}

void ModelFile::Release()
{
  if (Map)
  {
    ::munmap(const_cast<std::uint8_t*>(Map), MapBytes);
    Map = nullptr;
  }
}

void ModelFile::Throw(const std::string& problem) const
{
  throw ModelError(FilePath + ": " + problem);
}

void ModelFile::ReadHead(int fd)
{
  auto readAt = [&](std::uint64_t offset, std::uint64_t bytes) {
    std::uint8_t* to = Head.data() + offset;
    while (bytes > 0)
    {
      const ssize_t got = ::pread(fd, to, std::size_t(bytes), off_t(offset));
      if (got < 0 && errno == EINTR)
      {
        continue;
      }
      if (got < 0)
      {
        Throw(Cat("cannot read: ", std::strerror(errno)));
      }
      if (got == 0)
      {
        Throw("truncated while being read");
      }
      to += got;
      offset += std::uint64_t(got);
      bytes -= std::uint64_t(got);
    }
  };
  Head.resize(sizeof(ModelHeader));
  readAt(0, sizeof(ModelHeader));
  ValidateHeader();
  // The header's layout is checked against the file's size: this allocates no more than the file.
  const std::uint64_t patchOffset = Header().PatchSectionOffset;
  Head.resize(std::size_t(patchOffset));
  readAt(sizeof(ModelHeader), patchOffset - sizeof(ModelHeader));
}

void ModelFile::ValidateHeader()
{
  const ModelHeader& h = Header();
  if (std::memcmp(h.Magic, ModelMagic, sizeof(ModelMagic)) != 0)
  {
    Throw("not an ATP model");
  }
  // The byte order first: with the other one, every field after the magic reads wrong.
  if (h.ByteOrder != ModelByteOrderMark)
  {
    if (h.ByteOrder == __builtin_bswap32(ModelByteOrderMark))
    {
      Throw("written on a machine of the other byte order");
    }
    Throw(Cat("bad byte-order mark ", Hex(h.ByteOrder)));
  }
  if (h.Version > ModelVersion)
  {
    Throw(Cat("made by a newer version ", h.Version, " of the format (this reader reads version ",
      ModelVersion, ")"));
  }
  if (h.Version >= 1 && h.Version < OldestReadableModelVersion)
  {
    // Versions 1 and 2 had another patch header (16-bit normals; no position prediction).
    Throw(Cat("made by the older version ", h.Version, " of the format (this reader reads versions ",
      OldestReadableModelVersion, " to ", ModelVersion, "): build it again"));
  }
  if (h.Version < OldestReadableModelVersion)
  {
    Throw(Cat("unknown format version ", h.Version));
  }
  if (h.HeaderBytes != sizeof(ModelHeader))
  {
    Throw(Cat("header record of ", h.HeaderBytes, " bytes, expected ", sizeof(ModelHeader)));
  }
  if (h.NodeBytes != sizeof(ModelNode))
  {
    Throw(Cat("node record of ", h.NodeBytes, " bytes, expected ", sizeof(ModelNode)));
  }
  if (Checksum(&h, offsetof(ModelHeader, HeaderChecksum)) != h.HeaderChecksum)
  {
    Throw("header checksum mismatch: the header is corrupt");
  }
  if (MapBytes < h.FileBytes)
  {
    Throw(Cat("truncated: ", MapBytes, " of ", h.FileBytes, " bytes"));
  }
  if (MapBytes > h.FileBytes)
  {
    Throw(Cat(MapBytes, " bytes, but the header says ", h.FileBytes, ": trailing data"));
  }

  // The one layout of version 3: header, nodes, patches, each 64-byte aligned, nothing after.
  // The node count is bounded by the file size before anything is sized from it.
  const std::uint64_t nodeOffset = AlignUp(sizeof(ModelHeader), SectionAlignment);
  const std::uint64_t room = h.FileBytes > nodeOffset ? h.FileBytes - nodeOffset : 0;
  if (h.NodeCount < RootCount)
  {
    Throw(Cat(h.NodeCount, " nodes, fewer than the ", RootCount, " roots"));
  }
  if (h.NodeCount > room / sizeof(ModelNode) || h.NodeCount > std::uint64_t(INT32_MAX))
  {
    Throw(Cat(h.NodeCount, " nodes cannot fit in a file of ", h.FileBytes, " bytes"));
  }
  const std::uint64_t nodeBytes = h.NodeCount * sizeof(ModelNode);
  const std::uint64_t patchOffset = AlignUp(nodeOffset + nodeBytes, SectionAlignment);
  if (h.NodeSectionOffset != nodeOffset)
  {
    Throw(Cat("node section at offset ", h.NodeSectionOffset, ", expected ", nodeOffset));
  }
  if (h.NodeSectionBytes != nodeBytes)
  {
    Throw(Cat("node section of ", h.NodeSectionBytes, " bytes, expected ", nodeBytes, " for ",
      h.NodeCount, " nodes"));
  }
  if (h.PatchSectionOffset != patchOffset)
  {
    Throw(Cat("patch section at offset ", h.PatchSectionOffset, ", expected ", patchOffset));
  }
  if (patchOffset > h.FileBytes || h.PatchSectionBytes != h.FileBytes - patchOffset)
  {
    Throw(Cat("patch section of ", h.PatchSectionBytes, " bytes at offset ", patchOffset,
      " does not end the file at ", h.FileBytes));
  }
  if (!AllFinite(h.BoxMin, 3) || !AllFinite(h.BoxMax, 3) || h.BoxMin[0] > h.BoxMax[0] ||
    h.BoxMin[1] > h.BoxMax[1] || h.BoxMin[2] > h.BoxMax[2])
  {
    Throw("bounding box is not finite or is inverted");
  }
  if (!AllFinite(h.LatticeOrigin, 3) || !std::isfinite(h.LatticeScale) || !(h.LatticeScale > 0))
  {
    Throw("lattice origin or scale is not finite and positive");
  }
  if (!AllFinite(h.QuantizationOrigin, 3) || !std::isfinite(h.QuantizationStep) ||
    !(h.QuantizationStep > 0))
  {
    Throw("quantization origin or step is not finite and positive");
  }
  // Patches decode to floats: every point of the grid must be one.
  for (int a = 0; a < 3; ++a)
  {
    const double last = h.QuantizationOrigin[a] + double(QuantizationGrid::MaxInteger) * h.QuantizationStep;
    if (!(std::abs(h.QuantizationOrigin[a]) <= FLT_MAX) || !(std::abs(last) <= FLT_MAX))
    {
      Throw("the quantization grid reaches beyond the range of floats");
    }
    // The builder's grid holds the box, its points' floats rounded to the step at most.
    if (h.QuantizationOrigin[a] > h.BoxMin[a] + h.QuantizationStep || last < h.BoxMax[a] - h.QuantizationStep)
    {
      Throw("the quantization grid does not cover the bounding box");
    }
  }
  if (!std::isfinite(h.ErrorScale) || !(h.ErrorScale >= 0))
  {
    Throw("error scale is not finite and non-negative");
  }
  if (h.Flags & ~(ModelFlagColors | ModelFlagFastCacheOrder))
  {
    Throw("unknown flags " + Hex(h.Flags & ~(ModelFlagColors | ModelFlagFastCacheOrder)));
  }
  if (!AllZero(h.Reserved))
  {
    Throw("reserved header bytes are not zero");
  }
}

void ModelFile::ValidateNodes()
{
  const ModelHeader& h = Header();
  const std::uint64_t nodeOffset = h.NodeSectionOffset;
  const std::uint64_t nodeBytes = h.NodeSectionBytes;
  // No checksum covers the padding between sections, so it must be zero.
  const std::uint64_t gaps[2][2] = { { sizeof(ModelHeader), nodeOffset },
    { nodeOffset + nodeBytes, h.PatchSectionOffset } };
  for (const auto& gap : gaps)
  {
    const auto end = Head.begin() + std::ptrdiff_t(gap[1]);
    const auto nonzero =
      std::find_if(Head.begin() + std::ptrdiff_t(gap[0]), end, [](std::uint8_t b) { return b != 0; });
    if (nonzero != end)
    {
      Throw(Cat("nonzero padding at byte ", nonzero - Head.begin()));
    }
  }
  if (Checksum(Head.data() + nodeOffset, std::size_t(nodeBytes)) != h.NodeSectionChecksum)
  {
    Throw("node section checksum mismatch: the nodes are corrupt");
  }

  NodeArray = reinterpret_cast<const ModelNode*>(Head.data() + nodeOffset);
  Count = std::size_t(h.NodeCount);

  // The forest: 6 distinct roots first, then every node reached from an earlier parent that
  // names it in the slot its last TetId bit selects, and that it names back. So each node has
  // exactly one path from a root, ids are unique and there are no cycles.
  unsigned rootsSeen = 0;
  int previousLevel = 0;
  std::uint64_t triangles = 0;
  std::uint64_t leafTriangles = 0; // the full-resolution mesh, all of it
  std::uint64_t patchEnd = 0;      // where the next patch must start
  for (std::size_t i = 0; i < Count; ++i)
  {
    const ModelNode& n = NodeArray[i];
    auto bad = [&](const std::string& problem) { Throw(Cat("node ", i, ": ", problem)); };
    if (!TetValid(n.Tet))
    {
      bad(Cat("invalid tetrahedron id ", Hex(n.Tet)));
    }
    const int level = TetLevel(n.Tet);
    if (i < RootCount)
    {
      if (level != 0)
      {
        bad(Cat("one of the ", RootCount, " roots expected, found a level-", level,
          " tetrahedron"));
      }
      if (n.Parent != -1)
      {
        bad(Cat("a root with parent ", n.Parent));
      }
      const unsigned bit = 1u << (n.Tet & 7u);
      if (rootsSeen & bit)
      {
        bad(Cat("root ", n.Tet & 7u, " listed twice"));
      }
      rootsSeen |= bit;
    }
    else
    {
      if (level == 0)
      {
        bad(Cat("a root after the first ", RootCount, " nodes"));
      }
      if (level < previousLevel)
      {
        bad(Cat("level ", level, " after level ", previousLevel, ": nodes not in level order"));
      }
      if (n.Parent < 0 || std::size_t(n.Parent) >= i)
      {
        bad(Cat("parent ", n.Parent, " is not an earlier node"));
      }
      const ModelNode& parent = NodeArray[n.Parent];
      if (parent.Tet != n.Tet >> 1)
      {
        bad(Cat("parent ", n.Parent, " is not its parent tetrahedron"));
      }
      if (parent.Children[n.Tet & 1u] != std::int32_t(i))
      {
        bad(Cat("parent ", n.Parent, " does not list it as its child"));
      }
      if (n.SaturatedError > parent.SaturatedError)
      {
        bad(Cat("saturated error ", n.SaturatedError, " above its parent's ",
          parent.SaturatedError));
      }
    }
    previousLevel = level;

    if ((n.Children[0] == -1) != (n.Children[1] == -1))
    {
      bad("one child: a node has both children or none");
    }
    if (n.Children[0] != -1)
    {
      if (level == 60)
      {
        bad("children below the deepest level 60");
      }
      for (int which = 0; which < 2; ++which)
      {
        const std::int32_t c = n.Children[which];
        if (c <= std::int32_t(i) || std::size_t(c) >= Count)
        {
          bad(Cat("child ", c, " is not a later node"));
        }
        if (NodeArray[c].Tet != ((n.Tet << 1) | std::uint64_t(which)))
        {
          bad(Cat("child ", c, " is not its child tetrahedron ", which));
        }
        if (NodeArray[c].Parent != std::int32_t(i))
        {
          bad(Cat("child ", c, " names node ", NodeArray[c].Parent, " as its parent"));
        }
      }
    }

    if (n.PatchOffset > h.PatchSectionBytes || n.PatchBytes > h.PatchSectionBytes - n.PatchOffset)
    {
      bad(Cat("patch of ", n.PatchBytes, " bytes at offset ", n.PatchOffset,
        " outside the patch section of ", h.PatchSectionBytes, " bytes"));
    }
    // One layout only: so no patch is shared, skipped or overlapped, and every byte between
    // patches is alignment padding (which Verify checks is zero).
    if (n.PatchOffset != patchEnd)
    {
      bad(Cat("patch at offset ", n.PatchOffset, ", expected ", patchEnd,
        ": patches follow one another in node order, each ", PatchAlignment, "-byte aligned"));
    }
    if (n.PatchBytes < PatchHeaderBytes)
    {
      bad(Cat("patch of ", n.PatchBytes, " bytes, shorter than the ", PatchHeaderBytes,
        "-byte patch header"));
    }
    patchEnd = AlignUp(n.PatchOffset + n.PatchBytes, PatchAlignment);
    if (n.TriangleCount > MaxTrianglesPerPatch)
    {
      bad(Cat(n.TriangleCount, " triangles, more than ", MaxTrianglesPerPatch));
    }
    if (std::uint64_t(n.VertexCount) > 3 * std::uint64_t(n.TriangleCount))
    {
      bad(Cat(n.VertexCount, " vertices for ", n.TriangleCount, " triangles"));
    }
    triangles += n.TriangleCount;
    leafTriangles += n.Children[0] == -1 ? n.TriangleCount : 0;

    if (!AllFinite(n.Sphere, 4) || !AllFinite(n.ConeAxis, 3) || !std::isfinite(n.ConeCos) ||
      !std::isfinite(n.Error) || !std::isfinite(n.SaturatedError) ||
      !AllFinite(n.SaturatedSphere, 4))
    {
      bad("bounds or errors not finite");
    }
    if (n.Sphere[3] < 0 || n.SaturatedSphere[3] < 0)
    {
      bad("negative sphere radius");
    }
    if (n.TriangleCount == 0 && std::any_of(n.Sphere, n.Sphere + 4, [](float x) { return x != 0; }))
    {
      bad("an empty patch with a sphere that is not all zeros");
    }
    if (n.ConeCos < -1 || n.ConeCos > 1)
    {
      bad(Cat("normal cone cosine ", n.ConeCos, " outside [-1, 1]"));
    }
    if (n.Error < 0)
    {
      bad(Cat("negative error ", n.Error));
    }
    if (n.SaturatedError < n.Error)
    {
      bad(Cat("saturated error ", n.SaturatedError, " below its own error ", n.Error));
    }
    if (!AllZero(n.Reserved))
    {
      bad("reserved bytes are not zero");
    }
  }
  if (patchEnd != h.PatchSectionBytes)
  {
    Throw(Cat("the patches end at byte ", patchEnd, " of a patch section of ", h.PatchSectionBytes,
      " bytes"));
  }
  if (triangles != h.StoredTriangles)
  {
    Throw(Cat("header says ", h.StoredTriangles, " stored triangles, the nodes hold ", triangles));
  }
  if (leafTriangles != h.InputTriangles)
  {
    Throw(Cat("header says ", h.InputTriangles, " input triangles, the leaves hold ", leafTriangles));
  }
  if (h.Depth != std::uint32_t(previousLevel))
  {
    Throw(Cat("header says depth ", h.Depth, ", the deepest node is at level ", previousLevel));
  }
}

bool ModelFile::CopyPatchSection(
  std::uint64_t from, std::uint64_t to, std::vector<std::uint8_t>& bytes) const
{
  bytes.resize(std::size_t(to - from));
  return CopyFromMapping(bytes.data(), PatchSection + from, bytes.size());
}

void ModelFile::ReadPatch(std::size_t i, std::vector<std::uint8_t>& bytes) const
{
  if (i >= Count)
  {
    throw std::out_of_range(Cat(FilePath, ": no node ", i, " (", Count, " nodes)"));
  }
  const ModelNode& n = NodeArray[i];
  if (!CopyPatchSection(n.PatchOffset, n.PatchOffset + n.PatchBytes, bytes))
  {
    Throw(ShrankWhileOpen);
  }
  if (Checksum(bytes.data(), bytes.size()) != n.PatchChecksum)
  {
    Throw(Cat("node ", i, ": patch checksum mismatch: the patch is corrupt"));
  }
}

void ModelFile::CheckPatch(std::size_t i) const
{
  std::vector<std::uint8_t> bytes;
  ReadPatch(i, bytes);
}

QuantizationGrid ModelFile::PatchGrid() const
{
  const ModelHeader& h = Header();
  QuantizationGrid grid;
  for (int a = 0; a < 3; ++a)
  {
    grid.Origin[a] = h.QuantizationOrigin[a];
  }
  grid.Step = h.QuantizationStep;
  return grid;
}

void ModelFile::DecodePatch(std::size_t i, PatchMesh& out) const
{
  // Decoding threads keep their buffer: no allocation per patch.
  thread_local std::vector<std::uint8_t> bytes;
  ReadPatch(i, bytes);
  // The decoder reads either patch format; a model holds the one of its version only.
  static_assert(OldestReadableModelVersion == 3 && ModelVersion == 4 && OldestPatchFormatVersion == 3 &&
      PatchFormatVersion == 4,
    "a new model or patch format version needs its place here");
  const std::uint8_t format =
    Header().Version == OldestReadableModelVersion ? OldestPatchFormatVersion : PatchFormatVersion;
  if (bytes[0] != format)
  {
    Throw(Cat("node ", i, ": patch format ", int(bytes[0]), " in a model of version ",
      Header().Version, ", whose patches are format ", int(format)));
  }
  atp::DecodePatch(bytes.data(), bytes.size(), PatchGrid(), out);
}

void ModelFile::ReleasePatchPages(std::size_t i) const
{
  ReleaseResidentPages(PatchData(i), NodeArray[i].PatchBytes);
}

std::vector<std::string> ModelFile::Verify() const
{
  const ModelHeader& h = Header();
  const std::uint64_t page = std::uint64_t(::sysconf(_SC_PAGESIZE));
  const std::uint64_t adviseFrom = AlignUp(h.PatchSectionOffset, page);
  std::uint8_t* advised = const_cast<std::uint8_t*>(Map) + adviseFrom;
  const std::size_t advisedBytes = adviseFrom < MapBytes ? MapBytes - adviseFrom : 0;
  if (advisedBytes > 0)
  {
    ::madvise(advised, advisedBytes, MADV_SEQUENTIAL);
  }

  // One pass over the section: each step copies from where the section hash stands (the end of
  // the patch before, as Open checked the layout) to the end of the patch, hashes it, and checks
  // the padding before the patch and the patch in the copy.
  std::vector<std::string> problems;
  const std::unique_ptr<XXH3_state_t, XXH_errorcode (*)(XXH3_state_t*)> hash(
    XXH3_createState(), XXH3_freeState);
  XXH3_state_t* state = hash.get();
  if (!state)
  {
    throw std::bad_alloc();
  }
  XXH3_64bits_reset(state);
  std::uint64_t hashed = 0;
  std::vector<std::uint8_t> bytes;
  bool shrank = false;
  // A damaged file can have a problem at every node: the first MaxListedPatches are listed.
  std::size_t unlisted = 0;
  const auto report = [&](std::string problem) {
    if (problems.size() < MaxListedPatches)
    {
      problems.push_back(std::move(problem));
    }
    else
    {
      ++unlisted;
    }
  };
  // The checksum covers the padding too, but a file whose checksums were made to match would
  // pass with bytes that no patch holds.
  const auto checkPadding = [&](std::size_t paddingBytes, std::size_t after) {
    if (std::any_of(bytes.begin(), bytes.begin() + std::ptrdiff_t(paddingBytes),
          [](std::uint8_t b) { return b != 0; }))
    {
      report(Cat(FilePath, ": node ", after, ": nonzero padding after its patch"));
    }
  };
  for (std::size_t i = 0; i < Count; ++i)
  {
    const ModelNode& n = NodeArray[i];
    const std::uint64_t end = n.PatchOffset + n.PatchBytes;
    if (!CopyPatchSection(hashed, end, bytes))
    {
      shrank = true;
      break;
    }
    const std::size_t padding = std::size_t(n.PatchOffset - hashed);
    XXH3_64bits_update(state, bytes.data(), bytes.size());
    hashed = end;
    if (i > 0)
    {
      checkPadding(padding, i - 1);
    }
    if (Checksum(bytes.data() + padding, n.PatchBytes) != n.PatchChecksum)
    {
      report(Cat(FilePath, ": node ", i, ": patch checksum mismatch"));
    }
  }
  const bool complete = !shrank && CopyPatchSection(hashed, h.PatchSectionBytes, bytes);
  if (complete)
  {
    checkPadding(bytes.size(), Count - 1);
    XXH3_64bits_update(state, bytes.data(), bytes.size());
  }
  if (unlisted > 0)
  {
    problems.push_back(Cat(FilePath, ": ", unlisted, " more corrupt patches or paddings"));
  }
  if (!complete)
  {
    problems.push_back(Cat(FilePath, ": ", ShrankWhileOpen));
  }
  else if (XXH3_64bits_digest(state) != h.PatchSectionChecksum)
  {
    problems.push_back(Cat(FilePath, ": patch section checksum mismatch"));
  }

  if (advisedBytes > 0)
  {
    ::madvise(advised, advisedBytes, MADV_RANDOM);
  }
  return problems;
}

} // namespace atp
