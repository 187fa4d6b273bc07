#include "atpPatchCodec.h"

#include "atpNormalEncoding.h"
#include "atpNormalPrediction.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

namespace atp
{

namespace
{
// Bytes per vertex of each vertex stream (meshopt's vertex codec wants multiples of 4).
constexpr std::size_t PositionStride = 3 * sizeof(std::uint32_t);
constexpr std::size_t NormalStride = 2 * sizeof(std::int16_t);
constexpr std::size_t ColorStride = 4;
/// Normals are stored with NormalBits = 16 - NormalShift bits per octahedral coordinate.
constexpr int NormalShift = 16 - NormalBits;
/// Stored octahedral coordinates lie in [-StoredNormalScale, StoredNormalScale].
constexpr std::int32_t StoredNormalScale = 1 << (NormalBits - 1);
// meshopt's index codec: a header byte, at least one code byte per triangle, a 16-byte tail.
constexpr std::uint64_t IndexStreamOverhead = 17;
// meshopt's vertex codec spends at least 2 bits per 16 vertices on each byte of a vertex.
constexpr std::uint64_t MaxVerticesPerStreamByte = 64;

enum Stream
{
  IndexStream,
  PositionStream,
  NormalStream,
  ColorStream,
  StreamCount
};

// Byte offsets of the header fields after the version and flags bytes.
constexpr std::size_t VertexCountOffset = 2;
constexpr std::size_t TriangleCountOffset = 6;
constexpr std::size_t MinOffset = 10;
constexpr std::size_t BorderCountOffset = 22;
constexpr std::size_t InteriorShiftOffset = 26;
constexpr std::size_t StreamBytesOffset = 27;
static_assert(StreamBytesOffset + 4 * StreamCount == PatchHeaderBytes, "header layout");

/// The header fields, in the order of the layout in atpPatchCodec.h.
struct PatchHeader
{
  std::uint8_t Version;
  std::uint8_t Flags;
  std::uint32_t VertexCount;
  std::uint32_t TriangleCount;
  std::uint32_t Min[3];
  std::uint32_t BorderVertices;
  std::uint8_t InteriorShift;
  std::uint32_t StreamBytes[StreamCount];
};

void PutU32(std::uint8_t* p, std::uint32_t v)
{
  for (int i = 0; i < 4; ++i)
  {
    p[i] = static_cast<std::uint8_t>(v >> (8 * i));
  }
}

std::uint32_t GetU32(const std::uint8_t* p)
{
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
    std::uint32_t(p[3]) << 24;
}

void WriteHeader(const PatchHeader& h, std::uint8_t* p)
{
  p[0] = h.Version;
  p[1] = h.Flags;
  PutU32(p + VertexCountOffset, h.VertexCount);
  PutU32(p + TriangleCountOffset, h.TriangleCount);
  for (int a = 0; a < 3; ++a)
  {
    PutU32(p + MinOffset + 4 * a, h.Min[a]);
  }
  PutU32(p + BorderCountOffset, h.BorderVertices);
  p[InteriorShiftOffset] = h.InteriorShift;
  for (int s = 0; s < StreamCount; ++s)
  {
    PutU32(p + StreamBytesOffset + 4 * s, h.StreamBytes[s]);
  }
}

[[noreturn]] void Fail(const std::string& what)
{
  throw PatchFormatError("invalid patch encoding: " + what);
}

/// Parses and checks everything the header alone can tell, so the counts it returns are safe
/// to allocate for.
PatchHeader ReadHeader(const std::uint8_t* p, std::size_t bytes)
{
  if (!p || bytes < PatchHeaderBytes)
  {
    Fail(std::to_string(bytes) + " bytes is shorter than the header");
  }
  PatchHeader h;
  h.Version = p[0];
  h.Flags = p[1];
  h.VertexCount = GetU32(p + VertexCountOffset);
  h.TriangleCount = GetU32(p + TriangleCountOffset);
  for (int a = 0; a < 3; ++a)
  {
    h.Min[a] = GetU32(p + MinOffset + 4 * a);
  }
  h.BorderVertices = GetU32(p + BorderCountOffset);
  h.InteriorShift = p[InteriorShiftOffset];
  std::uint64_t streamTotal = 0;
  for (int s = 0; s < StreamCount; ++s)
  {
    h.StreamBytes[s] = GetU32(p + StreamBytesOffset + 4 * s);
    streamTotal += h.StreamBytes[s];
  }
  if (h.Version < OldestPatchFormatVersion || h.Version > PatchFormatVersion)
  {
    Fail("format version " + std::to_string(h.Version) + ", expected " +
      std::to_string(OldestPatchFormatVersion) + " to " + std::to_string(PatchFormatVersion));
  }
  if (h.Flags & ~PatchFlagColors)
  {
    Fail("unknown flags " + std::to_string(h.Flags));
  }
  if (streamTotal != bytes - PatchHeaderBytes)
  {
    Fail("stream sizes add up to " + std::to_string(streamTotal) + " bytes, the patch has " +
      std::to_string(bytes - PatchHeaderBytes) + " after the header");
  }
  if (h.VertexCount > MaxPatchVertices || h.TriangleCount > MaxPatchTriangles)
  {
    Fail(std::to_string(h.VertexCount) + " vertices and " + std::to_string(h.TriangleCount) +
      " triangles exceed the caps");
  }
  for (int a = 0; a < 3; ++a)
  {
    if (h.Min[a] > QuantizationGrid::MaxInteger)
    {
      Fail("patch minimum outside the quantization grid");
    }
  }
  if (h.BorderVertices > h.VertexCount || h.InteriorShift >= QuantizationGrid::Bits)
  {
    Fail(std::to_string(h.BorderVertices) + " border vertices of " +
      std::to_string(h.VertexCount) + ", interior shift " + std::to_string(h.InteriorShift));
  }
  if (h.VertexCount == 0 || h.TriangleCount == 0)
  {
    // The encoder drops unused vertices: no triangles means no vertices and no streams.
    if (h.VertexCount != 0 || h.TriangleCount != 0 || streamTotal != 0)
    {
      Fail("a patch without triangles must have no vertices and no streams");
    }
    return h;
  }
  if (h.StreamBytes[IndexStream] < IndexStreamOverhead ||
    h.TriangleCount > h.StreamBytes[IndexStream] - IndexStreamOverhead)
  {
    Fail(std::to_string(h.TriangleCount) + " triangles cannot fit in an index stream of " +
      std::to_string(h.StreamBytes[IndexStream]) + " bytes");
  }
  const std::size_t strides[StreamCount] = { 0, PositionStride, NormalStride,
    (h.Flags & PatchFlagColors) ? ColorStride : 0 };
  for (int s = PositionStream; s < StreamCount; ++s)
  {
    if (strides[s] == 0)
    {
      if (h.StreamBytes[s] != 0)
      {
        Fail("a color stream without the colors flag");
      }
    }
    else if (h.VertexCount > MaxVerticesPerStreamByte * h.StreamBytes[s] / strides[s])
    {
      Fail(std::to_string(h.VertexCount) + " vertices cannot fit in a vertex stream of " +
        std::to_string(h.StreamBytes[s]) + " bytes");
    }
  }
  return h;
}

template<typename T>
void EncodeVertices(std::vector<std::uint8_t>& out, std::uint32_t& streamBytes,
  const std::vector<T>& vertices, std::size_t stride)
{
  const std::size_t count = vertices.size() * sizeof(T) / stride;
  const std::size_t start = out.size();
  out.resize(start + meshopt_encodeVertexBufferBound(count, stride));
  const std::size_t written =
    meshopt_encodeVertexBuffer(out.data() + start, out.size() - start, vertices.data(), count, stride);
  out.resize(start + written);
  streamBytes = static_cast<std::uint32_t>(written);
}

void DecodeVertices(void* destination, std::size_t count, std::size_t stride,
  const std::uint8_t* stream, std::size_t streamBytes, const char* name)
{
  if (meshopt_decodeVertexBuffer(destination, count, stride, stream, streamBytes) != 0)
  {
    Fail(std::string("corrupt ") + name + " stream");
  }
}

void CheckMesh(const PatchMesh& mesh)
{
  const std::size_t vertices = mesh.VertexCount();
  if (mesh.Positions.size() % 3 != 0 || mesh.Normals.size() != mesh.Positions.size() ||
    (mesh.HasColors() && mesh.Colors.size() != 4 * vertices) || mesh.Indices.size() % 3 != 0 ||
    !mesh.UsesSized())
  {
    throw std::invalid_argument("EncodePatch: inconsistent array sizes");
  }
  if (vertices > MaxPatchVertices || mesh.TriangleCount() > MaxPatchTriangles)
  {
    throw std::invalid_argument("EncodePatch: patch over the vertex or triangle cap");
  }
  for (const std::uint32_t i : mesh.Indices)
  {
    if (i >= vertices)
    {
      throw std::invalid_argument("EncodePatch: index out of range");
    }
  }
}
/// Each directed edge a->b of a triangle list with its triangle, grouped by a (a counting
/// sort): the edges leaving a are End[e], Triangle[e] for e in [First[a], First[a + 1]), in
/// triangle order. Groups hold a vertex's few neighbours.
struct EdgesByStart
{
  EdgesByStart(const std::vector<std::uint32_t>& indices, std::size_t vertexCount)
    : First(vertexCount + 1, 0)
    , End(new std::uint32_t[indices.size()]) // every entry is written: no zeroing
    , Triangle(new std::uint32_t[indices.size()])
  {
    for (const std::uint32_t a : indices)
    {
      ++First[a + 1];
    }
    for (std::size_t v = 0; v < vertexCount; ++v)
    {
      First[v + 1] += First[v];
    }
    std::vector<std::uint32_t> fill(First.begin(), First.end() - 1);
    const auto put = [&](std::uint32_t a, std::uint32_t b, std::uint32_t t) {
      End[fill[a]] = b;
      Triangle[fill[a]++] = t;
    };
    for (std::size_t t = 0; t < indices.size() / 3; ++t)
    {
      const std::uint32_t* corners = &indices[3 * t];
      put(corners[0], corners[1], std::uint32_t(t));
      put(corners[1], corners[2], std::uint32_t(t));
      put(corners[2], corners[0], std::uint32_t(t));
    }
  }

