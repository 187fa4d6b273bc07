#include "atpMeshTriangleSource.h"

#include "atpNormalEncoding.h"
#include "atpProduceConsume.h"
#include "atpResidentPages.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace atp
{
namespace
{
/// Whether a * b == c * d exactly: fma recovers each product's rounding error, and the error is
/// only computed (a slow call without hardware fma) when the rounded products are equal.
bool ExactProductsEqual(double a, double b, double c, double d)
{
  const double p = a * b;
  const double q = c * d;
  return p == q && std::fma(a, b, -p) == std::fma(c, d, -q);
}

/// Whether the cross product of the float edges is exactly zero. Differences of floats are exact
/// in double unless the coordinates differ in magnitude by more than 2^29, and products of such
/// doubles neither overflow nor lose their rounding error to underflow.
bool HasZeroArea(const float v[3][3])
{
  double e[3], f[3];
  for (int a = 0; a < 3; ++a)
  {
    e[a] = double(v[1][a]) - double(v[0][a]);
    f[a] = double(v[2][a]) - double(v[0][a]);
  }
  return ExactProductsEqual(e[1], f[2], e[2], f[1]) && ExactProductsEqual(e[2], f[0], e[0], f[2]) &&
    ExactProductsEqual(e[0], f[1], e[1], f[0]);
}

/// Twice the area times the unit normal: summing these weights each face by its area.
std::array<double, 3> AreaNormal(const float v[3][3])
{
  double e[3], f[3];
  for (int a = 0; a < 3; ++a)
  {
    e[a] = double(v[1][a]) - double(v[0][a]);
    f[a] = double(v[2][a]) - double(v[0][a]);
  }
  return { { e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0] } };
}

/// Vertices scanned, or triangles visited, between releases of resident pages.
constexpr std::uint64_t ReleaseInterval = std::uint64_t(1) << 22;

/// Kept triangles of the first pass and their corners' positions.
struct FirstPassBatch
{
  static constexpr std::size_t Capacity = 1 << 16;
  struct Corners
  {
    float V[3][3];
  };
  std::vector<std::array<std::uint32_t, 3>> Triangles;
  std::vector<Corners> Positions;
};

} // namespace

MeshTriangleSource::MeshTriangleSource(
  std::unique_ptr<PolygonMesh> mesh, const std::string& path, const std::string& scratchDirectory)
  : Path(path)
  , Mesh(std::move(mesh))
  , Vertices(this->Mesh->Vertices())
  , Sketch(this->Vertices.Count, scratchDirectory)
  , NormalSums(scratchDirectory, this->Vertices.Count)
  , InputUses(scratchDirectory, this->Vertices.Count)
{
  this->CheckVerticesAndBound();
  if (!this->VertexBounds.IsEmpty()) // without vertices no triangle is kept: the mesh is empty
  {
    this->Grid = QuantizationGrid::ForBounds(this->VertexBounds.Min.data(), this->VertexBounds.Max.data());
  }
  this->FirstPass();
  if (!this->UsedBounds.IsEmpty() && this->UsedBounds != this->VertexBounds)
  {
    // Vertices no face uses lie outside the faces' box (a stray point of a scan, what a clip
    // left behind): the model's box, and the grid its precision comes from, are the faces'.
    // Which triangles the grid leaves an area decides what the first pass kept: again.
    this->VertexBounds = this->UsedBounds;
    this->Grid = QuantizationGrid::ForBounds(this->VertexBounds.Min.data(), this->VertexBounds.Max.data());
    this->Sketch.Clear();
    this->NormalSums.Assign(this->Vertices.Count, { { 0, 0, 0 } });
    this->InputUses.Assign(this->Vertices.Count, 0);
    this->Statistics.FacesRead = 0;
    this->Statistics.DegenerateDropped = 0;
    this->KeptTriangles = 0;
    this->FirstPass();
  }
  if (this->KeptTriangles == 0)
  {
    // Coordinates far larger than the mesh's detail are the usual cause: say what precision
    // the model keeps.
    char precision[160];
    std::snprintf(precision, sizeof(precision),
      "; coordinates are kept as 32-bit floats on a grid of step %g, the float spacing at the "
      "largest coordinate", this->Grid.Step);
    throw InputError(this->Path + ": empty mesh (no triangles: " +
      (this->Statistics.FacesRead == 0
          ? std::string("it has no faces")
          : "all " + std::to_string(this->Statistics.DegenerateDropped) + " are degenerate" + precision) +
      ")");
  }
  this->CollectOpenEdgeEnds();
}

