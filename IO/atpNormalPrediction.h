// Predicting a patch's vertex normals from its own triangles. Construction gives each vertex the
// area-weighted sum of its faces' normals in the full-resolution mesh (and simplification carries
// normals close to the surface's), so a decoder that already has the positions can compute
// nearly the same normal itself; the normal stream then stores only how far each normal is from
// that prediction.
//
// Integer arithmetic only: every reader on every platform predicts bit for bit what the encoder
// predicted, which a floating-point sum (contracted into fused multiply-adds or not) would not
// promise.
#ifndef atpNormalPrediction_h
#define atpNormalPrediction_h

#include "vtkATPIOModule.h" // export macro

#include <cstddef>
#include <cstdint>
#include <vector>

namespace atp
{

/// Magnitudes OctahedralOfDirection keeps of a direction's components.
constexpr int DirectionBits = 19;
/// The largest scale OctahedralOfDirection takes.
constexpr std::int32_t MaxOctahedralScale = 1 << 10;

/// Octahedral coordinates (the mapping of atpNormalEncoding.h) of the direction `direction`, on
/// the square [-scale, scale]^2 (rounded half away from zero), `scale` from 1 to
/// MaxOctahedralScale (std::invalid_argument otherwise). The components are first shifted right
/// (magnitudes, signs kept) until all fit in DirectionBits bits. The zero vector gives +z, (0, 0).
VTKATPIO_EXPORT void OctahedralOfDirection(
  const std::int64_t direction[3], std::int32_t scale, std::int32_t out[2]);

/// For each of `vertexCount` vertices, OctahedralOfDirection of the sum, over the triangles of
/// `indices` that use it, of (b - a) x (c - a) for the triangle's grid points a, b, c (three
/// per vertex in `points`, each below 2^26). Sums that leave 64 bits wrap around, the same way
/// for encoder and decoder. Writes 2 x vertexCount values to `out`. `scale` as for
/// OctahedralOfDirection.
VTKATPIO_EXPORT void PredictNormals(const std::vector<std::uint32_t>& indices,
  const std::int64_t* points, std::size_t vertexCount, std::int32_t scale, std::int32_t* out);

} // namespace atp

#endif