  std::vector<std::uint32_t> First;
  std::unique_ptr<std::uint32_t[]> End, Triangle;
};

/// Per vertex: whether it lies on an edge used by exactly one triangle of the patch. Counted
/// around each vertex a, from its own edges only: every triangle at a uses the edges from a to
/// its two other corners once each, so a neighbor met once around a is across such an edge.
/// Nothing is looked up in a neighbor's edges (those searches, with branches no predictor
/// learns, took 3.7% of a build's CPU). A triangle's third corner is the XOR of its corners
/// with the edge's two ends, which holds for degenerate triangles too.
std::vector<std::uint8_t> BorderVertices(
  const EdgesByStart& edges, const std::vector<std::uint32_t>& indices, std::size_t vertexCount)
{
  struct Uses
  {
    std::uint32_t Around = ~0u; ///< the vertex the count is of
    std::uint32_t Count = 0;
  };
  std::vector<Uses> uses(vertexCount);
  std::vector<std::uint8_t> border(vertexCount, 0);
  const auto third = [&](std::uint32_t a, std::uint32_t e) {
    const std::uint32_t* corners = &indices[3 * std::size_t(edges.Triangle[e])];
    return corners[0] ^ corners[1] ^ corners[2] ^ a ^ edges.End[e];
  };
  for (std::uint32_t a = 0; a < vertexCount; ++a)
  {
    const std::uint32_t first = edges.First[a], last = edges.First[a + 1];
    for (std::uint32_t e = first; e < last; ++e)
    {
      for (const std::uint32_t x : { edges.End[e], third(a, e) })
      {
        // Without a branch: a neighbor is met once or twice in no order a predictor learns.
        const std::uint32_t keep = 0u - std::uint32_t(uses[x].Around == a);
        uses[x].Count = (uses[x].Count & keep) + 1;
        uses[x].Around = a;
      }
    }
    bool once = false;
    for (std::uint32_t e = first; e < last; ++e)
    {
      const std::uint32_t b = edges.End[e], c = third(a, e);
      once |= (b != a && uses[b].Count == 1) | (c != a && uses[c].Count == 1);
    }
    border[a] = once;
  }
  return border;
}

/// Rounds to the nearest multiple of 2^shift that stays within [0, limit].
std::uint32_t RoundToMultiple(std::uint32_t value, int shift, std::uint32_t limit)
{
  if (shift == 0)
  {
    return value;
  }
  const std::uint64_t step = std::uint64_t(1) << shift;
  std::uint64_t rounded = (std::uint64_t(value) + step / 2) & ~(step - 1);
  while (rounded > limit)
  {
    rounded -= step;
  }
  return static_cast<std::uint32_t>(rounded);
}

/// An octahedral coordinate (EncodeNormal's 16 bits) on the stream's coarser scale, rounded
/// half away from zero: -1024..1024.
std::int16_t StoredNormal(std::int16_t value)
{
  constexpr int half = 1 << (NormalShift - 1);
  const int magnitude = (std::abs(int(value)) + half) >> NormalShift;
  return static_cast<std::int16_t>(value < 0 ? -magnitude : magnitude);
}

/// Back to EncodeNormal's scale (1024 << 5 is one past 32767: DecodeNormal's range ends there).
std::int16_t UnstoredNormal(std::int16_t stored)
{
  const int value = int(stored) * (1 << NormalShift);
  return static_cast<std::int16_t>(std::min(32767, std::max(-32767, value)));
}
/// Parallelogram prediction (Touma and Gotsman 1998), the walk encoder and decoder share:
/// triangles in order; a vertex at its first use is predicted from vertices already visited:
/// across the edge it faces, from the triangle on the other side if that one came earlier
/// (a + b - c), else from a visited corner of its triangle, else from the last vertex visited
/// (`start` for the first). visit(v, prediction) must set q[v] (the encoder's are already
/// there); it returns false to stop the walk. Returns whether every vertex was visited.
/// `edges` holds the edges of these triangles in this order, its vertex of v being
/// tableVertex(v): the encoder walks with the table it found the border vertices with, built
/// before the vertices were renumbered (corners the index codec rotated keep their edges).
template<typename TableVertex, typename Visit>
bool PredictionWalk(const std::vector<std::uint32_t>& indices, std::size_t vertexCount,
  const EdgesByStart& edges, const TableVertex& tableVertex, const std::uint32_t start[3],
  std::vector<std::int64_t>& q, const Visit& visit)
{
  const std::size_t triangles = indices.size() / 3;
  std::vector<char> visited(vertexCount, 0);
  std::size_t visitedCount = 0;
  std::int64_t last[3] = { start[0], start[1], start[2] };
  for (std::size_t t = 0; t < triangles; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t v = indices[3 * t + k];
      if (visited[v])
      {
        continue;
      }
      const std::uint32_t a = indices[3 * t + (k + 1) % 3], b = indices[3 * t + (k + 2) % 3];
      std::int64_t prediction[3] = { last[0], last[1], last[2] };
      std::uint32_t across = ~0u;
      if (visited[a] && visited[b])
      {
        const std::uint32_t tableA = tableVertex(a), tableB = tableVertex(b);
        const std::uint32_t groupEnd = edges.First[tableB + 1];
        for (std::uint32_t e = edges.First[tableB]; e < groupEnd && across == ~0u; ++e)
        {
          across = edges.End[e] == tableA && edges.Triangle[e] < t ? edges.Triangle[e] : ~0u;
        }
      }
      if (across != ~0u)
      {
        const std::uint32_t* s = &indices[3 * std::size_t(across)];
        const std::uint32_t c = s[0] != a && s[0] != b ? s[0] : (s[1] != a && s[1] != b ? s[1] : s[2]);
        for (int x = 0; x < 3; ++x)
        {
          prediction[x] = q[3 * a + x] + q[3 * b + x] - q[3 * c + x];
        }
      }
      else if (visited[a] || visited[b])
      {
        const std::uint32_t known = visited[a] ? a : b;
        for (int x = 0; x < 3; ++x)
        {
          prediction[x] = q[3 * known + x];
        }
      }
      if (!visit(v, prediction))
      {
        return false;
      }
      visited[v] = 1;
      ++visitedCount;
      for (int x = 0; x < 3; ++x)
      {
        last[x] = q[3 * v + x];
      }
    }
  }
  return visitedCount == vertexCount;
}

/// The prediction on an interior vertex's coarser grid: the nearest multiple of 2^shift (the
/// right shift floors negative predictions too; multiplying back avoids shifting them left).
inline std::int64_t RoundPrediction(std::int64_t prediction, int shift)
{
  return shift == 0
    ? prediction
    : ((prediction + (std::int64_t(1) << (shift - 1))) >> shift) * (std::int64_t(1) << shift);
}

// Without a branch on the sign: residuals' signs follow no pattern (they were a tenth of the
// encoder's mispredicted branches).
inline std::uint32_t ZigZag(std::int64_t value)
{
  const std::uint64_t bits = std::uint64_t(value);
  return std::uint32_t((bits << 1) ^ (0 - (bits >> 63)));
}

inline std::int64_t UnZigZag(std::uint32_t value)
{
  return std::int64_t(value >> 1) ^ -std::int64_t(value & 1);
}

// Byte-wise arithmetic on the 8 bytes of a word (SIMD within a register): no carry, borrow or
// shifted bit crosses from one byte into the next.
constexpr std::uint64_t HighBits = 0x8080808080808080ull, LowBits = 0x0101010101010101ull;

inline std::uint64_t AddBytes(std::uint64_t a, std::uint64_t b)
{
  return ((a & ~HighBits) + (b & ~HighBits)) ^ ((a ^ b) & HighBits);
}

inline std::uint64_t SubtractBytes(std::uint64_t a, std::uint64_t b)
{
  return ((a | HighBits) - (b & ~HighBits)) ^ ((a ^ ~b) & HighBits);
}

/// Each byte's 8-bit zigzag code: (d << 1) ^ -(d >> 7).
inline std::uint64_t ZigZagBytes(std::uint64_t d)
{
  return ((d << 1) & ~LowBits) ^ (((d >> 7) & LowBits) * 0xFF);
}

/// Each byte decoded from its 8-bit zigzag code: (z >> 1) ^ -(z & 1).
inline std::uint64_t UnZigZagBytes(std::uint64_t z)
{
  return ((z >> 1) & ~HighBits) ^ ((z & LowBits) * 0xFF);
}

/// meshopt's vertex codec stores each byte of a vertex as the zigzag-coded difference from the
/// same byte of the vertex before. Residuals of a prediction are already small and independent;
/// differencing them again would double their spread. Storing each byte lane's running sum
/// instead makes the differences the codec takes exactly the residual bytes.
template<std::size_t Stride>
void SumByteLanes(std::uint8_t* data, std::size_t count)
{
  static_assert(Stride % 4 == 0, "records of whole 4-byte words");
  constexpr std::size_t Words = (Stride + 7) / 8; // the last one half used when Stride % 8 = 4
  std::uint64_t sum[Words] = {};
  for (std::size_t i = 0; i < count; ++i, data += Stride)
  {
    for (std::size_t w = 0; w < Words; ++w)
    {
      const std::size_t bytes = std::min<std::size_t>(8, Stride - 8 * w);
      std::uint64_t residuals = 0;
      std::memcpy(&residuals, data + 8 * w, bytes);
      sum[w] = AddBytes(sum[w], UnZigZagBytes(residuals));
      std::memcpy(data + 8 * w, &sum[w], bytes);
    }
  }
}

/// Undoes SumByteLanes: each byte becomes the zigzag code of its difference from the byte
/// Stride places before it. Eight bytes at a time from the end back, so every byte still reads
/// an unchanged predecessor.
template<std::size_t Stride>
void DifferenceByteLanes(std::uint8_t* data, std::size_t count)
{
  std::size_t end = count * Stride;
  for (; end >= Stride + 8; end -= 8)
  {
    std::uint64_t a, b;
    std::memcpy(&a, data + end - 8, 8);
    std::memcpy(&b, data + end - 8 - Stride, 8);
    const std::uint64_t z = ZigZagBytes(SubtractBytes(a, b));
    std::memcpy(data + end - 8, &z, 8);
  }
  for (std::size_t j = end; j-- > 0;)
  {
    const std::uint64_t z = ZigZagBytes(SubtractBytes(data[j], j >= Stride ? data[j - Stride] : 0));
    data[j] = std::uint8_t(z);
  }
}

/// The most triangles around one vertex (a triangle with a repeated corner counts twice there).
std::uint32_t LargestValence(const std::vector<std::uint32_t>& indices, std::size_t vertexCount)
{
  std::vector<std::uint32_t> valence(vertexCount, 0);
  std::uint32_t largest = 0;
  for (const std::uint32_t v : indices)
  {
    largest = std::max(largest, ++valence[v]);
  }
  return largest;
}
} // namespace