void MeshTriangleSource::CheckVerticesAndBound()
{
  this->Statistics.VerticesRead = this->Vertices.Count;
  this->Statistics.HasColors = this->Vertices.HasColors();
  // The scan reads the whole vertex array once: it lets go of what it has read as it goes, or
  // all of it would stay resident (648 MiB for the 108M-triangle torus, the build's peak).
  for (std::uint64_t i = 0; i < this->Vertices.Count; ++i)
  {
    if (i % ReleaseInterval == 0 && i > 0)
    {
      this->ReleaseVertexPages(i - ReleaseInterval, ReleaseInterval);
    }
    float p[3];
    this->Vertices.Get(static_cast<std::uint32_t>(i), p);
    if (const char* bad = FirstNonFinite(p))
    {
      throw InputError(this->Path + ": vertex " + std::to_string(i) +
        " has a non-finite coordinate (" + bad + ")");
    }
    this->VertexBounds.Add(p);
  }
}

void MeshTriangleSource::ReleaseVertexPages(std::uint64_t first, std::uint64_t count) const
{
  if (this->Vertices.FileBacked)
  {
    ReleaseResidentPages(this->Vertices.Base + first * this->Vertices.Stride, count * this->Vertices.Stride);
  }
}

bool MeshTriangleSource::GetCorners(const std::uint32_t triangle[3], float corners[3][3]) const
{
  if (triangle[0] == triangle[1] || triangle[1] == triangle[2] || triangle[2] == triangle[0])
  {
    return false;
  }
  for (int c = 0; c < 3; ++c)
  {
    this->Vertices.Get(triangle[c], corners[c]);
    for (int a = 0; a < 3; ++a)
    {
      corners[c][a] += 0.0f; // -0 becomes +0: one point, one bit pattern for welding
    }
  }
  return true;
}

bool MeshTriangleSource::HasArea(const float corners[3][3]) const
{
  return !HasZeroArea(corners) && !this->VanishesOnTheGrid(corners);
}

bool MeshTriangleSource::VanishesOnTheGrid(const float corners[3][3]) const
{
  // Rounding to the grid moves each corner by at most (sqrt(3)/2) step, which changes twice the
  // area, |e x f|, by at most about 1.74 step (|e| + |f|) + 3.1 step^2, whose square is below
  // 16 step^2 (|e|^2 + |f|^2) + 32 step^4: a triangle with more keeps an area, and nearly every
  // one has far more.
  double e[3], f[3];
  for (int a = 0; a < 3; ++a)
  {
    e[a] = double(corners[1][a]) - double(corners[0][a]);
    f[a] = double(corners[2][a]) - double(corners[0][a]);
  }
  const double cross[3] = { e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0] };
  const double step2 = this->Grid.Step * this->Grid.Step;
  const double edges2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + f[0] * f[0] + f[1] * f[1] + f[2] * f[2];
  if (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2] > 16 * step2 * edges2 + 32 * step2 * step2)
  {
    return false;
  }
  float onGrid[3][3];
  std::memcpy(onGrid, corners, sizeof(onGrid));
  for (float* corner : onGrid)
  {
    this->Grid.Snap(corner);
  }
  return HasZeroArea(onGrid);
}

