// Writes a raw float32 volume of any size, one slice at a time, for the volume input's
// figures: the distance from the centre, rippled (a sphere with bumps at the iso value N/3),
// so the surface grows with N like a scanned object's.
//   atp-bench-volume OUT.raw N
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char** argv)
{
  const long n = argc > 2 ? std::atol(argv[2]) : 0;
  if (argc < 3 || n < 2 || n > 4096)
  {
    std::fprintf(stderr, "usage: atp-bench-volume OUT.raw N (2 to 4096 voxels a side)\n");
    return 2;
  }
  std::FILE* out = std::fopen(argv[1], "wb");
  if (!out)
  {
    std::fprintf(stderr, "atp-bench-volume: cannot create %s\n", argv[1]);
    return 1;
  }
  std::vector<float> slice(std::size_t(n * n));
  const double centre = 0.5 * double(n - 1), frequency = 40.0 / double(n);
  for (long k = 0; k < n; ++k)
  {
    for (long j = 0; j < n; ++j)
    {
      for (long i = 0; i < n; ++i)
      {
        const double x = double(i) - centre, y = double(j) - centre, z = double(k) - centre;
        const double ripple = std::sin(frequency * x) * std::sin(frequency * y) * std::sin(frequency * z);
        slice[std::size_t(j * n + i)] = float(std::sqrt(x * x + y * y + z * z) + 0.02 * double(n) * ripple);
      }
    }
    if (std::fwrite(slice.data(), sizeof(float), slice.size(), out) != slice.size())
    {
      std::fprintf(stderr, "atp-bench-volume: cannot write %s\n", argv[1]);
      std::fclose(out);
      return 1;
    }
  }
  if (std::fclose(out) != 0)
  {
    std::fprintf(stderr, "atp-bench-volume: cannot write %s\n", argv[1]);
    return 1;
  }
  std::printf("wrote %s: %ldx%ldx%ld float32, %.0f MiB\n", argv[1], n, n, n,
    double(n) * double(n) * double(n) * 4 / 1048576);
  return 0;
}
