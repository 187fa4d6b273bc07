// Unit normals in 32 bits: octahedral mapping (Meyer et al. 2010, "On floating-point normal
// vectors") to two signed 16-bit values. The angular error stays below 0.005 degrees, far below
// what shading shows, at a third of the size of three floats.
#ifndef atpNormalEncoding_h
#define atpNormalEncoding_h

#include <cmath>
#include <cstdint>

namespace atp
{

namespace detail
{
inline float SignNotZero(float v)
{
  return v < 0 ? -1.0f : 1.0f;
}

/// Rounds [-1, 1] to the nearest of -32767..32767, half away from zero, without a libm call.
inline std::int16_t Snorm16(float v)
{
  v = v < -1.0f ? -1.0f : (v > 1.0f ? 1.0f : v);
  const float scaled = v * 32767.0f;
  return std::int16_t(scaled < 0 ? scaled - 0.5f : scaled + 0.5f);
}
} // namespace detail

/// A zero vector encodes as +z (callers avoid it; the result is still a valid unit normal).
inline void EncodeNormal(const float given[3], std::int16_t out[2])
{
  float n[3] = { given[0], given[1], given[2] };
  float l1 = std::fabs(n[0]) + std::fabs(n[1]) + std::fabs(n[2]);
  if (!std::isfinite(l1))
  {
    // Sums of area-weighted normals can leave the float range: infinite components then give
    // the direction (finite ones are negligible beside them), NaN ones count as zero, and
    // finite ones too large to add up are scaled down.
    const bool infinite = std::isinf(n[0]) || std::isinf(n[1]) || std::isinf(n[2]);
    float largest = 0;
    for (const float v : n)
    {
      largest = std::isfinite(v) && std::fabs(v) > largest ? std::fabs(v) : largest;
    }
    for (float& v : n)
    {
      v = std::isinf(v) ? std::copysign(1.0f, v) : (std::isnan(v) || infinite ? 0.0f : v / largest);
    }
    l1 = std::fabs(n[0]) + std::fabs(n[1]) + std::fabs(n[2]);
  }
  float x = l1 > 0 ? n[0] / l1 : 0;
  float y = l1 > 0 ? n[1] / l1 : 0;
  if (l1 > 0 && n[2] < 0)
  {
    // Fold the lower hemisphere over the diagonals of the square.
    const float fx = (1 - std::fabs(y)) * detail::SignNotZero(x);
    const float fy = (1 - std::fabs(x)) * detail::SignNotZero(y);
    x = fx;
    y = fy;
  }
  out[0] = detail::Snorm16(x);
  out[1] = detail::Snorm16(y);
}

inline void DecodeNormal(const std::int16_t in[2], float n[3])
{
  // -32768 is one step past -1: clamp it (a ternary, not fmax, stays a single instruction).
  float x = float(in[0]) * (1.0f / 32767.0f);
  float y = float(in[1]) * (1.0f / 32767.0f);
  x = x < -1.0f ? -1.0f : x;
  y = y < -1.0f ? -1.0f : y;
  const float z = 1 - std::fabs(x) - std::fabs(y);
  if (z < 0)
  {
    const float fx = (1 - std::fabs(y)) * detail::SignNotZero(x);
    const float fy = (1 - std::fabs(x)) * detail::SignNotZero(y);
    x = fx;
    y = fy;
  }
  const float inverseLength = 1.0f / std::sqrt(x * x + y * y + z * z);
  n[0] = x * inverseLength;
  n[1] = y * inverseLength;
  n[2] = z * inverseLength;
}

} // namespace atp

#endif
