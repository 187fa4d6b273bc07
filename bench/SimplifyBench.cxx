// Our constrained simplifier against meshopt_simplify (meshoptimizer 0.18, LockBorder): speed
// (triangles removed per second) and the symmetric, sampled Hausdorff distance between input and
// output, relative to the input's box diagonal, on either of
// - diamond-like chunks of a mesh:
//     atp-bench-simplify [MESH] [CHUNK_TRIANGLES] [CHUNKS] [options]
//   MESH defaults to Data/bumpy-torus.ply; for chunks the size of a real diamond (2-8 members x
//   2 children x 1000-4000 triangles) of a larger mesh:
//     atp generate -n 2000000 -o /tmp/g.ply && atp-bench-simplify /tmp/g.ply 16000 6
//   A chunk is the set of triangles whose centroid lies in a box around a mesh vertex: its cut
//   border is the "diamond-external" boundary (locked by both simplifiers), the input's own
//   holes inside it are the original boundary. Ours halves it as one region.
// - the diamonds of a build of MESH, up to N of each level (--diamonds=N): each exactly what the
//   build hands our simplifier (its children's patches merged, one region per member, the
//   build's quotas: the budget per member, half of the children in all); meshoptimizer, which
//   has no regions, gets the total. The time ratio is also given level by level, and with
//   each level's time per triangle weighted by the triangles the whole build simplifies there
//   (the fine levels: each halves the one below); a large N (--diamonds=100000) takes every
//   diamond, so that the sample itself weighs as the build (half a minute for the bundled torus
//   with --speed-only, over half an hour for the brain).
// --speed-only skips the error measures (for profiling the simplifiers: they take most of the
// run otherwise); --normal-weight=W sets SimplifyOptions::NormalWeight of the first variant
// (default: the library's).
#include "atpClosestPoint.h"
#include "atpMemberLocator.h"
#include "atpMergePatches.h"
#include "atpPatchJob.h"
#include "atpPatchJobRunner.h"
#include "atpSimplifier.h"
#include "atpNormalEncoding.h"
#include "atpTriangleSource.h"
#include "vtkATPBuilder.h"

#include <vtkNew.h>

#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <stdexcept>
#include <vector>

#include <unistd.h>

using namespace atp;

namespace
{

PatchMesh Load(const std::string& path)
{
  std::unique_ptr<TriangleSource> source = OpenTriangleSource(path, "/tmp");
  PatchMesh soup;
  std::vector<SoupTriangle> buffer(4096);
  while (const std::size_t n = source->Read(buffer.data(), buffer.size()))
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      const SoupTriangle& t = buffer[i];
      for (int k = 0; k < 3; ++k)
      {
        float normal[3];
        DecodeNormal(t.Normals[k], normal);
        soup.Indices.push_back(std::uint32_t(soup.VertexCount()));
        soup.Positions.insert(soup.Positions.end(), t.V[k], t.V[k] + 3);
        soup.Normals.insert(soup.Normals.end(), normal, normal + 3);
      }
      soup.BoundaryEdges.push_back(t.BoundaryEdges);
    }
  }
  return MergePatches({ &soup });
}

/// The triangles whose centroid is within `half` of `center` on every axis, compacted.
PatchMesh Cut(const PatchMesh& mesh, const float* center, double half)
{
  PatchMesh chunk;
  std::vector<std::uint32_t> local(mesh.VertexCount(), ~0u);
  for (std::size_t t = 0; t < mesh.TriangleCount(); ++t)
  {
    bool inside = true;
    for (int a = 0; a < 3; ++a)
    {
      double c = 0;
      for (int k = 0; k < 3; ++k)
      {
        c += mesh.Positions[3 * std::size_t(mesh.Indices[3 * t + std::size_t(k)]) + std::size_t(a)] / 3.0;
      }
      inside = inside && std::abs(c - center[a]) <= half;
    }
    if (!inside)
    {
      continue;
    }
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t v = mesh.Indices[3 * t + std::size_t(k)];
      if (local[v] == ~0u)
      {
        local[v] = std::uint32_t(chunk.VertexCount());
        chunk.Positions.insert(chunk.Positions.end(), &mesh.Positions[3 * v], &mesh.Positions[3 * v] + 3);
        chunk.Normals.insert(chunk.Normals.end(), &mesh.Normals[3 * v], &mesh.Normals[3 * v] + 3);
      }
      chunk.Indices.push_back(local[v]);
    }
    chunk.BoundaryEdges.push_back(mesh.BoundaryEdges[t]);
  }
  return chunk;
}

