#include "atpSurfaceGenerator.h"

#include "atpPendingFile.h"

#include <cerrno>
#include <array>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

namespace atp
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

class BufferedFile
{
public:
  // Written beside `path` and renamed into place only when complete (PendingFile), so a failed
  // or interrupted run never leaves a truncated mesh that looks like a real one.
  explicit BufferedFile(const std::string& path)
    : Pending(path, "mesh")
    , File(std::fopen(Pending.PartialPath().c_str(), "wb"))
  {
    if (!File)
    {
      throw Pending.Failure(std::strerror(errno));
    }
    Buffer.reserve(Capacity);
  }
  ~BufferedFile()
  {
    if (File)
    {
      std::fclose(File);
    }
  }
  template <typename T>
  void Put(const T& value)
  {
    const auto* bytes = reinterpret_cast<const char*>(&value);
    Buffer.insert(Buffer.end(), bytes, bytes + sizeof(T));
    if (Buffer.size() >= Capacity)
    {
      Flush();
    }
  }
  void PutText(const std::string& text) { Buffer.insert(Buffer.end(), text.begin(), text.end()); }
  void Close()
  {
    Flush();
    const int closed = std::fclose(File);
    File = nullptr;
    if (closed != 0)
    {
      throw Pending.Failure(std::strerror(errno));
    }
    Pending.Commit();
  }

private:
  void Flush()
  {
    if (!Buffer.empty() && std::fwrite(Buffer.data(), 1, Buffer.size(), File) != Buffer.size())
    {
      throw Pending.Failure(std::strerror(errno));
    }
    Buffer.clear();
  }

  static constexpr std::size_t Capacity = std::size_t(4) << 20;
  PendingFile Pending;
  std::FILE* File;
  std::vector<char> Buffer;
};

/// Whether grid cell (i, j) lies in one of the holes (a few rectangles spread over the torus).
bool InHole(std::uint64_t i, std::uint64_t j, std::uint64_t nu, std::uint64_t nv, int holes)
{
  for (int h = 0; h < holes; ++h)
  {
    const double cu = (h + 0.5) / holes, cv = std::fmod(0.37 * (h + 1), 1.0);
    const double du = std::abs(double(i) / nu - cu), dv = std::abs(double(j) / nv - cv);
    if (du < 0.2 / holes && dv < 0.08)
    {
      return true;
    }
  }
  return false;
}
} // namespace

std::uint64_t WriteBumpyTorusPly(const std::string& path, const SurfaceOptions& options)
{
  // A closed nu x nv grid on the torus has 2 nu nv triangles; nu = 2 nv keeps cells square-ish,
  // and nu is rounded up so that benchmarks asking for N triangles get at least N.
  const double cells = std::max<double>(8, std::ceil(double(options.Triangles) / 2));
  const auto nv = std::uint64_t(std::max(4.0, std::round(std::sqrt(cells / 2))));
  const auto nu = std::uint64_t(std::max(4.0, std::ceil(cells / double(nv))));
  if (nu * nv > std::uint64_t(INT32_MAX))
  {
    throw std::runtime_error(path + ": too many triangles for 32-bit PLY indices");
  }
  std::uint64_t faces = 0;
  for (std::uint64_t i = 0; i < nu; ++i)
  {
    for (std::uint64_t j = 0; j < nv; ++j)
    {
      faces += InHole(i, j, nu, nv, options.Holes) ? 0 : 2;
    }
  }

  BufferedFile out(path);
  out.PutText("ply\nformat binary_little_endian 1.0\ncomment made by atp generate (bumpy torus)\n"
              "element vertex " +
    std::to_string(nu * nv) +
    "\nproperty float x\nproperty float y\nproperty float z\n"
    "element face " +
    std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n");

  const double R = 1.0, r = 0.35;
  for (std::uint64_t i = 0; i < nu; ++i)
  {
    const double u = 2 * Pi * double(i) / double(nu);
    for (std::uint64_t j = 0; j < nv; ++j)
    {
      const double v = 2 * Pi * double(j) / double(nv);
      // Bumps at several scales so every level of detail has something to keep.
      const double bump = 1 + 0.12 * std::sin(9 * u) * std::sin(5 * v) +
        0.04 * std::sin(47 * u + 3 * v) + 0.01 * std::sin(311 * u) * std::cos(173 * v);
      const double rr = r * bump;
      const float p[3] = { float((R + rr * std::cos(v)) * std::cos(u)),
        float((R + rr * std::cos(v)) * std::sin(u)), float(rr * std::sin(v)) };
      out.Put(p);
    }
  }
  for (std::uint64_t i = 0; i < nu; ++i)
  {
    for (std::uint64_t j = 0; j < nv; ++j)
    {
      if (InHole(i, j, nu, nv, options.Holes))
      {
        continue;
      }
      const auto a = std::int32_t(i * nv + j), b = std::int32_t(((i + 1) % nu) * nv + j),
                 c = std::int32_t(((i + 1) % nu) * nv + (j + 1) % nv),
                 d = std::int32_t(i * nv + (j + 1) % nv);
      const std::uint8_t three = 3;
      out.Put(three);
      out.Put(std::array<std::int32_t, 3>{ { a, b, c } });
      out.Put(three);
      out.Put(std::array<std::int32_t, 3>{ { a, c, d } });
    }
  }
  out.Close();
  return faces;
}

} // namespace atp