double PatchPrecision::PositionError(const QuantizationGrid& grid) const
{
  // Half a coarse step per axis; the grid's own rounding is the same for every patch.
  return InteriorPositionShift == 0
    ? 0
    : std::sqrt(3.0) * std::ldexp(grid.Step, InteriorPositionShift - 1);
}

std::vector<std::uint8_t> EncodePatch(const PatchMesh& mesh, const QuantizationGrid& grid,
  const PatchPrecision& precision, PatchMesh* decoded, CacheOrder order)
{
  CheckMesh(mesh);
  if (precision.InteriorPositionShift < 0 || precision.InteriorPositionShift >= QuantizationGrid::Bits)
  {
    throw std::invalid_argument("EncodePatch: precision out of range");
  }
  PatchHeader header{};
  header.Version = PatchFormatVersion;
  header.Flags = mesh.HasColors() ? PatchFlagColors : 0;
  std::vector<std::uint8_t> out(PatchHeaderBytes);
  const std::size_t indexCount = mesh.Indices.size();
  if (indexCount == 0)
  {
    WriteHeader(header, out.data());
    if (decoded)
    {
      *decoded = PatchMesh();
    }
    return out;
  }

  // Indexed triangle lists, not strips: GPUs shade a vertex once per post-transform cache miss,
  // and atp-bench-decode measures 0.70 misses per triangle for these lists against 0.88 for
  // strips from meshopt's strip-oriented order (cache of 16). Strips only save index bandwidth
  // (1.4 instead of 3 indices per triangle), which is not what limits drawing, and on disk the
  // index codec already stores lists in ~1.2 bytes per triangle.
  const std::size_t vertexCount = mesh.VertexCount();
  std::vector<std::uint32_t> indices(indexCount);
  if (order == CacheOrder::Fast || LargestValence(mesh.Indices, vertexCount) > MaxBestOrderValence)
  {
    meshopt_optimizeVertexCacheFifo(
      indices.data(), mesh.Indices.data(), indexCount, vertexCount, 16);
  }
  else
  {
    meshopt_optimizeVertexCache(indices.data(), mesh.Indices.data(), indexCount, vertexCount);
  }
  std::vector<std::uint32_t> remap(vertexCount);
  const std::size_t used =
    meshopt_optimizeVertexFetchRemap(remap.data(), indices.data(), indexCount, vertexCount);
  // Border vertices first, each group in fetch order: the interior's zeroed low bits then form
  // long runs the vertex codec stores in almost nothing.
  const EdgesByStart edges(indices, vertexCount);
  std::vector<std::uint8_t> border = BorderVertices(edges, indices, vertexCount);
  // A vertex on an edge of four or more sheets, split between this patch and another
  // (PatchMesh::UsedElsewhere), is shared as well.
  const std::vector<std::uint8_t> elsewhere = VerticesUsedElsewhere(mesh);
  for (std::size_t v = 0; v < elsewhere.size(); ++v)
  {
    border[v] |= elsewhere[v];
  }
  // An input edge of three or more triangles may look inner here, with two of its triangles in
  // this patch, while another patch holds a third: its ends are shared, so stored exactly.
  for (std::size_t t = 0; t < mesh.BoundaryEdges.size() && t < mesh.TriangleCount(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      if (mesh.BoundaryEdges[t] & (8u << k))
      {
        border[mesh.Indices[3 * t + std::size_t(k)]] = 1;
        border[mesh.Indices[3 * t + std::size_t(k + 1) % 3]] = 1;
      }
    }
  }
  std::vector<std::uint32_t> byFetch(used);
  for (std::size_t v = 0; v < vertexCount; ++v)
  {
    if (remap[v] != ~0u)
    {
      byFetch[remap[v]] = std::uint32_t(v);
    }
  }
  std::uint32_t next = 0;
  std::vector<std::uint32_t> numberedFrom(used); // per final number: the vertex in the edge table
  for (const bool borderFirst : { true, false })
  {
    for (const std::uint32_t v : byFetch)
    {
      if (bool(border[v]) == borderFirst)
      {
        numberedFrom[next] = v;
        remap[v] = next++;
      }
    }
  }
  meshopt_remapIndexBuffer(indices.data(), indices.data(), indexCount, remap.data());

  std::vector<std::uint32_t> positions(3 * used);
  std::vector<std::int16_t> normals(2 * used);
  std::vector<std::uint8_t> colors(mesh.HasColors() ? 4 * used : 0);
  std::fill(header.Min, header.Min + 3, QuantizationGrid::MaxInteger);
  for (std::size_t v = 0; v < vertexCount; ++v)
  {
    const std::uint32_t to = remap[v];
    if (to == ~0u)
    {
      continue;
    }
    const std::array<std::uint32_t, 3> q = grid.Quantize(&mesh.Positions[3 * v]);
    const int positionShift = border[v] ? 0 : precision.InteriorPositionShift;
    for (int a = 0; a < 3; ++a)
    {
      positions[3 * to + a] = RoundToMultiple(q[a], positionShift, QuantizationGrid::MaxInteger);
      header.Min[a] = std::min(header.Min[a], positions[3 * to + a]);
    }
    EncodeNormal(&mesh.Normals[3 * v], &normals[2 * to]);
    for (int k = 0; k < 2; ++k)
    {
      normals[2 * to + k] = StoredNormal(normals[2 * to + k]);
    }
    if (mesh.HasColors())
    {
      std::copy_n(&mesh.Colors[4 * v], 4, &colors[4 * to]);
    }
  }
  header.BorderVertices = 0;
  for (std::size_t v = 0; v < vertexCount; ++v)
  {
    header.BorderVertices += remap[v] != ~0u && border[v];
  }
  header.InteriorShift = static_cast<std::uint8_t>(precision.InteriorPositionShift);
  header.VertexCount = static_cast<std::uint32_t>(used);
  header.TriangleCount = static_cast<std::uint32_t>(indexCount / 3);
  // Version 1 of meshopt's index codec (decoded by 0.14 and later) also codes the third
  // index of a triangle against the one before: smaller streams than the library's default 0.
  static const bool indexVersion1 = (meshopt_encodeIndexVersion(1), true);
  (void)indexVersion1;
  out.resize(PatchHeaderBytes + meshopt_encodeIndexBufferBound(indexCount, used));
  const std::size_t indexBytes = meshopt_encodeIndexBuffer(
    out.data() + PatchHeaderBytes, out.size() - PatchHeaderBytes, indices.data(), indexCount);
  out.resize(PatchHeaderBytes + indexBytes);
  header.StreamBytes[IndexStream] = static_cast<std::uint32_t>(indexBytes);
  // The index codec may rotate a triangle's corners: the prediction walks the triangles as the
  // decoder will see them.
  meshopt_decodeIndexBuffer(indices.data(), indexCount, sizeof(std::uint32_t),
    out.data() + PatchHeaderBytes, indexBytes);
  // Positions become residuals of their prediction; interior ones count coarse steps.
  std::vector<std::int64_t> q(positions.begin(), positions.end());
  const auto tableVertex = [&](std::uint32_t v) { return numberedFrom[v]; };
  PredictionWalk(indices, used, edges, tableVertex, header.Min, q,
    [&](std::uint32_t v, const std::int64_t* prediction) {
      const int shift = v < header.BorderVertices ? 0 : header.InteriorShift;
      for (int a = 0; a < 3; ++a)
      {
        positions[3 * v + a] =
          ZigZag((q[3 * v + a] - RoundPrediction(prediction[a], shift)) >> shift);
      }
      return true;
    });
  SumByteLanes<PositionStride>(reinterpret_cast<std::uint8_t*>(positions.data()), used);
  // Normals become residuals of their prediction from the (decoded) geometry.
  std::vector<std::int32_t> predicted(2 * used);
  PredictNormals(indices, q.data(), used, StoredNormalScale, predicted.data());
  std::vector<std::uint16_t> normalResiduals(2 * used);
  for (std::size_t i = 0; i < 2 * used; ++i)
  {
    normalResiduals[i] = static_cast<std::uint16_t>(ZigZag(normals[i] - predicted[i]));
  }
  SumByteLanes<NormalStride>(reinterpret_cast<std::uint8_t*>(normalResiduals.data()), used);

  EncodeVertices(out, header.StreamBytes[PositionStream], positions, PositionStride);
  EncodeVertices(out, header.StreamBytes[NormalStream], normalResiduals, NormalStride);
  if (mesh.HasColors())
  {
    EncodeVertices(out, header.StreamBytes[ColorStream], colors, ColorStride);
  }
  WriteHeader(header, out.data());
  if (decoded)
  {
    // What DecodePatch gives back, from the values encoded rather than from the bytes.
    decoded->BoundaryEdges.clear();
    decoded->Indices = std::move(indices);
    decoded->Positions.resize(3 * used);
    decoded->Normals.resize(3 * used);
    for (std::size_t v = 0; v < used; ++v)
    {
      const std::uint32_t point[3] = { std::uint32_t(q[3 * v]), std::uint32_t(q[3 * v + 1]),
        std::uint32_t(q[3 * v + 2]) };
      grid.Dequantize(point, &decoded->Positions[3 * v]);
      const std::int16_t octahedral[2] = { UnstoredNormal(normals[2 * v]),
        UnstoredNormal(normals[2 * v + 1]) };
      DecodeNormal(octahedral, &decoded->Normals[3 * v]);
    }
    decoded->Colors = std::move(colors);
  }
  return out;
}