/// Open edges of the chunk: (hole edges with the bit set, cut edges without).
std::pair<std::size_t, std::size_t> CountOpenEdges(const PatchMesh& mesh)
{
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (std::size_t t = 0; t < mesh.TriangleCount(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      std::uint32_t a = mesh.Indices[3 * t + std::size_t(k)], b = mesh.Indices[3 * t + std::size_t((k + 1) % 3)];
      ++uses[{ std::min(a, b), std::max(a, b) }];
    }
  }
  std::size_t holes = 0, cut = 0;
  for (std::size_t t = 0; t < mesh.TriangleCount(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      std::uint32_t a = mesh.Indices[3 * t + std::size_t(k)], b = mesh.Indices[3 * t + std::size_t((k + 1) % 3)];
      if (uses[{ std::min(a, b), std::max(a, b) }] == 1)
      {
        ((mesh.BoundaryEdges[t] >> k) & 1 ? holes : cut)++;
      }
    }
  }
  return { holes, cut };
}

struct Vec
{
  double x, y, z;
};
Vec operator-(Vec a, Vec b)
{
  return { a.x - b.x, a.y - b.y, a.z - b.z };
}
Vec operator+(Vec a, Vec b)
{
  return { a.x + b.x, a.y + b.y, a.z + b.z };
}
Vec operator*(double s, Vec a)
{
  return { s * a.x, s * a.y, s * a.z };
}
double Dot(Vec a, Vec b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
std::array<double, 3> Coordinates(Vec a)
{
  return { a.x, a.y, a.z };
}

/// Triangles binned in a uniform grid, for nearest-surface queries.
class SurfaceGrid
{
public:
  SurfaceGrid(const std::vector<float>& positions, const std::vector<std::uint32_t>& indices)
    : Positions(positions)
    , Indices(indices)
    , Stamp(indices.size() / 3, 0)
  {
    for (int a = 0; a < 3; ++a)
    {
      Lo[a] = 1e300;
      double hi = -1e300;
      for (std::uint32_t v : indices)
      {
        Lo[a] = std::min(Lo[a], double(positions[3 * v + std::uint32_t(a)]));
        hi = std::max(hi, double(positions[3 * v + std::uint32_t(a)]));
      }
      Extent[a] = hi - Lo[a];
    }
    const double cells = std::max<double>(1, double(indices.size() / 3) / 2);
    const double volume = std::max(1e-30, std::max(Extent[0], 1e-9) * std::max(Extent[1], 1e-9) * std::max(Extent[2], 1e-9));
    Cell = std::cbrt(volume / cells);
    for (int a = 0; a < 3; ++a)
    {
      Dim[a] = std::max(1, std::min(256, int(Extent[a] / Cell) + 1));
    }
    Start.assign(std::size_t(Dim[0] * Dim[1] * Dim[2]) + 1, 0);
    // Two passes: count, then fill (CSR).
    for (int pass = 0; pass < 2; ++pass)
    {
      if (pass == 1)
      {
        for (std::size_t i = 1; i < Start.size(); ++i)
        {
          Start[i] += Start[i - 1];
        }
        Items.resize(Start.back());
      }
      for (std::size_t t = 0; t < indices.size() / 3; ++t)
      {
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a)
        {
          double mn = 1e300, mx = -1e300;
          for (int k = 0; k < 3; ++k)
          {
            const double x = positions[3 * indices[3 * t + std::size_t(k)] + std::uint32_t(a)];
            mn = std::min(mn, x);
            mx = std::max(mx, x);
          }
          lo[a] = CellOf(a, mn);
          hi[a] = CellOf(a, mx);
        }
        for (int z = lo[2]; z <= hi[2]; ++z)
          for (int y = lo[1]; y <= hi[1]; ++y)
            for (int x = lo[0]; x <= hi[0]; ++x)
            {
              const std::size_t cell = std::size_t((z * Dim[1] + y) * Dim[0] + x);
              if (pass == 0)
                ++Start[cell + 1];
              else
                Items[Start[cell] + Fill[cell]++] = std::uint32_t(t);
            }
      }
      Fill.assign(Start.size(), 0);
    }
  }

  struct Hit
  {
    double Distance = 0;
    std::uint32_t Triangle = 0;
    TrianglePoint Point; ///< where on Triangle
  };

  double Distance(Vec p) { return Nearest(p).Distance; }

  /// The point of the surface nearest to p, and its triangle.
  Hit Nearest(Vec p)
  {
    Hit hit;
    ++Query;
    const int c[3] = { CellOf(0, p.x), CellOf(1, p.y), CellOf(2, p.z) };
    double best = 1e300;
    const int maxRing = std::max(Dim[0], std::max(Dim[1], Dim[2]));
    for (int r = 0; r <= maxRing; ++r)
    {
      for (int z = c[2] - r; z <= c[2] + r; ++z)
        for (int y = c[1] - r; y <= c[1] + r; ++y)
          for (int x = c[0] - r; x <= c[0] + r; ++x)
          {
            if (std::max(std::abs(x - c[0]), std::max(std::abs(y - c[1]), std::abs(z - c[2]))) != r ||
              x < 0 || y < 0 || z < 0 || x >= Dim[0] || y >= Dim[1] || z >= Dim[2])
              continue;
            const std::size_t cell = std::size_t((z * Dim[1] + y) * Dim[0] + x);
            for (std::size_t i = Start[cell]; i < Start[cell + 1]; ++i)
            {
              const std::uint32_t t = Items[i];
              if (Stamp[t] == Query)
                continue;
              Stamp[t] = Query;
              const TrianglePoint nearest = ClosestOnTriangle(Coordinates(p).data(),
                Coordinates(Corner(t, 0)).data(), Coordinates(Corner(t, 1)).data(), Coordinates(Corner(t, 2)).data());
              const Vec q{ nearest.Point[0], nearest.Point[1], nearest.Point[2] };
              if (Dot(q - p, q - p) < best)
              {
                best = Dot(q - p, q - p);
                hit.Triangle = t;
                hit.Point = nearest;
              }
            }
          }
      if (best <= (r * Cell) * (r * Cell))
        break;
    }
    hit.Distance = std::sqrt(best);
    return hit;
  }

  Vec Corner(std::uint32_t t, int k) const
  {
    const float* p = &Positions[3 * std::size_t(Indices[3 * t + std::uint32_t(k)])];
    return { p[0], p[1], p[2] };
  }
  std::uint32_t CornerVertex(std::uint32_t t, int k) const { return Indices[3 * t + std::uint32_t(k)]; }

private:
  int CellOf(int a, double x) const
  {
    return std::max(0, std::min(Dim[a] - 1, int((x - Lo[a]) / Cell)));
  }

  const std::vector<float>& Positions;
  const std::vector<std::uint32_t>& Indices;
  double Lo[3], Extent[3], Cell = 1;
  int Dim[3];
  std::vector<std::size_t> Start, Fill;
  std::vector<std::uint32_t> Items;
  std::vector<std::uint32_t> Stamp;
  std::uint32_t Query = 0;
};

