// The cut alone (no rendering): how long opening the model and indexing its diamonds takes,
// and the median and 95th-percentile time of a view-dependent cut over random views around
// the model (frustum culling on, 800x600, 1 px by default).
//   atp-bench-cut MODEL.atp [--views N] [--tolerance PX] [--backface]
#include "atpCut.h"
#include "atpCutIndex.h"
#include "atpModelFile.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}
} // namespace

int main(int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: atp-bench-cut MODEL.atp [--views N] [--tolerance PX] [--backface]\n");
    return 2;
  }
  int views = 200;
  double tolerance = 1;
  bool backface = false;
  for (int i = 2; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--views") && i + 1 < argc) { views = std::max(1, std::atoi(argv[++i])); }
    else if (!std::strcmp(argv[i], "--tolerance") && i + 1 < argc) { tolerance = std::atof(argv[++i]); }
    else if (!std::strcmp(argv[i], "--backface")) { backface = true; }
    else { std::fprintf(stderr, "atp-bench-cut: unknown option %s\n", argv[i]); return 2; }
  }
  try
  {
    Clock::time_point start = Clock::now();
    const atp::ModelFile model = atp::ModelFile::Open(argv[1]);
    const double openSeconds = Since(start);
    start = Clock::now();
    auto index = std::make_shared<const atp::CutIndex>(model);
    const double indexSeconds = Since(start);
    atp::CutSelector selector(model, index);

    const atp::ModelHeader& h = model.Header();
    double center[3], radius = 0;
    for (int a = 0; a < 3; ++a)
    {
      center[a] = (h.BoxMin[a] + h.BoxMax[a]) / 2;
      radius += (h.BoxMax[a] - h.BoxMin[a]) * (h.BoxMax[a] - h.BoxMin[a]) / 4;
    }
    radius = std::sqrt(radius);
    std::mt19937_64 random(1);
    std::uniform_real_distribution<double> unit(-1, 1), distance(1.2, 4);
    std::vector<double> seconds;
    std::vector<std::size_t> visited, drawn, triangles;
    atp::CutResult cut;
    for (int v = 0; v < views; ++v)
    {
      // Eyes around the bounding sphere looking at its centre: a symmetric frustum of 30 by 40
      // degrees (800x600) built from the view direction.
      double dir[3] = { unit(random), unit(random), unit(random) };
      const double length = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
      for (double& d : dir) d /= length;
      atp::ViewPoint view;
      view.TolerancePixels = tolerance;
      view.BackfaceCulling = backface;
      const double d = distance(random) * radius;
      for (int a = 0; a < 3; ++a) view.Eye[a] = center[a] + dir[a] * d;
      // Side planes: a cone of half angle 25 degrees around the view axis, as four planes.
      double up[3] = { 0, 0, 1 };
      if (std::abs(dir[2]) > 0.9) { up[0] = 1; up[2] = 0; }
      double right[3] = { up[1] * dir[2] - up[2] * dir[1], up[2] * dir[0] - up[0] * dir[2], up[0] * dir[1] - up[1] * dir[0] };
      const double rl = std::sqrt(right[0] * right[0] + right[1] * right[1] + right[2] * right[2]);
      for (double& r : right) r /= rl;
      const double trueUp[3] = { dir[1] * right[2] - dir[2] * right[1], dir[2] * right[0] - dir[0] * right[2], dir[0] * right[1] - dir[1] * right[0] };
      const double c = std::cos(25 * M_PI / 180), s = std::sin(25 * M_PI / 180);
      const double* sides[2] = { right, trueUp };
      view.PlaneCount = 4;
      for (int p = 0; p < 4; ++p)
      {
        const double sign = p % 2 ? -1 : 1;
        for (int a = 0; a < 3; ++a) view.Planes[p][a] = -dir[a] * s + sign * sides[p / 2][a] * c;
        view.Planes[p][3] = -(view.Planes[p][0] * view.Eye[0] + view.Planes[p][1] * view.Eye[1] + view.Planes[p][2] * view.Eye[2]);
      }
      start = Clock::now();
      selector.Select(view, h.ErrorScale, atp::ResidentFunction(), cut);
      seconds.push_back(Since(start));
      visited.push_back(cut.Visited);
      drawn.push_back(cut.Drawn.size());
      std::size_t drawnTriangles = 0;
      for (const std::uint32_t node : cut.Drawn)
      {
        drawnTriangles += model.Node(node).TriangleCount;
      }
      triangles.push_back(drawnTriangles);
    }
    std::sort(seconds.begin(), seconds.end());
    std::sort(visited.begin(), visited.end());
    std::sort(drawn.begin(), drawn.end());
    std::sort(triangles.begin(), triangles.end());
    std::printf("model: %s: %zu nodes, %zu diamonds; open %.1f ms, diamond index %.1f ms\n", argv[1],
      model.NodeCount(), index->DiamondCount(), 1e3 * openSeconds, 1e3 * indexSeconds);
    std::printf("cut: %d views at %g px: median %.3f ms, p95 %.3f ms; nodes visited median %zu; "
                "patches median %zu, max %zu; triangles median %zu, max %zu\n",
      views, tolerance, 1e3 * seconds[seconds.size() / 2], 1e3 * seconds[seconds.size() * 95 / 100],
      visited[visited.size() / 2], drawn[drawn.size() / 2], drawn.back(), triangles[triangles.size() / 2],
      triangles.back());
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "atp-bench-cut: %s\n", e.what());
    return 1;
  }
  return 0;
}
