#include "atpQuantizationGrid.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>

namespace atp
{

QuantizationGrid QuantizationGrid::ForBounds(
  const double min[3], const double max[3], int extraBitsDropped)
{
  if (extraBitsDropped < 0 || extraBitsDropped > Bits)
  {
    throw std::invalid_argument("QuantizationGrid: extraBitsDropped must be in [0, 26]");
  }
  // Positions are floats: work with the bounds as the floats the points can be.
  float lo[3];
  float hi[3];
  float largest = 0;
  for (int a = 0; a < 3; ++a)
  {
    if (!std::isfinite(min[a]) || !std::isfinite(max[a]) || min[a] > max[a] ||
      std::fabs(min[a]) > FLT_MAX || std::fabs(max[a]) > FLT_MAX)
    {
      throw std::invalid_argument("QuantizationGrid: bounds must be finite floats, min <= max");
    }
    lo[a] = static_cast<float>(min[a]);
    hi[a] = static_cast<float>(max[a]);
    largest = std::fmax(largest, std::fmax(std::fabs(lo[a]), std::fabs(hi[a])));
  }
  // largest in [2^e, 2^(e+1)): its ULP is 2^(e-23); below FLT_MIN floats are spaced 2^-149
  // (this also covers a single point at the origin).
  int exponent = 0;
  std::frexp(largest, &exponent); // largest = f * 2^exponent, f in [0.5, 1)
  const int e = std::max(exponent - 1, FLT_MIN_EXP - 1);
  QuantizationGrid grid;
  grid.Step = std::ldexp(1.0, e - (FLT_MANT_DIG - 1) + extraBitsDropped);
  for (int a = 0; a < 3; ++a)
  {
    // A multiple of the step, so grid points are multiples of it too (and floats).
    grid.Origin[a] = std::floor(lo[a] / grid.Step) * grid.Step;
  }
  return grid;
}

std::array<std::uint32_t, 3> QuantizationGrid::Quantize(const float p[3]) const
{
  // Every input corner comes through here: no division and no libm call. The step is a power
  // of two, so multiplying by its inverse is exact, as dividing was; and truncating equals
  // flooring where the result is kept, at 0 and above.
  const double scale = 1 / this->Step;
  std::array<std::uint32_t, 3> q;
  for (int a = 0; a < 3; ++a)
  {
    const double x = (p[a] - this->Origin[a]) * scale + 0.5;
    // Written so that NaN clamps to 0.
    q[a] = x >= 0 ? static_cast<std::uint32_t>(x < double(MaxInteger) ? x : double(MaxInteger)) : 0;
  }
  return q;
}

void QuantizationGrid::Dequantize(const std::uint32_t q[3], float out[3]) const
{
  for (int a = 0; a < 3; ++a)
  {
    // q * Step and the sum are exact in double (26-bit integers, power-of-two step).
    out[a] = static_cast<float>(this->Origin[a] + double(q[a]) * this->Step);
  }
}

} // namespace atp