/// Largest distance from points sampled on `from` (its vertices and `perTriangle` random points
/// per triangle on average, by area) to the surface `to`.
double OneSidedHausdorff(const std::vector<float>& positions, const std::vector<std::uint32_t>& from,
  const std::vector<std::uint32_t>& to, int perTriangle)
{
  SurfaceGrid grid(positions, to);
  std::mt19937 random(12345);
  std::uniform_real_distribution<double> unit(0, 1);
  const auto corner = [&](std::size_t t, int k) {
    const float* p = &positions[3 * std::size_t(from[3 * t + std::size_t(k)])];
    return Vec{ p[0], p[1], p[2] };
  };
  double area = 0;
  for (std::size_t t = 0; t < from.size() / 3; ++t)
  {
    const Vec a = corner(t, 0), b = corner(t, 1) - a, c = corner(t, 2) - a;
    const Vec n{ b.y * c.z - b.z * c.y, b.z * c.x - b.x * c.z, b.x * c.y - b.y * c.x };
    area += std::sqrt(Dot(n, n));
  }
  const double density = perTriangle * double(from.size() / 3) / area;
  double worst = 0;
  for (std::size_t t = 0; t < from.size() / 3; ++t)
  {
    const Vec a = corner(t, 0), b = corner(t, 1), c = corner(t, 2);
    worst = std::max(worst, grid.Distance(a));
    const Vec u = b - a, v = c - a;
    const Vec n{ u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x };
    const double expected = density * std::sqrt(Dot(n, n));
    int samples = int(expected);
    samples += unit(random) < expected - samples ? 1 : 0;
    for (int s = 0; s < samples; ++s)
    {
      double r1 = unit(random), r2 = unit(random);
      if (r1 + r2 > 1)
      {
        r1 = 1 - r1;
        r2 = 1 - r2;
      }
      worst = std::max(worst, grid.Distance(a + r1 * u + r2 * v));
    }
  }
  return worst;
}

