// The partitioning phase alone, as `atp build` runs it (default options), timed in its two
// parts: opening the input (the first pass over the faces: normals, boundary edges, counts) and
// streaming the triangles into the forest and its buckets (the second pass).
//   atp-bench-partition MESH [SCRATCH_DIR]
#include "atpStreamPartition.h"
#include "atpTriangleSource.h"

#include <chrono>
#include <cstdio>
#include <exception>
#include <string>

namespace
{
double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
} // namespace

int main(int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: atp-bench-partition MESH [SCRATCH_DIR]\n");
    return 2;
  }
  try
  {
    const std::string scratch = argc > 2 ? argv[2] : "";
    const auto start = std::chrono::steady_clock::now();
    const std::unique_ptr<atp::TriangleSource> source = atp::OpenTriangleSource(argv[1], scratch);
    const double opened = SecondsSince(start);
    atp::PartitionOptions options;
    options.ScratchDirectory = scratch;
    options.Colors = source->HasColors();
    const auto streamed = std::chrono::steady_clock::now();
    const std::unique_ptr<atp::Partitioner> partitioner =
      atp::PartitionStream(*source, options, [](std::uint64_t) {});
    const double streaming = SecondsSince(streamed);
    const double total = SecondsSince(start);
    const atp::PartitionStats stats = partitioner->Stats();
    std::printf("triangles: %llu, leaves %llu, depth %d\n", static_cast<unsigned long long>(stats.Triangles),
      static_cast<unsigned long long>(stats.Leaves), stats.Depth);
    std::printf("first pass (open): %.2f s; streaming into buckets: %.2f s; partition: %.2f s, %.2fM triangles/s\n",
      opened, streaming, total, double(stats.Triangles) / total / 1e6);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "atp-bench-partition: %s\n", e.what());
    return 1;
  }
  return 0;
}