void DecodePatch(
  const std::uint8_t* data, std::size_t bytes, const QuantizationGrid& grid, PatchMesh& out)
{
  const PatchHeader h = ReadHeader(data, bytes);
  const std::size_t vertexCount = h.VertexCount;
  // Format 3 stored normals as they are, and both vertex streams without byte lanes.
  const bool residualLanes = h.Version >= 4;
  const std::uint8_t* streams[StreamCount];
  streams[IndexStream] = data + PatchHeaderBytes;
  for (int s = 1; s < StreamCount; ++s)
  {
    streams[s] = streams[s - 1] + h.StreamBytes[s - 1];
  }
  out.BoundaryEdges.clear();

  out.Indices.resize(3 * std::size_t(h.TriangleCount));
  if (h.TriangleCount > 0 &&
    meshopt_decodeIndexBuffer(out.Indices.data(), out.Indices.size(), sizeof(std::uint32_t),
      streams[IndexStream], h.StreamBytes[IndexStream]) != 0)
  {
    Fail("corrupt index stream");
  }
  std::uint32_t largestIndex = 0;
  for (const std::uint32_t i : out.Indices)
  {
    largestIndex = std::max(largestIndex, i);
  }
  if (!out.Indices.empty() && largestIndex >= vertexCount)
  {
    Fail("index " + std::to_string(largestIndex) + " out of range for " +
      std::to_string(vertexCount) + " vertices");
  }

  // Residuals decode in place (3 x u32 per vertex, the size of 3 floats); the walk rebuilds the
  // grid points from them, which then become floats in place.
  out.Positions.resize(3 * vertexCount);
  if (vertexCount > 0)
  {
    DecodeVertices(out.Positions.data(), vertexCount, PositionStride, streams[PositionStream],
      h.StreamBytes[PositionStream], "position");
    if (residualLanes)
    {
      DifferenceByteLanes<PositionStride>(reinterpret_cast<std::uint8_t*>(out.Positions.data()), vertexCount);
    }
  }
  std::vector<std::int64_t> q(3 * vertexCount);
  const auto sameVertex = [](std::uint32_t v) { return v; };
  const bool inside = PredictionWalk(out.Indices, vertexCount,
    EdgesByStart(out.Indices, vertexCount), sameVertex, h.Min, q,
    [&](std::uint32_t v, const std::int64_t* prediction) {
      const int shift = v < h.BorderVertices ? 0 : h.InteriorShift;
      std::uint32_t residual[3];
      std::memcpy(residual, &out.Positions[3 * std::size_t(v)], sizeof(residual));
      for (int a = 0; a < 3; ++a)
      {
        const std::int64_t value = RoundPrediction(prediction[a], shift) +
          UnZigZag(residual[a]) * (std::int64_t(1) << shift);
        if (value < 0 || value > std::int64_t(QuantizationGrid::MaxInteger))
        {
          return false;
        }
        q[3 * v + a] = value;
      }
      return true;
    });
  if (!inside)
  {
    Fail("position outside the quantization grid, or a vertex no triangle uses");
  }
  for (std::size_t v = 0; v < vertexCount; ++v)
  {
    const std::uint32_t grid3[3] = { std::uint32_t(q[3 * v]), std::uint32_t(q[3 * v + 1]),
      std::uint32_t(q[3 * v + 2]) };
    grid.Dequantize(grid3, &out.Positions[3 * v]);
  }

  // Normals decode into the last third of their own array (4 of the 12 bytes per vertex) and
  // expand forward: normal v is written to bytes [12v, 12v + 12), never past the encoded bytes
  // of normals after v, which start at 8n + 4(v + 1) >= 12v + 12. No scratch buffer needed.
  out.Normals.resize(3 * vertexCount);
  std::uint8_t* packed = reinterpret_cast<std::uint8_t*>(out.Normals.data()) + 8 * vertexCount;
  if (vertexCount > 0)
  {
    DecodeVertices(packed, vertexCount, NormalStride, streams[NormalStream],
      h.StreamBytes[NormalStream], "normal");
    if (residualLanes)
    {
      DifferenceByteLanes<NormalStride>(packed, vertexCount);
    }
  }
  std::vector<std::int32_t> predicted(2 * vertexCount, 0);
  if (residualLanes)
  {
    PredictNormals(out.Indices, q.data(), vertexCount, StoredNormalScale, predicted.data());
  }
  for (std::size_t v = 0; v < vertexCount; ++v)
  {
    std::uint16_t residual[2];
    std::int16_t value[2];
    std::memcpy(residual, packed + NormalStride * v, sizeof(residual));
    std::memcpy(value, packed + NormalStride * v, sizeof(value));
    std::int16_t octahedral[2];
    for (int k = 0; k < 2; ++k)
    {
      const std::int64_t stored =
        residualLanes ? predicted[2 * v + k] + UnZigZag(residual[k]) : std::int64_t(value[k]);
      if (stored < -StoredNormalScale || stored > StoredNormalScale)
      {
        Fail("normal outside the octahedral square");
      }
      octahedral[k] = UnstoredNormal(static_cast<std::int16_t>(stored));
    }
    DecodeNormal(octahedral, &out.Normals[3 * v]);
  }

  const bool colors = (h.Flags & PatchFlagColors) && vertexCount > 0;
  out.Colors.resize(colors ? 4 * vertexCount : 0);
  if (colors)
  {
    DecodeVertices(out.Colors.data(), vertexCount, ColorStride, streams[ColorStream],
      h.StreamBytes[ColorStream], "color");
  }
}

} // namespace atp
