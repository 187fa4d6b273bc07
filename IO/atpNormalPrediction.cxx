#include "atpNormalPrediction.h"

namespace atp
{

namespace
{
/// n / d rounded half away from zero, for d > 0 and |2n| + d below 2^31.
std::int32_t RoundedQuotient(std::int32_t n, std::int32_t d)
{
  return n >= 0 ? (2 * n + d) / (2 * d) : -((2 * -n + d) / (2 * d));
}

std::uint64_t Magnitude(std::int64_t v)
{
  return v < 0 ? 0 - std::uint64_t(v) : std::uint64_t(v);
}

/// The number of bits up to the highest set one (0 for 0).
int BitLength(std::uint64_t v)
{
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
}
} // namespace

void OctahedralOfDirection(const std::int64_t direction[3], std::int32_t scale, std::int32_t out[2])
{
  // Magnitudes are cut to 19 bits, far more than an octahedral grid of 2^10 resolves, so that
  // the rounding below stays within 32 bits.
  const std::uint64_t magnitude[3] = { Magnitude(direction[0]), Magnitude(direction[1]),
    Magnitude(direction[2]) };
  const int length = BitLength(magnitude[0] | magnitude[1] | magnitude[2]);
  const int shift = length > DirectionBits ? length - DirectionBits : 0;
  std::int32_t n[3];
  for (int a = 0; a < 3; ++a)
  {
    const std::int32_t cut = std::int32_t(magnitude[a] >> shift);
    n[a] = direction[a] < 0 ? -cut : cut;
  }
  const std::int32_t l1 = (n[0] < 0 ? -n[0] : n[0]) + (n[1] < 0 ? -n[1] : n[1]) + (n[2] < 0 ? -n[2] : n[2]);
  if (l1 == 0)
  {
    out[0] = out[1] = 0;
    return;
  }
  std::int32_t x = RoundedQuotient(n[0] * scale, l1);
  std::int32_t y = RoundedQuotient(n[1] * scale, l1);
  if (n[2] < 0)
  {
    // The lower hemisphere folds over the square's diagonals, as EncodeNormal folds it (the
    // side from the direction's own sign: a coordinate rounded to 0 may still be negative).
    const std::int32_t fx = (scale - (y < 0 ? -y : y)) * (n[0] < 0 ? -1 : 1);
    const std::int32_t fy = (scale - (x < 0 ? -x : x)) * (n[1] < 0 ? -1 : 1);
    x = fx;
    y = fy;
  }
  out[0] = x;
  out[1] = y;
}

void PredictNormals(const std::vector<std::uint32_t>& indices, const std::int64_t* points,
  std::size_t vertexCount, std::int32_t scale, std::int32_t* out)
{
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
    OctahedralOfDirection(direction, scale, out + 2 * v);
  }
}

} // namespace atp