void MeshTriangleSource::FirstPass()
{
  // One thread reads the faces and fetches their corners while this one weighs their normals
  // and adds them to the sketch and the normal sums, in face order: the sums come out bit for
  // bit as one thread's. The reading thread is the busier of the two.
  bool facesLeft = true;
  ProduceConsume<FirstPassBatch>(
    3,
    [&](FirstPassBatch& batch) {
      batch.Triangles.clear();
      batch.Positions.clear();
      std::uint32_t triangle[3];
      float corners[3][3];
      while (batch.Triangles.size() < FirstPassBatch::Capacity)
      {
        if (!this->Triangles.Next(triangle))
        {
          PolygonBatch polygons;
          facesLeft = facesLeft && this->Mesh->NextBatch(polygons);
          if (!facesLeft)
          {
            break;
          }
          this->Statistics.FacesRead += polygons.Count;
          for (std::size_t k = 0; k < polygons.Count; ++k)
          {
            this->Statistics.DegenerateDropped += polygons.Sizes[k] < 3;
          }
          this->Triangles.Reset(polygons);
          continue;
        }
        this->BoundResidentMemory();
        if (!this->GetCorners(triangle, corners))
        {
          ++this->Statistics.DegenerateDropped;
          continue;
        }
        for (const float* corner : corners)
        {
          this->UsedBounds.Add(corner);
        }
        if (!this->HasArea(corners))
        {
          ++this->Statistics.DegenerateDropped;
          continue;
        }
        batch.Triangles.push_back({ { triangle[0], triangle[1], triangle[2] } });
        batch.Positions.emplace_back();
        std::memcpy(batch.Positions.back().V, corners, sizeof(corners));
      }
      this->KeptTriangles += batch.Triangles.size();
      return !batch.Triangles.empty();
    },
    [&](const FirstPassBatch& batch) {
      for (std::size_t i = 0; i < batch.Triangles.size(); ++i)
      {
        const std::array<std::uint32_t, 3>& triangle = batch.Triangles[i];
        this->Sketch.AddTriangle(triangle[0], triangle[1], triangle[2]);
        const std::array<double, 3> normal = AreaNormal(batch.Positions[i].V);
        const float weighted[3] = { float(normal[0]), float(normal[1]), float(normal[2]) };
        for (const std::uint32_t corner : triangle)
        {
          std::array<float, 3>& sum = this->NormalSums[corner];
          for (int a = 0; a < 3; ++a)
          {
            sum[a] += weighted[a];
          }
          std::uint8_t& uses = this->InputUses[corner];
          uses = std::uint8_t(uses + (uses < ManyInputUses));
        }
      }
    });
  this->Mesh->Rewind();
  this->Triangles.Reset(PolygonBatch());
}

void MeshTriangleSource::CollectOpenEdgeEnds()
{
  // Each scan reads the whole sketch (and, for an unwelded mesh, every vertex): it lets go of
  // what it has read a few MiB at a time, or that would add to the peak of what opening holds.
  const auto forEachOpenEdgeVertex = [this](auto visit) {
    constexpr std::uint64_t Interval = std::uint64_t(1) << 18;
    for (std::uint64_t i = 0; i < this->Vertices.Count; ++i)
    {
      if (i % Interval == 0 && i > 0)
      {
        this->Sketch.ReleaseResidentPages(i - Interval, Interval);
        this->ReleaseVertexPages(i - Interval, Interval);
      }
      if (this->Sketch.OnOpenEdge(std::uint32_t(i)))
      {
        float p[3];
        this->Vertices.Get(std::uint32_t(i), p);
        const std::array<std::uint32_t, 3> q = this->Grid.Snap(p); // as Read gives it
        visit(std::uint32_t(i), q, p);
      }
    }
  };
  std::size_t openEdgeVertices = 0;
  forEachOpenEdgeVertex([&](std::uint32_t, const std::array<std::uint32_t, 3>&, const float* p) {
    this->Check->AddEndPosition(p);
    ++openEdgeVertices;
  });
  if (openEdgeVertices == 0)
  {
    return;
  }
  std::vector<std::pair<std::array<std::uint32_t, 3>, std::uint32_t>> atPosition;
  const bool join = openEdgeVertices <= MaxJoinedVertices;
  atPosition.reserve(join ? openEdgeVertices : 0);
  forEachOpenEdgeVertex([&](std::uint32_t v, const std::array<std::uint32_t, 3>& q, const float* p) {
    if (join)
    {
      atPosition.emplace_back(q, v);
    }
    // An end position one grid point away from another: a seam whose sides' copies rounded to
    // neighbouring grid points.
    for (int d = 0; d < 27; ++d)
    {
      const int offset[3] = { d % 3 - 1, d / 3 % 3 - 1, d / 9 - 1 };
      std::uint32_t n[3];
      bool onGrid = d != 13; // 13: the point itself
      for (int a = 0; a < 3 && onGrid; ++a)
      {
        n[a] = q[std::size_t(a)] + std::uint32_t(offset[a]);
        onGrid = (offset[a] >= 0 || q[std::size_t(a)] > 0) &&
          (offset[a] <= 0 || q[std::size_t(a)] < QuantizationGrid::MaxInteger);
      }
      float neighbour[3];
      if (onGrid && (this->Grid.Dequantize(n, neighbour), this->Check->IsEndPosition(neighbour)))
      {
        this->Check->MarkNearAnother(p);
        break;
      }
    }
  });
  this->JoinVerticesAtOnePosition(atPosition);
}

