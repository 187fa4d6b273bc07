// The on-disk layout of a .atp model (see docs/atp-format.md). Fixed-size little-endian records,
// so a memory map of the file can be read in place.
#ifndef atpModelFormat_h
#define atpModelFormat_h

#include <cstdint>

namespace atp
{

constexpr char ModelMagic[8] = { 'A', 'T', 'P', 'M', 'O', 'D', 'E', 'L' };
constexpr std::uint32_t ModelVersion = 4;
/// The oldest version a reader still reads: version 3 differs only in its patches' encoding,
/// which DecodePatch reads too.
constexpr std::uint32_t OldestReadableModelVersion = 3;
/// Written as a native uint32: reads back as this value only on a machine of the same byte order.
constexpr std::uint32_t ModelByteOrderMark = 0x01020304u;
constexpr std::uint32_t ModelFlagColors = 1u; ///< patches carry per-vertex RGBA colors
/// Patches were ordered for the vertex cache by meshoptimizer's FIFO optimizer (CacheOrder::Fast),
/// which builds faster; a reader needs nothing from it.
constexpr std::uint32_t ModelFlagFastCacheOrder = 2u;

/// At offset 0. Sections follow at the offsets it gives, each aligned to 64 bytes.
struct ModelHeader
{
  char Magic[8];
  std::uint32_t Version;
  std::uint32_t ByteOrder;
  std::uint32_t HeaderBytes; ///< sizeof(ModelHeader)
  std::uint32_t NodeBytes;   ///< sizeof(ModelNode)
  std::uint64_t FileBytes;   ///< the whole file: a shorter file is truncated
  std::uint64_t NodeCount;
  std::uint64_t NodeSectionOffset;
  std::uint64_t NodeSectionBytes;
  std::uint64_t PatchSectionOffset;
  std::uint64_t PatchSectionBytes;
  std::uint64_t NodeSectionChecksum;  ///< Checksum() of the node section
  std::uint64_t PatchSectionChecksum; ///< Checksum() of the patch section (checked by verify)

  double BoxMin[3]; ///< input bounds
  double BoxMax[3];
  double LatticeOrigin[3]; ///< the tetrahedra: world = origin + lattice / scale
  double LatticeScale;
  double QuantizationOrigin[3]; ///< patch positions: world = origin + integer * step
  double QuantizationStep;

  std::uint64_t InputTriangles;
  std::uint64_t InputBoundaryEdges;
  std::uint64_t StoredTriangles; ///< over all patches of all levels
  std::uint32_t LeafCapacity;    ///< options the model was built with
  std::uint32_t PatchBudget;
  std::uint32_t Depth;           ///< deepest level
  std::uint32_t Flags;           ///< ModelFlag* bits
  /// Screen-space error = ErrorScale * object-space error projected (calibrated at build).
  float ErrorScale;
  std::uint8_t Reserved[164];
  std::uint64_t HeaderChecksum; ///< Checksum() of every byte of the header before this field
};
static_assert(sizeof(ModelHeader) == 416, "ModelHeader is an on-disk record");

/// One tetrahedron of the forest. Nodes are sorted by level, then by the Morton code of the
/// tetrahedron's centroid; the 6 roots come first, children always after their parent.
struct ModelNode
{
  std::uint64_t Tet;          ///< TetId bits: root and bisection path
  std::uint64_t PatchOffset;  ///< from the start of the patch section
  std::uint64_t PatchChecksum;
  std::uint32_t PatchBytes;
  std::uint32_t TriangleCount;
  std::uint32_t VertexCount;
  std::int32_t Parent;        ///< node index, -1 for a root
  std::int32_t Children[2];   ///< node indices, -1 for a leaf
  float Sphere[4];            ///< tight bounding sphere of the patch: center, radius
  float ConeAxis[3];          ///< normal cone of the patch
  float ConeCos;              ///< cosine of its half angle; -1: normals in every direction
  float Error;                ///< object-space error of this patch against the input
  float SaturatedError;       ///< equal over the node's diamond, never larger than the parent's
  float SaturatedSphere[4];   ///< encloses the diamond's spheres and all descendants'
  std::uint8_t Reserved[24];
};
static_assert(sizeof(ModelNode) == 128, "ModelNode is an on-disk record");

} // namespace atp

#endif
