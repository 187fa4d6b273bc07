#include "atpNormalPrediction.h"

#include <stdexcept>
#include <string>

namespace atp
{

namespace
{
std::uint64_t Magnitude(std::int64_t v)
{
  return v < 0 ? 0 - std::uint64_t(v) : std::uint64_t(v);
}

/// The number of bits up to the highest set one (0 for 0).
int BitLength(std::uint64_t v)
{
#if defined(__GNUC__)
  return v == 0 ? 0 : 64 - __builtin_clzll(v);
#else
  int length = 0;
  for (int step = 32; step > 0; step /= 2)
  {
    if (v >> step)
    {
      v >>= step;
      length += step;
    }
  }
  return length + int(v != 0);
#endif
}

/// OctahedralOfDirection, inlined where PredictNormals calls it once per vertex.
inline void Octahedral(const std::int64_t direction[3], std::int32_t scale, std::int32_t out[2])
{
  // Magnitudes are cut to DirectionBits bits, far more than an octahedral grid of 2^10
  // resolves, so that the rounding below stays within 32 bits.
  std::uint32_t cut[3];
  {
    const std::uint64_t magnitude[3] = { Magnitude(direction[0]), Magnitude(direction[1]),
      Magnitude(direction[2]) };
    const int length = BitLength(magnitude[0] | magnitude[1] | magnitude[2]);
    const int shift = length > DirectionBits ? length - DirectionBits : 0;
    for (int a = 0; a < 3; ++a)
    {
      cut[a] = std::uint32_t(magnitude[a] >> shift);
    }
  }
  // A component cut to 0 has no sign left.
  const bool negative[3] = { direction[0] < 0 && cut[0] != 0, direction[1] < 0 && cut[1] != 0,
    direction[2] < 0 && cut[2] != 0 };
  const std::uint32_t l1 = cut[0] + cut[1] + cut[2];
  if (l1 == 0)
  {
    out[0] = out[1] = 0;
    return;
  }
  // |n| scale / l1 rounded half away from zero, on magnitudes.
  const std::uint32_t u = scale;
  const std::int32_t ax = std::int32_t((2 * cut[0] * u + l1) / (2 * l1));
  const std::int32_t ay = std::int32_t((2 * cut[1] * u + l1) / (2 * l1));
  if (negative[2])
  {
    // The lower hemisphere folds over the square's diagonals, as EncodeNormal folds it (the
    // side from the direction's own sign: a coordinate rounded to 0 may still be negative).
    out[0] = negative[0] ? ay - scale : scale - ay;
    out[1] = negative[1] ? ax - scale : scale - ax;
  }
  else
  {
    out[0] = negative[0] ? -ax : ax;
    out[1] = negative[1] ? -ay : ay;
  }
}

void CheckScale(std::int32_t scale)
{
  if (scale < 1 || scale > MaxOctahedralScale)
  {
    throw std::invalid_argument("octahedral scale " + std::to_string(scale) + " outside 1.." +
      std::to_string(MaxOctahedralScale));
  }
}
} // namespace

void OctahedralOfDirection(const std::int64_t direction[3], std::int32_t scale, std::int32_t out[2])
{
  CheckScale(scale);
  Octahedral(direction, scale, out);
}

void PredictNormals(const std::vector<std::uint32_t>& indices, const std::int64_t* points,
  std::size_t vertexCount, std::int32_t scale, std::int32_t* out)
{
  CheckScale(scale);
  // Unsigned arithmetic: wrapping is defined, so even sums a huge fan overflows agree.
  std::vector<std::uint64_t> sums(3 * vertexCount, 0);
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
  {
    const std::int64_t* a = points + 3 * std::size_t(indices[t]);
    const std::int64_t* b = points + 3 * std::size_t(indices[t + 1]);
    const std::int64_t* c = points + 3 * std::size_t(indices[t + 2]);
    std::uint64_t u[3], v[3];
    for (int k = 0; k < 3; ++k)
    {
      u[k] = std::uint64_t(b[k]) - std::uint64_t(a[k]);
      v[k] = std::uint64_t(c[k]) - std::uint64_t(a[k]);
    }
    const std::uint64_t normal[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
      u[0] * v[1] - u[1] * v[0] };
    for (int corner = 0; corner < 3; ++corner)
    {
      std::uint64_t* sum = &sums[3 * std::size_t(indices[t + corner])];
      for (int k = 0; k < 3; ++k)
      {
        sum[k] += normal[k];
      }
    }
  }
  for (std::size_t v = 0; v < vertexCount; ++v)
  {
    const std::int64_t direction[3] = { std::int64_t(sums[3 * v]), std::int64_t(sums[3 * v + 1]),
      std::int64_t(sums[3 * v + 2]) };
    Octahedral(direction, scale, out + 2 * v);
  }
}

} // namespace atp