void MeshTriangleSource::JoinVerticesAtOnePosition(
  std::vector<std::pair<std::array<std::uint32_t, 3>, std::uint32_t>>& atPosition)
{
  // By position, then vertex: the sums are added in vertex order, the same on every run.
  std::sort(atPosition.begin(), atPosition.end());
  for (std::size_t first = 0, end = 0; first < atPosition.size(); first = end)
  {
    std::array<float, 3> sum{ { 0, 0, 0 } };
    unsigned uses = 0;
    for (end = first; end < atPosition.size() && atPosition[end].first == atPosition[first].first; ++end)
    {
      const std::uint32_t v = atPosition[end].second;
      for (int a = 0; a < 3; ++a)
      {
        sum[std::size_t(a)] += this->NormalSums[v][std::size_t(a)];
      }
      uses += this->InputUses[v];
    }
    if (end - first < 2)
    {
      continue;
    }
    for (std::size_t k = first; k < end; ++k)
    {
      const std::uint32_t v = atPosition[k].second;
      this->NormalSums[v] = sum;
      this->InputUses[v] = std::uint8_t(std::min(uses, unsigned(ManyInputUses)));
      if (k > first && this->Vertices.HasColors())
      {
        this->ColorFrom.emplace_back(v, atPosition[first].second);
      }
    }
  }
  std::sort(this->ColorFrom.begin(), this->ColorFrom.end());
}

void MeshTriangleSource::CountEdgesBetweenEnds(SoupTriangle& soup)
{
  bool end[3];
  for (int c = 0; c < 3; ++c)
  {
    end[c] = this->Check->IsEndPosition(soup.V[c]);
  }
  for (int c = 0; c < 3; ++c)
  {
    if (end[c] && end[(c + 1) % 3])
    {
      this->Check->Count(soup.V[c], soup.V[(c + 1) % 3], soup.BoundaryEdges & (1u << c));
      soup.BoundaryEdges |= BoundaryEdgeCheck::CountedBit;
    }
  }
}

void MeshTriangleSource::BoundResidentMemory()
{
  if (++this->VisitedSinceRelease < ReleaseInterval)
  {
    return;
  }
  this->VisitedSinceRelease = 0;
  if (this->Vertices.FileBacked)
  {
    ReleaseResidentPages(this->Vertices.Base, this->Vertices.Count * this->Vertices.Stride);
    if (this->Vertices.HasColors())
    {
      ReleaseResidentPages(
        this->Vertices.Colors, this->Vertices.Count * this->Vertices.ColorStride);
    }
  }
  this->Sketch.ReleaseResidentPages();
  ReleaseResidentPages(this->NormalSums.Data(), this->NormalSums.Size() * sizeof(this->NormalSums[0]));
  ReleaseResidentPages(this->InputUses.Data(), this->InputUses.Size());
}

