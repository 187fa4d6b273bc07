// atp-bench-decode [mesh file] [seconds] [--fast-cache-order]: splits a mesh into patches of
// ~3000 triangles (consecutive in Morton order of their centroids, welded by position and
// normal), encodes them with the patch codec on the model's quantization grid (in the default or
// the fast cache order), and times decoding them over and over.
// Prints encoded size per triangle and vertex, decode and checksum throughput, and the vertex
// cache figures behind the choice of indexed lists over strips.
#include "atpChecksum.h"
#include "atpNormalEncoding.h"
#include "atpPatchCodec.h"
#include "atpTetra.h"
#include "atpQuantizationGrid.h"
#include "atpTriangleSource.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace
{
constexpr std::size_t TrianglesPerPatch = 3000;
constexpr unsigned CacheSize = 16; // post-transform cache entries modelled by meshopt

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::vector<atp::SoupTriangle> ReadAll(atp::TriangleSource& source)
{
  std::vector<atp::SoupTriangle> triangles;
  std::vector<atp::SoupTriangle> buffer(4096);
  while (const std::size_t n = source.Read(buffer.data(), buffer.size()))
  {
    triangles.insert(triangles.end(), buffer.begin(), buffer.begin() + n);
  }
  return triangles;
}

void SortByMorton(std::vector<atp::SoupTriangle>& triangles, const atp::Box& box)
{
  std::vector<std::pair<std::uint64_t, std::size_t>> keys(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    std::uint32_t cell[3];
    for (int a = 0; a < 3; ++a)
    {
      const double extent = std::max(box.Max[a] - box.Min[a], 1e-30);
      const double c = (triangles[t].V[0][a] + triangles[t].V[1][a] + triangles[t].V[2][a]) / 3;
      cell[a] = static_cast<std::uint32_t>((c - box.Min[a]) / extent * 0x1fffff);
    }
    keys[t] = { atp::MortonCode(cell[0], cell[1], cell[2]), t };
  }
  std::sort(keys.begin(), keys.end());
  std::vector<atp::SoupTriangle> sorted(triangles.size());
  for (std::size_t t = 0; t < keys.size(); ++t)
  {
    sorted[t] = triangles[keys[t].second];
  }
  triangles.swap(sorted);
}

/// Welds corners with equal position and normal bits into indexed vertices.
atp::PatchMesh Weld(const atp::SoupTriangle* triangles, std::size_t count)
{
  atp::PatchMesh mesh;
  std::unordered_map<std::string, std::uint32_t> vertices;
  for (std::size_t t = 0; t < count; ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      std::string key(reinterpret_cast<const char*>(triangles[t].V[c]), sizeof(float[3]));
      key.append(reinterpret_cast<const char*>(triangles[t].Normals[c]), sizeof(std::int16_t[2]));
      const auto inserted =
        vertices.emplace(key, static_cast<std::uint32_t>(mesh.VertexCount()));
      if (inserted.second)
      {
        mesh.Positions.insert(mesh.Positions.end(), triangles[t].V[c], triangles[t].V[c] + 3);
        float n[3];
        atp::DecodeNormal(triangles[t].Normals[c], n);
        mesh.Normals.insert(mesh.Normals.end(), n, n + 3);
      }
      mesh.Indices.push_back(inserted.first->second);
    }
  }
  return mesh;
}

/// Average cache misses per triangle at CacheSize entries.
float Acmr(const std::vector<std::uint32_t>& indices, std::size_t vertexCount)
{
  return meshopt_analyzeVertexCache(indices.data(), indices.size(), vertexCount, CacheSize, 0, 0)
    .acmr;
}

