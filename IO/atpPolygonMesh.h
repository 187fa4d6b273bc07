// What every format reader hands to the shared triangle path (MeshTriangleSource): the vertex
// positions, and the faces as a rewindable stream of polygon batches (vertex index lists already
// checked against the vertex count). Batches keep the per-face work free of virtual calls.
#ifndef atpPolygonMesh_h
#define atpPolygonMesh_h

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

namespace atp
{

/// Vertex indices are 32-bit.
constexpr std::uint64_t MaxVertices = std::numeric_limits<std::uint32_t>::max();

/// Faces per batch: large enough that per-batch costs vanish, small enough to stay in cache.
constexpr std::size_t PolygonBatchFaces = 16384;

/// Vertex i's x, y, z are three consecutive floats at Base + i * Stride: a packed array, or the
/// vertex records of a memory-mapped binary PLY read in place. Colors, when the input has them,
/// are ColorComponents bytes (red, green, blue, and alpha when there are 4) at
/// Colors + i * ColorStride: other color types are converted to bytes when the vertices are read.
struct VertexView
{
  const unsigned char* Base = nullptr;
  std::size_t Stride = 3 * sizeof(float);
  std::uint64_t Count = 0;
  const unsigned char* Colors = nullptr;
  std::size_t ColorStride = 0;
  int ColorComponents = 0;
  /// The positions and colors are in file-backed mappings, whose pages may be released (and
  /// come back from the file) to bound resident memory; false for heap arrays.
  bool FileBacked = false;

  bool HasColors() const { return this->Colors != nullptr; }

  void Get(std::uint32_t i, float p[3]) const
  {
    std::memcpy(p, this->Base + i * this->Stride, 3 * sizeof(float));
  }

  /// Opaque unless the input gives an alpha.
  void GetColor(std::uint32_t i, std::uint8_t rgba[4]) const
  {
    const unsigned char* c = this->Colors + i * this->ColorStride;
    rgba[0] = c[0];
    rgba[1] = c[1];
    rgba[2] = c[2];
    rgba[3] = this->ColorComponents == 4 ? c[3] : 255;
  }
};

/// Polygons of a batch, one after the other: polygon k has Sizes[k] corners, whose vertex indices
/// follow those of polygon k - 1 in Indices.
struct PolygonBatch
{
  const std::uint32_t* Indices = nullptr;
  const std::uint32_t* Sizes = nullptr;
  std::size_t Count = 0;
};

/// Input coordinates are stored as float. Values beyond float's range become infinities (and are
/// then reported as non-finite) rather than undefined behaviour.
inline float ToFloatCoordinate(double x)
{
  const double limit = std::numeric_limits<float>::max();
  if (x > limit || x < -limit)
  {
    return x > 0 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
  }
  return static_cast<float>(x);
}

/// A color component given as a fraction of 1, as a byte (clamped; NaN gives 0).
inline std::uint8_t ColorByte(double fraction)
{
  return static_cast<std::uint8_t>(fraction > 0 ? std::min(fraction, 1.0) * 255 + 0.5 : 0);
}

/// How a stored color component reads as a fraction of 1 (PLY's and vtkPolyData's arrays alike).
enum class ColorStorage
{
  Real,         ///< already a fraction of 1
  UInt16,       ///< a fraction of 65535
  OtherInteger, ///< a fraction of 255
};

/// A stored color component as a byte.
inline std::uint8_t ColorByte(double value, ColorStorage storage)
{
  return ColorByte(storage == ColorStorage::Real ? value
      : value / (storage == ColorStorage::UInt16 ? 65535 : 255));
}

/// "nan", "inf" or "-inf" for the first non-finite coordinate of p; nullptr when all are finite.
inline const char* FirstNonFinite(const float p[3])
{
  for (int a = 0; a < 3; ++a)
  {
    if (!std::isfinite(p[a]))
    {
      return std::isnan(p[a]) ? "nan" : (p[a] > 0 ? "inf" : "-inf");
    }
  }
  return nullptr;
}

class PolygonMesh
{
public:
  virtual ~PolygonMesh() = default;

  virtual VertexView Vertices() const = 0;

  /// Restarts the face stream at the first face.
  virtual void Rewind() = 0;

  /// The next polygons, valid until the next call; false at the end of the faces.
  /// Throws InputError on malformed or truncated faces.
  virtual bool NextBatch(PolygonBatch& batch) = 0;
};

} // namespace atp

#endif