void MeshTriangleSource::SetCornerNormals(const std::uint32_t triangle[3], SoupTriangle& soup) const
{
  for (int c = 0; c < 3; ++c)
  {
    const std::array<float, 3>& sum = this->NormalSums[triangle[c]];
    if (sum[0] == 0 && sum[1] == 0 && sum[2] == 0)
    {
      // Opposite faces cancelled out (a sheet folded onto itself): the face's own normal.
      const std::array<double, 3> face = AreaNormal(soup.V);
      const float n[3] = { float(face[0]), float(face[1]), float(face[2]) };
      EncodeNormal(n, soup.Normals[c]);
    }
    else
    {
      EncodeNormal(sum.data(), soup.Normals[c]);
    }
  }
}

void MeshTriangleSource::SetCornerColors(const std::uint32_t triangle[3], SoupTriangle& soup) const
{
  if (!this->Vertices.HasColors())
  {
    std::memset(soup.Colors, 255, sizeof(soup.Colors));
    return;
  }
  for (int c = 0; c < 3; ++c)
  {
    std::uint32_t v = triangle[c];
    if (!this->ColorFrom.empty() && this->Sketch.OnOpenEdge(v))
    {
      const auto joined = std::lower_bound(
        this->ColorFrom.begin(), this->ColorFrom.end(), std::make_pair(v, std::uint32_t(0)));
      v = joined != this->ColorFrom.end() && joined->first == v ? joined->second : v;
    }
    this->Vertices.GetColor(v, soup.Colors[c]);
  }
}

void MeshTriangleSource::FinishBoundaryCheck()
{
  this->Statistics.BoundaryEdges = this->Check->EdgesUsedOnce();
  this->Statistics.SharedOpenEdges = this->Check->EdgesShared();
  this->Statistics.BoundaryUnchecked = this->Check->Overflowed();
  this->Check->DropEndPositions();
}

bool MeshTriangleSource::StartNextBatch()
{
  PolygonBatch batch;
  if (this->FacesDone || !this->Mesh->NextBatch(batch))
  {
    if (!this->FacesDone)
    {
      this->FacesDone = true;
      this->FinishBoundaryCheck();
    }
    return false;
  }
  this->Triangles.Reset(batch);
  return true;
}

std::size_t MeshTriangleSource::Read(SoupTriangle* out, std::size_t max)
{
  std::size_t n = 0;
  std::uint32_t triangle[3];
  while (n < max)
  {
    if (!this->Triangles.Next(triangle))
    {
      if (!this->StartNextBatch())
      {
        break;
      }
      continue;
    }
    this->BoundResidentMemory();
    SoupTriangle& soup = out[n];
    if (!this->GetCorners(triangle, soup.V) || !this->HasArea(soup.V))
    {
      continue;
    }
    // The model holds every position on its grid, which merges points that round to one grid
    // point (a seam whose two sides differ in the last bits): on the grid from here on, so that
    // what the leaves weld and what counts as the input's boundary are what the model will hold.
    // A boundary decided on the positions as read left the sides of such a seam to simplify
    // apart above the leaves, which weld them: cracks at coarse levels only.
    for (float* corner : soup.V)
    {
      this->Grid.Snap(corner);
    }
    std::uint8_t boundary = 0;
    for (int c = 0; c < 3; ++c)
    {
      if (this->Sketch.IsBoundaryEdge(triangle[c], triangle[(c + 1) % 3]))
      {
        boundary |= std::uint8_t(1u << c);
      }
    }
    soup.BoundaryEdges = boundary;
    if (this->Check->HasEndPositions())
    {
      this->CountEdgesBetweenEnds(soup);
    }
    this->SetCornerNormals(triangle, soup);
    this->SetCornerColors(triangle, soup);
    for (int c = 0; c < 3; ++c)
    {
      soup.InputUses[c] = this->InputUses[triangle[c]];
    }
    ++n;
  }
  this->Statistics.TrianglesEmitted += n;
  return n;
}

} // namespace atp