int Run(const std::string& path, double minimumSeconds, atp::CacheOrder order)
{
  const std::string scratch = std::filesystem::temp_directory_path().string();
  std::unique_ptr<atp::TriangleSource> source = atp::OpenTriangleSource(path, scratch);
  const atp::Box box = source->Bounds();
  std::vector<atp::SoupTriangle> soup = ReadAll(*source);
  SortByMorton(soup, box);
  const atp::QuantizationGrid grid = atp::QuantizationGrid::ForBounds(box.Min.data(), box.Max.data());

  std::vector<atp::PatchMesh> patches;
  for (std::size_t first = 0; first < soup.size(); first += TrianglesPerPatch)
  {
    patches.push_back(Weld(&soup[first], std::min(TrianglesPerPatch, soup.size() - first)));
  }
  std::vector<std::vector<std::uint8_t>> encoded;
  std::size_t encodedBytes = 0, triangles = 0, vertices = 0;
  const Clock::time_point encodeStart = Clock::now();
  for (const atp::PatchMesh& patch : patches)
  {
    encoded.push_back(atp::EncodePatch(patch, grid, {}, nullptr, order));
    encodedBytes += encoded.back().size();
  }
  const double encodeSeconds = Seconds(encodeStart);

  // Decoded once more outside the timing: counts, and the vertex cache figures of what the
  // renderer would draw, against strips made by meshopt's strip-oriented cache optimizer.
  atp::PatchMesh out;
  double listAcmr = 0, stripAcmr = 0;
  std::size_t stripIndices = 0;
  std::vector<std::uint32_t> strip, stripOrder;
  for (const std::vector<std::uint8_t>& bytes : encoded)
  {
    atp::DecodePatch(bytes.data(), bytes.size(), grid, out);
    triangles += out.TriangleCount();
    vertices += out.VertexCount();
    listAcmr += Acmr(out.Indices, out.VertexCount()) * out.TriangleCount();
    std::vector<std::uint32_t> reordered(out.Indices.size());
    meshopt_optimizeVertexCacheStrip(
      reordered.data(), out.Indices.data(), out.Indices.size(), out.VertexCount());
    strip.resize(meshopt_stripifyBound(reordered.size()));
    strip.resize(meshopt_stripify(
      strip.data(), reordered.data(), reordered.size(), out.VertexCount(), ~0u));
    stripIndices += strip.size();
    stripOrder.resize(meshopt_unstripifyBound(strip.size()));
    stripOrder.resize(meshopt_unstripify(stripOrder.data(), strip.data(), strip.size(), ~0u));
    stripAcmr += Acmr(stripOrder, out.VertexCount()) * out.TriangleCount();
  }
  const std::size_t outputBytes =
    vertices * 6 * sizeof(float) + triangles * 3 * sizeof(std::uint32_t);

  int rounds = 0;
  const Clock::time_point decodeStart = Clock::now();
  do
  {
    for (const std::vector<std::uint8_t>& bytes : encoded)
    {
      atp::DecodePatch(bytes.data(), bytes.size(), grid, out);
    }
    ++rounds;
  } while (Seconds(decodeStart) < minimumSeconds);
  const double decodeSeconds = Seconds(decodeStart) / rounds;

  std::uint64_t sum = 0;
  int checksumRounds = 0;
  const Clock::time_point checksumStart = Clock::now();
  do
  {
    for (const std::vector<std::uint8_t>& bytes : encoded)
    {
      sum ^= atp::Checksum(bytes.data(), bytes.size());
    }
    ++checksumRounds;
  } while (Seconds(checksumStart) < minimumSeconds);
  const double checksumSeconds = Seconds(checksumStart) / checksumRounds;

  const double mb = 1e6;
  std::printf("input: %s, %zu triangles, %zu patches (%zu triangles, %zu vertices decoded)\n",
    path.c_str(), soup.size(), patches.size(), triangles, vertices);
  std::printf("grid step %.3g (max error %.3g)\n", grid.Step, grid.MaxError());
  std::printf("encoded: %zu bytes, %.2f bytes/triangle, %.2f bytes/vertex; raw %.1fx larger\n",
    encodedBytes, double(encodedBytes) / triangles, double(encodedBytes) / vertices,
    double(outputBytes) / encodedBytes);
  std::printf("encode: %.1f M triangles/s (%s cache order)\n", triangles / encodeSeconds / 1e6,
    order == atp::CacheOrder::Fast ? "fast" : "best");
  std::printf("decode: %.0f MB/s encoded, %.0f MB/s output, %.1f M triangles/s (%d rounds)\n",
    encodedBytes / decodeSeconds / mb, outputBytes / decodeSeconds / mb,
    triangles / decodeSeconds / 1e6, rounds);
  std::printf("checksum: %.0f MB/s (%016llx)\n", encodedBytes / checksumSeconds / mb,
    static_cast<unsigned long long>(sum));
  std::printf("vertex cache %u: lists ACMR %.3f (3 indices/triangle); strips ACMR %.3f "
              "(%.2f indices/triangle)\n",
    CacheSize, listAcmr / triangles, stripAcmr / triangles, double(stripIndices) / triangles);
  return 0;
}
} // namespace

int main(int argc, char* argv[])
{
  const std::string path = argc > 1 ? argv[1] : "Data/bumpy-torus.ply";
  const double seconds = argc > 2 ? std::atof(argv[2]) : 2.0;
  const atp::CacheOrder order = argc > 3 && std::string(argv[3]) == "--fast-cache-order"
    ? atp::CacheOrder::Fast
    : atp::CacheOrder::Best;
  try
  {
    return Run(path, seconds, order);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "atp-bench-decode: %s\n", e.what());
    return 1;
  }
}