double Hausdorff(const std::vector<float>& positions, const std::vector<std::uint32_t>& input,
  const std::vector<std::uint32_t>& output)
{
  return std::max(OneSidedHausdorff(positions, input, output, 8), OneSidedHausdorff(positions, output, input, 16));
}

/// Shading error: at every vertex of `input`, the angle in degrees between its normal and the
/// normal interpolated (barycentric, from the corners' normals) at the nearest point of
/// `output`, averaged. Both simplifiers keep input vertices with their normals, so this shows
/// how well the kept normals stand in for the removed ones once drawn.
double MeanNormalAngle(const std::vector<float>& positions, const std::vector<float>& normals,
  const std::vector<std::uint32_t>& input, const std::vector<std::uint32_t>& output)
{
  SurfaceGrid grid(positions, output);
  std::vector<bool> seen(positions.size() / 3, false);
  double sum = 0;
  std::size_t count = 0;
  for (const std::uint32_t v : input)
  {
    if (seen[v])
    {
      continue;
    }
    seen[v] = true;
    const SurfaceGrid::Hit hit = grid.Nearest({ positions[3 * v], positions[3 * v + 1], positions[3 * v + 2] });
    const double weights[3] = { 1 - hit.Point.S - hit.Point.T, hit.Point.S, hit.Point.T };
    Vec n{ 0, 0, 0 };
    for (int k = 0; k < 3; ++k)
    {
      const float* nk = &normals[3 * std::size_t(grid.CornerVertex(hit.Triangle, k))];
      n = n + weights[k] * Vec{ nk[0], nk[1], nk[2] };
    }
    const Vec m{ normals[3 * v], normals[3 * v + 1], normals[3 * v + 2] };
    const double cosine = Dot(n, m) / std::sqrt(std::max(1e-300, Dot(n, n) * Dot(m, m)));
    sum += std::acos(std::max(-1.0, std::min(1.0, cosine))) * 180 / 3.14159265358979323846;
    ++count;
  }
  return count > 0 ? sum / double(count) : 0;
}

