// The compact encoding of one patch in the .atp patch repository.
//
// Layout (little-endian): a PatchHeaderBytes header, then four streams back to back:
//   u8  format version (PatchFormatVersion)   u8 flags (PatchFlag*)
//   u32 vertex count   u32 triangle count
//   u32 patch minimum grid point x, y, z (where position prediction starts)
//   u32 border vertex count B (vertices 0..B-1 are on the patch border)
//   u8  interior shift S (vertices B.. lie on multiples of 2^S grid steps)
//   u32 byte sizes of the index, position, normal and color streams
// - indices: meshopt_encodeIndexBuffer of the vertex-cache-ordered triangle list;
// - positions: meshopt_encodeVertexBuffer of 3 x u32 per vertex: the zigzag-coded residual of
//   the vertex's QuantizationGrid integers from their parallelogram prediction (PredictionWalk
//   in atpPatchCodec.cxx), in units of 2^S steps for interior vertices, stored as running sums
//   per byte lane (SumByteLanes: the codec's own byte deltas then see the residuals);
// - normals: meshopt_encodeVertexBuffer of 2 x u16 per vertex, the zigzag-coded residuals of
//   octahedral coordinates of NormalBits bits (EncodeNormal of atpNormalEncoding.h, divided by
//   2^(16 - NormalBits) and rounded; at most 0.12 degrees off any unit normal, half a grey level
//   of diffuse shading at most; the same normal stores the same bits in every patch, so shared
//   vertices shade alike) from their prediction by the decoded geometry (PredictNormals of
//   atpNormalPrediction.h), stored as running sums per byte lane too;
// - colors: meshopt_encodeVertexBuffer of RGBA8, only with PatchFlagColors.
// An empty patch is the header alone.
#ifndef atpPatchCodec_h
#define atpPatchCodec_h

#include "atpPatchMesh.h"
#include "atpQuantizationGrid.h"
#include "vtkATPIOModule.h" // export macro

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace atp
{

constexpr std::uint8_t PatchFormatVersion = 4;
/// DecodePatch also reads version 3: normals stored as they are (2 x i16), no byte lanes.
constexpr std::uint8_t OldestPatchFormatVersion = 3;
/// Bits per octahedral normal coordinate in the normal stream. 16 bits cost 0.7 bytes more
/// per triangle (after compression) than 11 for no difference a display can show.
constexpr int NormalBits = 11;
constexpr std::uint8_t PatchFlagColors = 1u; ///< a color stream follows the normals
constexpr std::size_t PatchHeaderBytes = 43;
/// Hard caps a decoder checks before allocating (patches hold a few thousand triangles).
constexpr std::uint32_t MaxPatchVertices = 1u << 24;
constexpr std::uint32_t MaxPatchTriangles = 1u << 24;

/// A patch's bytes are not a valid encoding; the message says what is wrong.
class VTKATPIO_EXPORT PatchFormatError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// How much precision a patch's interior may give up. Vertices on the patch's border (on an edge
/// used by one of its triangles) are the only ones other patches share, so they always keep the
/// full grid: coarser interior vertices never open a crack. Coarse levels, whose simplification
/// error dwarfs the grid step, store their interior on a coarser grid and compress better.
struct PatchPrecision
{
  /// Interior positions are rounded to multiples of 2^InteriorPositionShift grid steps.
  int InteriorPositionShift = 0;

  /// The largest distance an interior vertex moves, for `grid` (object units).
  double PositionError(const QuantizationGrid& grid) const;
};

/// How EncodePatch orders a patch's triangles for the GPU's vertex cache (both with
/// meshoptimizer); DecodePatch reads either.
enum class CacheOrder : std::uint8_t
{
  /// meshopt_optimizeVertexCache: the smallest index stream and the fastest decoding. Its time
  /// per triangle grows with the valence of the vertices in its cache (about 1 ns per
  /// neighbor), so a patch with a vertex of more than MaxBestOrderValence triangles (a
  /// triangle repeated thousands of times, which no partition can split) is ordered Fast.
  Best,
  /// meshopt_optimizeVertexCacheFifo (a cache of 16): encodes about 1.7 times as fast, for about
  /// 6% more bytes and 8% more decoding time; about as few cache misses (docs/construction.md).
  Fast,
};

/// Above this many triangles around one vertex, CacheOrder::Best orders a patch as Fast: up to
/// it, the best order costs about what it costs on any patch (280 ns a triangle with fans of
/// 256 against 230 on the brain's patches); a fan of 4,000 took 3.6 us a triangle, and a
/// triangle repeated 16,000 times stalled a build for 40 s.
constexpr std::uint32_t MaxBestOrderValence = 256;

/// Reorders triangles for the vertex cache (`order`) and vertices for fetch order, border
/// vertices first (vertices no triangle uses are dropped), quantizes positions on `grid` with
/// `precision`, and encodes. BoundaryEdges is not stored. `decoded`, when given, receives
/// exactly what DecodePatch would give back from the bytes, without decoding them. Throws
/// std::invalid_argument for an inconsistent mesh (array sizes, indices out of range, counts
/// over the caps) or precision.
VTKATPIO_EXPORT std::vector<std::uint8_t> EncodePatch(const PatchMesh& mesh,
  const QuantizationGrid& grid, const PatchPrecision& precision = {}, PatchMesh* decoded = nullptr,
  CacheOrder order = CacheOrder::Best);

/// Decodes into `out`, reusing its capacity: positions through grid.Dequantize, unit normals,
/// colors when stored, indices all below the vertex count; BoundaryEdges is left empty.
/// Safe on any bytes: throws PatchFormatError (leaving `out` unspecified) for anything but a
/// valid encoding, checking counts against the byte size before allocating.
VTKATPIO_EXPORT void DecodePatch(
  const std::uint8_t* data, std::size_t bytes, const QuantizationGrid& grid, PatchMesh& out);

} // namespace atp

#endif
