// The one integer grid that every patch of a model stores its positions on. One grid for the
// whole model, so a vertex shared by two patches (of any levels) decodes to bit-identical floats
// in both: the renderer shows no cracks.
//
// Precision: the finest grid is lossless relative to single precision. Its step is the float
// spacing (ULP) at the box's largest absolute coordinate M, 2^(e-23) for M in [2^e, 2^(e+1)).
// Every float of that binade is a multiple of the step, so coordinates with M's magnitude
// round-trip bit-exactly; smaller coordinates (finer floats) move by at most half a step, i.e.
// half an ULP of the largest coordinate, below what the input's own rounding means at that
// scale. The box spans less than 2^(e+2), i.e. 2^25 steps, so integers fit in 26 bits. A grid
// with k extra bits dropped has step 2^k times that, for models that do not need full precision.
#ifndef atpQuantizationGrid_h
#define atpQuantizationGrid_h

#include "vtkATPIOModule.h" // export macro

#include <array>
#include <cstdint>

namespace atp
{

struct VTKATPIO_EXPORT QuantizationGrid
{
  static constexpr int Bits = 26;
  static constexpr std::uint32_t MaxInteger = (1u << Bits) - 1;

  double Origin[3]; ///< world = Origin + integer * Step, integers in [0, 2^26)
  double Step;      ///< a power of two; Origin is a multiple of it

  /// The grid for a model with these input bounds (see above). Flat and single-point boxes are
  /// fine: the step follows the magnitude of the coordinates, not the extent. Throws
  /// std::invalid_argument for non-finite or inverted bounds, a box beyond float range or
  /// a negative extraBitsDropped.
  static QuantizationGrid ForBounds(
    const double min[3], const double max[3], int extraBitsDropped = 0);

  /// Rounds to the nearest grid point, clamped into the grid.
  std::array<std::uint32_t, 3> Quantize(const float p[3]) const;
  /// Exact in double, then one rounding to float: the same integers give the same float bits.
  void Dequantize(const std::uint32_t q[3], float out[3]) const;
  /// Moves p to its grid point (Quantize, then Dequantize), where a model stores it; returns
  /// the point's integers.
  std::array<std::uint32_t, 3> Snap(float p[3]) const
  {
    const std::array<std::uint32_t, 3> q = this->Quantize(p);
    this->Dequantize(q.data(), p);
    return q;
  }
  /// The largest distance per coordinate between a point in the box and its dequantized float
  /// (every grid point within the box is a float: the conversion adds no error).
  double MaxError() const { return this->Step / 2; }
};

} // namespace atp

#endif