double Diagonal(const PatchMesh& mesh)
{
  double lo[3] = { 1e300, 1e300, 1e300 }, hi[3] = { -1e300, -1e300, -1e300 };
  for (std::size_t i = 0; i < mesh.Positions.size(); ++i)
  {
    lo[i % 3] = std::min(lo[i % 3], double(mesh.Positions[i]));
    hi[i % 3] = std::max(hi[i % 3], double(mesh.Positions[i]));
  }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/// Best of several timed runs, in seconds (at least 5 runs and 0.2 s in all).
template <typename Run>
double Time(Run run)
{
  double best = 1e300, total = 0;
  for (int i = 0; i < 5 || total < 0.2; ++i)
  {
    const auto start = std::chrono::steady_clock::now();
    run();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best = std::min(best, s);
    total += s;
  }
  return best;
}

/// The output of our simplifier as indices into its input's vertices (each output vertex is
/// an input vertex, found by its position).
std::vector<std::uint32_t> ToInputIndices(const PatchMesh& input, const SimplifyResult& result)
{
  std::map<std::array<float, 3>, std::uint32_t> index;
  for (std::uint32_t v = 0; v < input.VertexCount(); ++v)
  {
    index[{ input.Positions[3 * v], input.Positions[3 * v + 1], input.Positions[3 * v + 2] }] = v;
  }
  std::vector<std::uint32_t> out;
  for (const PatchMesh& region : result.Regions)
  {
    for (std::uint32_t v : region.Indices)
    {
      out.push_back(index.at({ region.Positions[3 * v], region.Positions[3 * v + 1], region.Positions[3 * v + 2] }));
    }
  }
  return out;
}

struct Row
{
  std::size_t Out = 0;
  double Seconds = 0, Hausdorff = 0, NormalAngle = 0;
};

void Print(const char* name, std::size_t in, const Row& row)
{
  std::printf("  %-26s %7zu %9.2f %12.2f %14.3e %10.2f\n", name, row.Out, row.Seconds * 1e3,
    double(in - row.Out) / row.Seconds / 1e6, row.Hausdorff, row.NormalAngle);
}

/// One input for the simplifiers: ours keeps each region within its quota and the whole within
/// TotalQuota, meshoptimizer (which has no regions) the whole within the smaller of the sum of
/// the quotas and TotalQuota.
struct Case
{
  std::string Title;
  PatchMesh Mesh;
  int Regions = 1;
  RegionFunction RegionOf = [](const double*, int) { return 0; };
  RegionFunction DeepRegionOf; ///< SimplifyOptions::DeepRegionOf, as the build sets it
  std::vector<std::uint32_t> Quotas;
  std::uint64_t TotalQuota = UINT64_MAX; ///< at most this many in all (SimplifyOptions)
  int Level = 0; ///< a diamond's level counted from the finest that simplifies (1); 0: a chunk
};

/// Chunks of `mesh`, each of about `target` triangles around a vertex, to be halved.
std::vector<Case> Chunks(const PatchMesh& mesh, std::size_t target, int chunks)
{
  std::vector<Case> cases;
  for (int c = 0; c < chunks; ++c)
  {
    const std::uint32_t seed = std::uint32_t((2 * c + 1) * mesh.VertexCount() / std::size_t(2 * chunks));
    const float* center = &mesh.Positions[3 * std::size_t(seed)];
    // Box size by bisection, for about `target` triangles.
    double lo = 0, hi = Diagonal(mesh);
    Case chunk;
    for (int i = 0; i < 40; ++i)
    {
      const double half = 0.5 * (lo + hi);
      chunk.Mesh = Cut(mesh, center, half);
      if (chunk.Mesh.TriangleCount() * 10 < target * 9)
        lo = half;
      else if (chunk.Mesh.TriangleCount() * 10 > target * 11)
        hi = half;
      else
        break;
    }
    const auto open = CountOpenEdges(chunk.Mesh);
    chunk.Quotas = { std::uint32_t(chunk.Mesh.TriangleCount() / 2) };
    chunk.Title = "chunk " + std::to_string(c) + ": " + std::to_string(chunk.Mesh.TriangleCount()) +
      " triangles, " + std::to_string(open.second) + " cut (locked) edges, " + std::to_string(open.first) +
      " hole edges -> quota " + std::to_string(chunk.Quotas[0]);
    cases.push_back(std::move(chunk));
  }
  return cases;
}

/// Runs a build's jobs on this process's threads, keeping a copy of up to `perLevel` diamond
/// jobs of each level, spread over it: the simplifier's inputs exactly as the build gives them.
class RecordingRunner final : public PatchJobRunner
{
public:
  explicit RecordingRunner(std::size_t perLevel)
    : PerLevel(perLevel)
  {
  }
  void Begin(const PatchJobContext& context) override
  {
    Context = std::make_unique<PatchJobContext>(context);
    Threads->Begin(context);
  }
  void Run(std::size_t count, const LoadJob& load, const StoreResult& store) override
  {
    const std::size_t step = std::max<std::size_t>(1, count / PerLevel);
    bool diamonds = false;
    std::mutex mutex; // jobs are loaded on several threads
    std::map<std::size_t, PatchJob> kept; // by index: recorded in job order whatever the threads
    Threads->Run(
      count,
      [&](std::size_t i, PatchJob& job) {
        load(i, job);
        std::uint64_t triangles = 0;
        for (const PatchMesh& child : job.Children)
        {
          triangles += child.TriangleCount();
        }
        const std::lock_guard<std::mutex> lock(mutex);
        diamonds = diamonds || !job.IsLeaf();
        LevelTriangles[DiamondLevels + 1] += double(triangles);
        if (!job.IsLeaf() && i % step == 0 && i / step < PerLevel)
        {
          kept.emplace(i, job);
        }
      },
      store);
    for (auto& indexAndJob : kept)
    {
      Jobs.push_back(std::move(indexAndJob.second));
      Levels.push_back(DiamondLevels + 1);
    }
    DiamondLevels += diamonds;
  }

  std::unique_ptr<PatchJobContext> Context;
  std::vector<PatchJob> Jobs;
  /// Per job: its level counted from the finest that simplifies (1) to the roots'.
  std::vector<int> Levels;
  /// Per level: the triangles all its diamonds simplify in the build.
  std::map<int, double> LevelTriangles;

private:
  std::size_t PerLevel;
  std::unique_ptr<PatchJobRunner> Threads = MakeThreadJobRunner(0);
  int DiamondLevels = 0;
};

/// Diamonds of a build of the mesh at `path`, up to `perLevel` of each level: their children's
/// patches merged, one region per member, the build's quotas. levelTriangles gets the triangles
/// each level simplifies in the whole build.
std::vector<Case> Diamonds(const std::string& path, std::size_t perLevel, std::map<int, double>& levelTriangles)
{
  RecordingRunner runner(perLevel);
  const std::string model = "/tmp/atp-bench-simplify-" + std::to_string(::getpid()) + ".atp";
  vtkNew<vtkATPBuilder> builder;
  builder->SetInputFileName(path.c_str());
  builder->SetFileName(model.c_str());
  builder->SetScratchDirectory("/tmp");
  builder->SetJobRunner(&runner);
  const int built = builder->Build();
  std::remove(model.c_str());
  if (!built)
  {
    throw std::runtime_error(std::string("the build failed: ") + builder->GetErrorMessage());
  }
  std::vector<Case> cases;
  for (std::size_t j = 0; j < runner.Jobs.size(); ++j)
  {
    const PatchJob& job = runner.Jobs[j];
    Case diamond;
    std::vector<const PatchMesh*> parts;
    for (const PatchMesh& child : job.Children)
    {
      parts.push_back(&child);
    }
    diamond.Mesh = MergePatches(parts);
    diamond.Regions = int(job.Members.size());
    const auto locator = std::make_shared<MemberLocator>(job.Members, runner.Context->Frame);
    diamond.RegionOf = [locator](const double p[3], int likely) { return locator->MemberOf(p, likely); };
    diamond.DeepRegionOf = [locator](const double p[3], int likely) { return locator->DeepMemberOf(p, likely); };
    const DiamondQuotas quotas = QuotasOf(job, runner.Context->PatchBudget);
    diamond.Quotas = quotas.Members;
    diamond.TotalQuota = quotas.Total;
    const auto open = CountOpenEdges(diamond.Mesh);
    diamond.Level = runner.Levels[j];
    diamond.Title = "diamond, level " + std::to_string(runner.Levels[j]) + " up: " +
      std::to_string(diamond.Mesh.TriangleCount()) + " triangles, " + std::to_string(open.second) +
      " locked edges, " + std::to_string(open.first) + " hole edges, " + std::to_string(diamond.Regions) +
      " members -> " + std::to_string(quotas.Total) + " in all, at most " +
      std::to_string(quotas.Members.front()) + " each";
    cases.push_back(std::move(diamond));
  }
  levelTriangles = runner.LevelTriangles;
  return cases;
}

} // namespace

