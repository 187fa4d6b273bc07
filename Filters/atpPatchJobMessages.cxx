#include "atpPatchJobMessages.h"

#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace atp
{
namespace
{

/// The messages' version: one more whenever a message gains, loses or widens a field (the
/// sizes of the shipped types count themselves). 1: the first; 2: a result carries the
/// triangles over its quotas instead of a flag; 3: and the closed pieces removed; 4: and the
/// CPU time of its steps; 5: the context carries the cache order; 6: a result carries the
/// repeated triangles dropped; 7: and whether its triangles face either way at random; 8: a
/// mesh carries its input uses (PatchMesh::InputUses, CornerUses).
/// TestPatchJob pins a result message's size.
constexpr std::uint64_t MessageVersion = 8;
static_assert(sizeof(JobCpuSeconds) == 3 * sizeof(double),
  "a step added to JobCpuSeconds changes the result message: bump MessageVersion");

static_assert(MessageVersion < 256 && sizeof(SoupTriangle) < 256 && sizeof(Tetra) < 256 &&
    sizeof(Sphere) < 256 && sizeof(NormalCone) < 256,
  "each part of the layout signature has one byte");

/// Mismatched builds refuse each other when the context arrives, not with a short read in the
/// middle of a job: "ATP", the version, then the sizes of the shipped types, a byte each.
constexpr std::uint64_t LayoutSignature = (std::uint64_t(0x415450) << 40) | (MessageVersion << 32) |
  (sizeof(SoupTriangle) << 24) | (sizeof(Tetra) << 16) | (sizeof(Sphere) << 8) | sizeof(NormalCone);

class ByteWriter
{
public:
  explicit ByteWriter(std::vector<std::uint8_t>& out)
    : Out(out)
  {
    Out.clear();
  }

  template<typename T>
  void Put(const T& value)
  {
    static_assert(std::is_trivially_copyable<T>::value, "memory images only");
    Append(&value, sizeof(T));
  }

  template<typename T>
  void PutArray(const std::vector<T>& values)
  {
    static_assert(std::is_trivially_copyable<T>::value, "memory images only");
    Put(std::uint64_t(values.size()));
    Append(values.data(), values.size() * sizeof(T));
  }

  void PutMesh(const PatchMesh& mesh)
  {
    PutArray(mesh.Positions);
    PutArray(mesh.Normals);
    PutArray(mesh.Colors);
    PutArray(mesh.Indices);
    PutArray(mesh.BoundaryEdges);
    PutArray(mesh.InputUses);
    PutArray(mesh.CornerUses);
  }

private:
  /// Resized, then copied: vector::insert of a few bytes trips GCC 12's -Wstringop-overflow
  /// (a false positive) once inlined.
  void Append(const void* bytes, std::size_t count)
  {
    if (count == 0)
    {
      return;
    }
    const std::size_t at = Out.size();
    Out.resize(at + count);
    std::memcpy(Out.data() + at, bytes, count);
  }

  std::vector<std::uint8_t>& Out;
};

class ByteReader
{
public:
  ByteReader(const std::uint8_t* data, std::size_t bytes, const char* what)
    : Next(data)
    , End(data + bytes)
    , What(what)
  {
  }

  template<typename T>
  T Get()
  {
    T value;
    Take(&value, sizeof(T));
    return value;
  }

  template<typename T>
  void GetArray(std::vector<T>& values)
  {
    const auto count = Get<std::uint64_t>();
    if (count > std::uint64_t(End - Next) / sizeof(T))
    {
      Fail();
    }
    values.resize(std::size_t(count));
    Take(values.data(), values.size() * sizeof(T));
  }

  void GetMesh(PatchMesh& mesh)
  {
    GetArray(mesh.Positions);
    GetArray(mesh.Normals);
    GetArray(mesh.Colors);
    GetArray(mesh.Indices);
    GetArray(mesh.BoundaryEdges);
    GetArray(mesh.InputUses);
    GetArray(mesh.CornerUses);
    // Read per vertex and per corner wherever they are not empty.
    if (!mesh.UsesSized())
    {
      Fail();
    }
  }

  /// A count of things that each take at least `minimumBytes`: checked before allocating.
  std::size_t GetCount(std::size_t minimumBytes)
  {
    const auto count = Get<std::uint64_t>();
    if (count > std::uint64_t(End - Next) / minimumBytes)
    {
      Fail();
    }
    return std::size_t(count);
  }

  [[noreturn]] void Fail() const
  {
    throw std::runtime_error(std::string("malformed ") + What + " message");
  }

  void ExpectEnd() const
  {
    if (Next != End)
    {
      Fail();
    }
  }

private:
  void Take(void* out, std::size_t bytes)
  {
    if (bytes > std::size_t(End - Next))
    {
      Fail();
    }
    if (bytes > 0)
    {
      std::memcpy(out, Next, bytes);
    }
    Next += bytes;
  }

  const std::uint8_t* Next;
  const std::uint8_t* End;
  const char* What;
};

/// The five counts of an encoded mesh.
constexpr std::size_t MeshMinimumBytes = 7 * sizeof(std::uint64_t);

} // namespace

std::vector<std::uint8_t> EncodeContext(const PatchJobContext& context)
{
  std::vector<std::uint8_t> out;
  ByteWriter w(out);
  w.Put(LayoutSignature);
  w.Put(context.Bounds);
  w.Put(context.PatchBudget);
  w.Put(std::uint8_t(context.Colors));
  w.Put(std::uint8_t(context.Order));
  return out;
}

PatchJobContext DecodeContext(const std::uint8_t* data, std::size_t bytes)
{
  ByteReader r(data, bytes, "build context");
  if (r.Get<std::uint64_t>() != LayoutSignature)
  {
    throw std::runtime_error(
      "build context from a different atp build (every process must run the same atp)");
  }
  const auto bounds = r.Get<Box>();
  const auto budget = r.Get<std::uint32_t>();
  const auto colors = r.Get<std::uint8_t>();
  const auto order = r.Get<std::uint8_t>();
  r.ExpectEnd();
  if (order > std::uint8_t(CacheOrder::Fast))
  {
    r.Fail();
  }
  return PatchJobContext(bounds, budget, colors != 0, CacheOrder(order));
}

void EncodeJob(const PatchJob& job, std::vector<std::uint8_t>& out)
{
  ByteWriter w(out);
  w.PutArray(job.Soup);
  w.PutArray(job.Members);
  w.Put(std::uint64_t(job.Children.size()));
  for (const PatchMesh& child : job.Children)
  {
    w.PutMesh(child);
  }
  w.Put(job.ChildError);
}

void DecodeJob(const std::uint8_t* data, std::size_t bytes, PatchJob& out)
{
  ByteReader r(data, bytes, "job");
  r.GetArray(out.Soup);
  r.GetArray(out.Members);
  out.Children.resize(r.GetCount(MeshMinimumBytes));
  for (PatchMesh& child : out.Children)
  {
    r.GetMesh(child);
  }
  out.ChildError = r.Get<double>();
  r.ExpectEnd();
}

void EncodeResult(const PatchJobResult& result, std::vector<std::uint8_t>& out)
{
  ByteWriter w(out);
  w.Put(std::uint64_t(result.Patches.size()));
  for (const MadePatch& patch : result.Patches)
  {
    w.PutMesh(patch.Mesh);
    w.PutArray(patch.Encoded);
    w.Put(patch.Tight);
    w.Put(patch.Cone);
  }
  w.Put(result.Error);
  w.Put(result.Collapses);
  w.Put(result.TrianglesOverQuotas);
  w.Put(result.PiecesRemoved);
  w.Put(std::uint8_t(result.FacingAtRandom));
  w.Put(result.RepeatedTrianglesDropped);
  w.Put(result.Cpu);
}

void DecodeResult(const std::uint8_t* data, std::size_t bytes, PatchJobResult& out)
{
  ByteReader r(data, bytes, "result");
  out.Patches.resize(r.GetCount(MeshMinimumBytes + sizeof(std::uint64_t)));
  for (MadePatch& patch : out.Patches)
  {
    r.GetMesh(patch.Mesh);
    r.GetArray(patch.Encoded);
    patch.Tight = r.Get<Sphere>();
    patch.Cone = r.Get<NormalCone>();
  }
  out.Error = r.Get<double>();
  out.Collapses = r.Get<std::uint64_t>();
  out.TrianglesOverQuotas = r.Get<std::uint64_t>();
  out.PiecesRemoved = r.Get<std::uint64_t>();
  const auto facingAtRandom = r.Get<std::uint8_t>();
  out.FacingAtRandom = facingAtRandom != 0;
  out.RepeatedTrianglesDropped = r.Get<std::uint64_t>();
  out.Cpu = r.Get<JobCpuSeconds>();
  r.ExpectEnd();
  if (facingAtRandom > 1)
  {
    r.Fail();
  }
}

} // namespace atp