int main(int argc, char** argv)
{
  std::vector<std::string> positional;
  bool measureError = true;
  double normalWeight = SimplifyOptions().NormalWeight;
  std::size_t diamondsPerLevel = 0;
  for (int i = 1; i < argc; ++i)
  {
    const std::string option = argv[i];
    if (option.rfind("--", 0) != 0)
    {
      positional.push_back(option);
    }
    else if (option == "--speed-only")
    {
      measureError = false;
    }
    else if (option.rfind("--normal-weight=", 0) == 0)
    {
      normalWeight = std::stod(option.substr(16));
    }
    else if (option.rfind("--diamonds=", 0) == 0)
    {
      diamondsPerLevel = std::stoul(option.substr(11));
    }
    else
    {
      std::fprintf(stderr, "unknown option %s\n", option.c_str());
      return 1;
    }
  }
  const std::string path = positional.size() > 0 ? positional[0] : ATP_DATA_DIR "/bumpy-torus.ply";
  const std::size_t target = positional.size() > 1 ? std::stoul(positional[1]) : 12000;
  const int chunks = positional.size() > 2 ? std::stoi(positional[2]) : 6;
  std::vector<Case> cases;
  std::map<int, double> levelTriangles; // diamonds: each level's triangles in the whole build
  try
  {
    if (diamondsPerLevel > 0)
    {
      cases = Diamonds(path, diamondsPerLevel, levelTriangles);
      std::printf("mesh %s: %zu diamonds of its build, up to %zu a level\n", path.c_str(), cases.size(),
        diamondsPerLevel);
    }
    else
    {
      const PatchMesh mesh = Load(path);
      std::printf("mesh %s: %zu vertices, %zu triangles; %d chunks of ~%zu triangles, each halved\n",
        path.c_str(), mesh.VertexCount(), mesh.TriangleCount(), chunks, target);
      cases = Chunks(mesh, target, chunks);
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "atp-bench-simplify: %s\n", e.what());
    return 1;
  }
  std::printf("meshopt_simplify (meshoptimizer %d.%d) runs with meshopt_SimplifyLockBorder and target_error 1,\n"
              "to the total quota (it has no regions). LockBorder also locks the input's own holes,\n"
              "which our simplifier may simplify along.\n"
              "Hausdorff: symmetric, sampled, relative to the input's box diagonal. Normal: the mean\n"
              "angle (degrees) between each input vertex's normal and the output's interpolated\n"
              "normal at its nearest point. Ours weighs normals by %g.\n\n",
    MESHOPTIMIZER_VERSION / 1000, MESHOPTIMIZER_VERSION % 1000 / 10, normalWeight);

  // With several regions, ours also runs as meshoptimizer does, to the total in one region:
  // what the members' budgets and regions cost apart from the simplifier itself.
  const bool regions = std::any_of(cases.begin(), cases.end(), [](const Case& c) { return c.Regions > 1; });
  const int variants = regions ? 4 : 3;
  Row sum[4];
  std::size_t sumIn = 0;
  // Per input, each variant's Hausdorff distance over meshoptimizer's: the mean of maxima above
  // follows a few inputs' worst points, so the comparison is also made input by input.
  std::vector<double> errorRatios[4];
  // Per level of diamonds: input triangles, and the seconds of ours (with normals) and of
  // meshoptimizer. A build's time goes mostly to the fine levels (each halves the one below),
  // which the sample of a few diamonds a level underweights.
  std::map<int, std::array<double, 3>> byLevel;
  const char* names[4] = { "ours (normals weighted)", "ours (positions only)", "meshopt LockBorder",
    "ours, one region" };
  for (const Case& input : cases)
  {
    const PatchMesh& mesh = input.Mesh;
    std::uint64_t quotaSum = 0;
    for (const std::uint32_t q : input.Quotas)
    {
      quotaSum += q;
    }
    const std::uint32_t total = std::uint32_t(std::min(quotaSum, input.TotalQuota));
    const double diagonal = Diagonal(mesh);
    // Relative to the input's diagonal; 0 (not sampled) with --speed-only.
    const auto measure = [&](const std::vector<std::uint32_t>& out, Row& row) {
      row.Out = out.size() / 3;
      if (measureError)
      {
        row.Hausdorff = Hausdorff(mesh.Positions, mesh.Indices, out) / diagonal;
        row.NormalAngle = MeanNormalAngle(mesh.Positions, mesh.Normals, mesh.Indices, out);
      }
    };
    std::printf("%s\n", input.Title.c_str());
    std::printf("  %-26s %7s %9s %12s %14s %10s\n", "", "out", "ms", "Mtri/s rem.", "Hausdorff/diag", "normal°");

    Row rows[4];
    for (int variant : { 0, 1, 3 })
    {
      if (variant >= variants)
      {
        continue;
      }
      SimplifyOptions options;
      options.NormalWeight = variant == 1 ? 0 : normalWeight;
      options.TotalQuota = input.TotalQuota;
      options.DeepRegionOf = variant == 3 ? nullptr : input.DeepRegionOf;
      SimplifyResult result;
      rows[variant].Seconds = Time([&] {
        result = variant == 3
          ? Simplify(mesh, 1, [](const double*, int) { return 0; }, { total }, options)
          : Simplify(mesh, input.Regions, input.RegionOf, input.Quotas, options);
      });
      measure(ToInputIndices(mesh, result), rows[variant]);
    }
    std::vector<std::uint32_t> out(mesh.Indices.size());
    std::size_t count = 0;
    rows[2].Seconds = Time([&] {
      count = meshopt_simplify(out.data(), mesh.Indices.data(), mesh.Indices.size(), mesh.Positions.data(),
        mesh.VertexCount(), 3 * sizeof(float), 3 * std::size_t(total), 1.0f, meshopt_SimplifyLockBorder, nullptr);
    });
    out.resize(count);
    measure(out, rows[2]);
    for (int v = 0; v < variants; ++v)
    {
      Print(names[v], mesh.TriangleCount(), rows[v]);
      sum[v].Out += rows[v].Out;
      sum[v].Seconds += rows[v].Seconds;
      sum[v].Hausdorff += rows[v].Hausdorff / double(cases.size());
      sum[v].NormalAngle += rows[v].NormalAngle / double(cases.size());
    }
    for (int v = 0; measureError && v < variants; ++v)
    {
      if (v == 2)
      {
        continue; // meshoptimizer itself
      }
      const double ours = rows[v].Hausdorff, theirs = rows[2].Hausdorff;
      // Both exact counts as level; ours off where meshoptimizer is exact, as a loss.
      errorRatios[v].push_back(theirs > 0 ? ours / theirs : (ours > 0 ? HUGE_VAL : 1.0));
    }
    sumIn += mesh.TriangleCount();
    std::array<double, 3>& level = byLevel[input.Level];
    level[0] += double(mesh.TriangleCount());
    level[1] += rows[0].Seconds;
    level[2] += rows[2].Seconds;
  }
  std::printf("\nall inputs (time and rate summed, errors averaged):\n");
  std::printf("  %-26s %7s %9s %12s %14s %10s\n", "", "out", "ms", "Mtri/s rem.", "Hausdorff/diag", "normal°");
  for (int v = 0; v < variants; ++v)
  {
    Print(names[v], sumIn, sum[v]);
  }
  for (int v = 0; measureError && v < variants; ++v)
  {
    std::vector<double>& ratios = errorRatios[v];
    if (ratios.empty())
    {
      continue;
    }
    std::sort(ratios.begin(), ratios.end());
    const std::size_t n = ratios.size();
    const auto level = std::equal_range(ratios.begin(), ratios.end(), 1.0);
    const double median = (ratios[(n - 1) / 2] + ratios[n / 2]) / 2;
    std::printf("  %-26s Hausdorff over meshopt's: median %.3f; under on %td, level on %td, over on %td"
                " of %zu inputs\n",
      names[v], median, level.first - ratios.begin(), level.second - level.first, ratios.end() - level.second, n);
  }
  if (byLevel.size() > 1)
  {
    std::printf("time against meshopt_simplify's by level (with normals):");
    for (const auto& [level, figures] : byLevel)
    {
      std::printf(" %d up %.2fx (%.0fk triangles);", level, figures[1] / figures[2], figures[0] / 1000);
    }
    std::printf("\n");
    // Each level's sampled time per triangle, times the triangles the build simplifies there:
    // the ratio the build itself sees.
    double ours = 0, theirs = 0;
    for (const auto& [level, figures] : byLevel)
    {
      const auto whole = levelTriangles.find(level);
      if (figures[0] > 0 && whole != levelTriangles.end())
      {
        ours += whole->second * figures[1] / figures[0];
        theirs += whole->second * figures[2] / figures[0];
      }
    }
    if (theirs > 0)
    {
      std::printf("time against meshopt_simplify's, each level weighted by its triangles in the build: %.3fx"
                  " with normals\n",
        ours / theirs);
    }
  }
  // Both run in the same process, input after input: the ratio holds still where this machine's
  // speed drifts (by 25-50% within minutes), so runs of different builds compare by it.
  std::printf("time against meshopt_simplify's: %.3fx with normals, %.3fx on positions\n",
    sum[0].Seconds / sum[2].Seconds, sum[1].Seconds / sum[2].Seconds);
  return 0;
}
