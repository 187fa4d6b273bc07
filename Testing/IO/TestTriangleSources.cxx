// OpenTriangleSource on every input format: the triangles and boundary flags it yields, what it
// drops, and a clear InputError (never a crash) for every kind of bad input. Inputs are written
// into a temporary directory by the tests themselves.
#include "atpBufferedReader.h"
#include "atpInputFile.h"
#include "atpNormalEncoding.h"
#include "atpPolyDataTriangleSource.h"
#include "atpTriangleSource.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkType.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLWriter.h>

#include "CompressedXmlFile.h"
#include "FileTestFixture.h"
#include "ProcessMemory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace
{
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Test meshes and what a source should yield for them

struct Mesh
{
  std::vector<std::array<double, 3>> Points;
  std::vector<std::vector<std::int64_t>> Faces;
  std::vector<std::array<std::uint8_t, 4>> Colors; ///< RGBA per point, or empty
};

/// A flat nx by ny grid of unit quads in z = 0; with `quads` the faces are quads, else triangles.
Mesh Grid(int nx, int ny, bool quads)
{
  Mesh mesh;
  for (int j = 0; j <= ny; ++j)
  {
    for (int i = 0; i <= nx; ++i)
    {
      mesh.Points.push_back({ double(i), double(j), 0.0 });
    }
  }
  auto id = [&](int i, int j) { return std::int64_t(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      if (quads)
      {
        mesh.Faces.push_back({ id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1) });
      }
      else
      {
        mesh.Faces.push_back({ id(i, j), id(i + 1, j), id(i + 1, j + 1) });
        mesh.Faces.push_back({ id(i, j), id(i + 1, j + 1), id(i, j + 1) });
      }
    }
  }
  return mesh;
}

/// `mesh` with a different color per point; opaque when the file will carry no alpha.
Mesh Colored(Mesh mesh, bool alpha)
{
  for (std::size_t i = 0; i < mesh.Points.size(); ++i)
  {
    mesh.Colors.push_back({ { std::uint8_t(40 + 7 * i), std::uint8_t(250 - 5 * i),
      std::uint8_t(3 * i + 1), std::uint8_t(alpha ? 200 - i : 255) } });
  }
  return mesh;
}

/// A closed tetrahedron, outward oriented.
Mesh Tetrahedron()
{
  Mesh mesh;
  mesh.Points = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  mesh.Faces = { { 0, 2, 1 }, { 0, 1, 3 }, { 1, 2, 3 }, { 2, 0, 3 } };
  return mesh;
}

/// Everything read from a source, in small chunks to exercise resuming mid-polygon.
struct Result
{
  std::vector<atp::SoupTriangle> Triangles;
  atp::Box Bounds;
  std::uint64_t Expected = 0;
  atp::InputStats Stats;
  bool HasColors = false;
};

Result ReadAll(const std::string& path, const std::string& scratch, std::size_t chunk = 5)
{
  auto source = atp::OpenTriangleSource(path, scratch);
  Result result;
  result.Bounds = source->Bounds();
  result.Expected = source->ExpectedTriangles();
  result.HasColors = source->HasColors();
  std::vector<atp::SoupTriangle> buffer(chunk);
  while (std::size_t n = source->Read(buffer.data(), buffer.size()))
  {
    result.Triangles.insert(result.Triangles.end(), buffer.begin(), buffer.begin() + long(n));
  }
  EXPECT_EQ(source->Read(buffer.data(), buffer.size()), 0u) << "the end stays the end";
  result.Stats = source->Stats();
  return result;
}

/// Total boundary bits over all triangles.
std::uint64_t BoundaryBits(const Result& result)
{
  std::uint64_t bits = 0;
  for (const atp::SoupTriangle& t : result.Triangles)
  {
    for (int c = 0; c < 3; ++c)
    {
      bits += (t.BoundaryEdges >> c) & 1u;
    }
  }
  return bits;
}

/// The triangles of `mesh` as a soup (fans, in order), without boundary flags.
std::vector<std::array<float, 9>> ExpectedSoup(const Mesh& mesh)
{
  std::vector<std::array<float, 9>> soup;
  for (const auto& face : mesh.Faces)
  {
    for (std::size_t k = 1; k + 1 < face.size(); ++k)
    {
      std::array<float, 9> t;
      const std::int64_t corners[3] = { face[0], face[k], face[k + 1] };
      for (int c = 0; c < 3; ++c)
      {
        for (int a = 0; a < 3; ++a)
        {
          t[3 * c + a] = float(mesh.Points[std::size_t(corners[c])][std::size_t(a)]);
        }
      }
      soup.push_back(t);
    }
  }
  return soup;
}

std::vector<std::array<float, 9>> Soup(const Result& result)
{
  std::vector<std::array<float, 9>> soup;
  for (const atp::SoupTriangle& t : result.Triangles)
  {
    std::array<float, 9> s;
    std::memcpy(s.data(), t.V, sizeof(t.V));
    soup.push_back(s);
  }
  return soup;
}

using CornerColors = std::array<std::uint8_t, 12>;

/// The colors of `mesh` (opaque white without) at the corners of ExpectedSoup's triangles.
std::vector<CornerColors> ExpectedColors(const Mesh& mesh)
{
  std::vector<CornerColors> colors;
  for (const auto& face : mesh.Faces)
  {
    for (std::size_t k = 1; k + 1 < face.size(); ++k)
    {
      CornerColors t;
      t.fill(255);
      const std::int64_t corners[3] = { face[0], face[k], face[k + 1] };
      for (std::size_t c = 0; c < 3 && !mesh.Colors.empty(); ++c)
      {
        std::copy_n(mesh.Colors[std::size_t(corners[c])].begin(), 4, t.begin() + 4 * c);
      }
      colors.push_back(t);
    }
  }
  return colors;
}

/// Checks the corner colors of a source read of `mesh`, and that it says whether it has colors.
void ExpectColors(const Result& result, const Mesh& mesh)
{
  EXPECT_EQ(result.HasColors, !mesh.Colors.empty());
  EXPECT_EQ(result.Stats.HasColors, !mesh.Colors.empty());
  std::vector<CornerColors> colors;
  for (const atp::SoupTriangle& t : result.Triangles)
  {
    CornerColors c;
    std::memcpy(c.data(), t.Colors, sizeof(t.Colors));
    colors.push_back(c);
  }
  EXPECT_EQ(colors, ExpectedColors(mesh));
}

/// Checks a source read of `mesh` (an open or closed manifold) against the mesh itself.
void ExpectMesh(const Result& result, const Mesh& mesh, std::uint64_t boundaryEdges)
{
  EXPECT_EQ(Soup(result), ExpectedSoup(mesh));
  EXPECT_EQ(result.Expected, result.Triangles.size());
  EXPECT_EQ(result.Stats.TrianglesEmitted, result.Triangles.size());
  EXPECT_EQ(result.Stats.VerticesRead, mesh.Points.size());
  EXPECT_EQ(result.Stats.FacesRead, mesh.Faces.size());
  EXPECT_EQ(result.Stats.DegenerateDropped, 0u);
  EXPECT_EQ(result.Stats.BoundaryEdges, boundaryEdges);
  EXPECT_EQ(BoundaryBits(result), boundaryEdges);
  for (int a = 0; a < 3; ++a)
  {
    double lo = 1e300, hi = -1e300;
    for (const auto& p : mesh.Points)
    {
      lo = std::min(lo, p[std::size_t(a)]);
      hi = std::max(hi, p[std::size_t(a)]);
    }
    EXPECT_EQ(result.Bounds.Min[std::size_t(a)], float(lo));
    EXPECT_EQ(result.Bounds.Max[std::size_t(a)], float(hi));
  }
}

// ---------------------------------------------------------------------------------------------
// Writers

class TriangleSources : public FileTestFixture
{
protected:
  std::string Scratch() const { return this->Dir.string(); }

  Result Read(const std::string& path, std::size_t chunk = 5) const
  {
    return ReadAll(path, this->Scratch(), chunk);
  }

  /// Opens and reads `path` expecting an InputError whose message names the file and contains
  /// `problem`.
  void ExpectError(const std::string& path, const std::string& problem) const
  {
    try
    {
      ReadAll(path, this->Scratch());
      ADD_FAILURE() << path << ": no error, expected one about '" << problem << "'";
    }
    catch (const atp::InputError& error)
    {
      const std::string message = error.what();
      EXPECT_NE(message.find(fs::path(path).filename().string()), std::string::npos) << message;
      EXPECT_NE(message.find(problem), std::string::npos)
        << "message: " << message << "\nexpected to contain: " << problem;
    }
  }

};

struct PlyOptions
{
  std::string Format = "binary_little_endian";
  std::string CoordinateType = "float";
  std::string CountType = "uchar";
  std::string IndexType = "int";
  std::string ListName = "vertex_indices";
  bool ExtraProperties = false; // colour before x, normal after z, a texcoord list per face
  bool ExtraElement = false;    // an element with a list between vertices and faces
  bool FacesFirst = false;
  bool ShuffledCoordinates = false; // z, x, y order
  std::string ColorType;            // the mesh's colors after z, of this type; none when empty
  std::string ColorPrefix;          // "diffuse_" for diffuse_red, ...
  bool Alpha = false;
};

/// A color byte as a PLY value of `type`: integers other than ushort hold bytes, reals fractions.
double PlyColorValue(std::uint8_t c, const std::string& type)
{
  return type == "ushort" ? c * 257.0 : (type == "float" || type == "double" ? c / 255.0 : c);
}

void Put(std::string& out, const std::string& type, double value, const PlyOptions& options)
{
  if (options.Format == "ascii")
  {
    std::ostringstream text;
    text.precision(17);
    text << value << ' ';
    out += text.str();
    return;
  }
  unsigned char bytes[8];
  std::size_t size = 0;
  auto store = [&](auto v)
  {
    size = sizeof(v);
    std::memcpy(bytes, &v, size);
  };
  if (type == "char")
    store(std::int8_t(value));
  else if (type == "uchar")
    store(std::uint8_t(value));
  else if (type == "short")
    store(std::int16_t(value));
  else if (type == "ushort")
    store(std::uint16_t(value));
  else if (type == "int")
    store(std::int32_t(value));
  else if (type == "uint")
    store(std::uint32_t(value));
  else if (type == "float")
    store(float(value));
  else
    store(double(value));
  if (options.Format == "binary_big_endian")
  {
    std::reverse(bytes, bytes + size);
  }
  out.append(reinterpret_cast<const char*>(bytes), size);
}

void EndRecord(std::string& out, const PlyOptions& options)
{
  if (options.Format == "ascii")
  {
    out += '\n';
  }
}

std::string PlyBytes(const Mesh& mesh, const PlyOptions& options = PlyOptions())
{
  const std::string& c = options.CoordinateType;
  std::string vertexHeader = "element vertex " + std::to_string(mesh.Points.size()) + "\n";
  if (options.ExtraProperties)
  {
    vertexHeader += "property uchar red\n";
  }
  vertexHeader += options.ShuffledCoordinates
    ? "property " + c + " z\nproperty " + c + " x\nproperty " + c + " y\n"
    : "property " + c + " x\nproperty " + c + " y\nproperty " + c + " z\n";
  const char* colorNames[4] = { "red", "green", "blue", "alpha" };
  const std::size_t colorComponents = options.ColorType.empty() ? 0 : (options.Alpha ? 4 : 3);
  for (std::size_t k = 0; k < colorComponents; ++k)
  {
    vertexHeader +=
      "property " + options.ColorType + " " + options.ColorPrefix + colorNames[k] + "\n";
  }
  if (options.ExtraProperties)
  {
    vertexHeader += "property float nx\n";
  }
  std::string faceHeader = "element face " + std::to_string(mesh.Faces.size()) + "\n";
  if (options.ExtraProperties)
  {
    faceHeader += "property uchar flags\n";
  }
  faceHeader +=
    "property list " + options.CountType + " " + options.IndexType + " " + options.ListName + "\n";
  if (options.ExtraProperties)
  {
    faceHeader += "property list uchar float texcoord\n";
  }
  const std::string extraHeader = options.ExtraElement
    ? "element material 2\nproperty list int short codes\nproperty double shine\n"
    : "";

  std::string vertices;
  for (std::size_t i = 0; i < mesh.Points.size(); ++i)
  {
    const auto& p = mesh.Points[i];
    if (options.ExtraProperties)
    {
      Put(vertices, "uchar", double(i % 200), options);
    }
    if (options.ShuffledCoordinates)
    {
      Put(vertices, c, p[2], options);
      Put(vertices, c, p[0], options);
      Put(vertices, c, p[1], options);
    }
    else
    {
      for (double x : p)
      {
        Put(vertices, c, x, options);
      }
    }
    for (std::size_t k = 0; k < colorComponents; ++k)
    {
      Put(vertices, options.ColorType, PlyColorValue(mesh.Colors[i][k], options.ColorType),
        options);
    }
    if (options.ExtraProperties)
    {
      Put(vertices, "float", 0.5, options);
    }
    EndRecord(vertices, options);
  }
  std::string faces;
  for (const auto& face : mesh.Faces)
  {
    if (options.ExtraProperties)
    {
      Put(faces, "uchar", 7, options);
    }
    Put(faces, options.CountType, double(face.size()), options);
    for (std::int64_t v : face)
    {
      Put(faces, options.IndexType, double(v), options);
    }
    if (options.ExtraProperties)
    {
      Put(faces, "uchar", 2, options);
      Put(faces, "float", 0.25, options);
      Put(faces, "float", 0.75, options);
    }
    EndRecord(faces, options);
  }
  std::string extra;
  if (options.ExtraElement)
  {
    for (int m = 0; m < 2; ++m)
    {
      Put(extra, "int", 3, options);
      for (int k = 0; k < 3; ++k)
      {
        Put(extra, "short", k, options);
      }
      Put(extra, "double", 1.5, options);
      EndRecord(extra, options);
    }
  }

  std::string header = "ply\nformat " + options.Format + " 1.0\ncomment written by a test\n";
  if (options.FacesFirst)
  {
    return header + faceHeader + extraHeader + vertexHeader + "end_header\n" + faces + extra +
      vertices;
  }
  return header + vertexHeader + extraHeader + faceHeader + "end_header\n" + vertices + extra +
    faces;
}

std::string ObjBytes(const Mesh& mesh)
{
  std::ostringstream out;
  out.precision(17);
  out << "# test\no thing\n";
  for (std::size_t i = 0; i < mesh.Points.size(); ++i)
  {
    const auto& p = mesh.Points[i];
    out << "v " << p[0] << ' ' << p[1] << ' ' << p[2];
    if (!mesh.Colors.empty())
    {
      out << ' ' << mesh.Colors[i][0] / 255.0 << ' ' << mesh.Colors[i][1] / 255.0 << ' '
          << mesh.Colors[i][2] / 255.0;
    }
    out << '\n';
  }
  for (const auto& face : mesh.Faces)
  {
    out << 'f';
    for (std::int64_t v : face)
    {
      out << ' ' << v + 1;
    }
    out << '\n';
  }
  return out.str();
}

std::string BinaryStlBytes(const Mesh& mesh, const std::string& headerText)
{
  std::string out = headerText;
  out.resize(80, ' ');
  const std::uint32_t count = std::uint32_t(mesh.Faces.size());
  out.append(reinterpret_cast<const char*>(&count), 4);
  for (const auto& face : mesh.Faces)
  {
    float record[12] = { 0 };
    for (int c = 0; c < 3; ++c)
    {
      for (int a = 0; a < 3; ++a)
      {
        record[3 + 3 * c + a] =
          float(mesh.Points[std::size_t(face[std::size_t(c)])][std::size_t(a)]);
      }
    }
    out.append(reinterpret_cast<const char*>(record), sizeof(record));
    out.append(2, '\0');
  }
  return out;
}

std::string AsciiStlBytes(const Mesh& mesh)
{
  std::ostringstream out;
  out << "solid my part\n";
  for (const auto& face : mesh.Faces)
  {
    out << "  facet normal 0 0 1\n    outer loop\n";
    for (std::int64_t v : face)
    {
      const auto& p = mesh.Points[std::size_t(v)];
      out << "      vertex " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    }
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid my part\n";
  return out.str();
}

// ---------------------------------------------------------------------------------------------
// PLY

TEST_F(TriangleSources, BinaryLittleEndianPly)
{
  const Mesh mesh = Grid(4, 3, false);
  ExpectMesh(this->Read(this->Write("grid.ply", PlyBytes(mesh))), mesh, 2 * (4 + 3));
}

TEST_F(TriangleSources, BinaryPlyReadInOneGoOrOneAtATime)
{
  const Mesh mesh = Grid(5, 5, true);
  const std::string path = this->Write("grid.ply", PlyBytes(mesh));
  const Result one = this->Read(path, 1);
  const Result all = this->Read(path, 1000);
  EXPECT_EQ(Soup(one), Soup(all));
  EXPECT_EQ(BoundaryBits(one), BoundaryBits(all));
  ExpectMesh(all, mesh, 20);
}

TEST_F(TriangleSources, BinaryBigEndianPlyWithDoublesAndOtherProperties)
{
  const Mesh mesh = Grid(3, 3, true);
  PlyOptions options;
  options.Format = "binary_big_endian";
  options.CoordinateType = "double";
  options.CountType = "ushort";
  options.IndexType = "uint";
  options.ExtraProperties = true;
  options.ExtraElement = true;
  ExpectMesh(this->Read(this->Write("grid.ply", PlyBytes(mesh, options))), mesh, 12);
}

TEST_F(TriangleSources, BinaryLittleEndianPlyWithOtherPropertiesAndDoubles)
{
  const Mesh mesh = Tetrahedron();
  PlyOptions options;
  options.CoordinateType = "double";
  options.CountType = "int";
  options.IndexType = "ushort";
  options.ExtraProperties = true;
  ExpectMesh(this->Read(this->Write("tet.ply", PlyBytes(mesh, options))), mesh, 0);
}

TEST_F(TriangleSources, BinaryPlyFloatsAmongOtherProperties)
{
  // x, y, z floats inside a larger record: read in place with a stride.
  const Mesh mesh = Grid(2, 2, false);
  PlyOptions options;
  options.ExtraProperties = true;
  options.ExtraElement = true;
  ExpectMesh(this->Read(this->Write("grid.ply", PlyBytes(mesh, options))), mesh, 8);
}

TEST_F(TriangleSources, PlyPropertyOrderAndElementOrder)
{
  const Mesh mesh = Grid(3, 2, false);
  PlyOptions shuffled;
  shuffled.ShuffledCoordinates = true;
  ExpectMesh(this->Read(this->Write("a.ply", PlyBytes(mesh, shuffled))), mesh, 10);
  PlyOptions facesFirst;
  facesFirst.FacesFirst = true;
  facesFirst.ExtraElement = true;
  facesFirst.ExtraProperties = true;
  ExpectMesh(this->Read(this->Write("b.ply", PlyBytes(mesh, facesFirst))), mesh, 10);
  facesFirst.Format = "ascii";
  ExpectMesh(this->Read(this->Write("c.ply", PlyBytes(mesh, facesFirst))), mesh, 10);
}

TEST_F(TriangleSources, PlyCountAndIndexTypes)
{
  const Mesh mesh = Grid(2, 3, true);
  const char* counts[] = { "uchar", "char", "ushort", "short", "uint", "int" };
  const char* indices[] = { "int", "uint", "short", "ushort", "uchar", "char" };
  for (const char* count : counts)
  {
    for (const char* index : indices)
    {
      for (const char* format : { "binary_little_endian", "binary_big_endian", "ascii" })
      {
        PlyOptions options;
        options.Format = format;
        options.CountType = count;
        options.IndexType = index;
        options.ListName = "vertex_index";
        SCOPED_TRACE(std::string(format) + " list " + count + " " + index);
        ExpectMesh(this->Read(this->Write("types.ply", PlyBytes(mesh, options))), mesh, 10);
      }
    }
  }
}

TEST_F(TriangleSources, AsciiPlyWithPolygons)
{
  Mesh mesh = Grid(3, 3, true);
  mesh.Points[5][2] = 0.25; // not flat: fans must still match
  PlyOptions options;
  options.Format = "ascii";
  options.ExtraProperties = true;
  options.ExtraElement = true;
  ExpectMesh(this->Read(this->Write("quads.ply", PlyBytes(mesh, options))), mesh, 12);
}

/// `text` with every "\n" (in its first `prefix` bytes only, when given) replaced by `lineEnd`.
std::string WithLineEnds(const std::string& text, const std::string& lineEnd,
  std::size_t prefix = std::string::npos)
{
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i)
  {
    out += text[i] == '\n' && i < prefix ? lineEnd : std::string(1, text[i]);
  }
  return out;
}

TEST_F(TriangleSources, TextLinesEndWithLineFeedsCarriageReturnsOrBoth)
{
  // Classic Mac OS text ends its lines with a carriage return alone: an OBJ read as one line
  // said "no faces", a PLY header had no end_header line.
  const Mesh mesh = Grid(3, 2, false);
  PlyOptions ascii;
  ascii.Format = "ascii";
  for (const std::string lineEnd : { "\n", "\r\n", "\r" })
  {
    SCOPED_TRACE(lineEnd == "\r" ? "CR" : lineEnd == "\n" ? "LF" : "CRLF");
    const std::string name = std::to_string(lineEnd.size()) + (lineEnd[0] == '\r' ? "cr" : "lf");
    EXPECT_EQ(Soup(this->Read(this->Write(name + ".obj", WithLineEnds(ObjBytes(mesh), lineEnd)))),
      ExpectedSoup(mesh));
    EXPECT_EQ(Soup(this->Read(this->Write(name + ".ply", WithLineEnds(PlyBytes(mesh, ascii), lineEnd)))),
      ExpectedSoup(mesh));
    EXPECT_EQ(Soup(this->Read(this->Write(name + ".stl", WithLineEnds(AsciiStlBytes(mesh), lineEnd)))),
      ExpectedSoup(mesh));

    // Errors name the line they are on, whatever ends the lines.
    this->ExpectError(this->Write(name + "-bad.obj",
                        WithLineEnds("v 0 0 0\n\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n", lineEnd)),
      "line 3");
    this->ExpectError(this->Write(name + "-bad.ply",
                        WithLineEnds("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
                                     "property float y\nproperty float z\nend_header\n0 0 0\n\n0 zero 0\n",
                          lineEnd)),
      "line 10: expected a number, found 'zero'");
  }

  // A binary body may begin with any byte: after a header of lone carriage returns, a first
  // byte 0x0A is the body's, not the rest of a "\r\n".
  Mesh lineFeedFirst = mesh;
  std::uint32_t bits = 0x3F80000A; // a float whose little-endian first byte is 0x0A
  float x;
  std::memcpy(&x, &bits, sizeof x);
  lineFeedFirst.Points[0][0] = x;
  const std::string binary = PlyBytes(lineFeedFirst);
  const std::size_t body = binary.find("end_header\n") + std::string("end_header\n").size();
  ASSERT_EQ(binary[body], '\x0A');
  EXPECT_EQ(Soup(this->Read(this->Write("cr-binary.ply", WithLineEnds(binary, "\r", body)))),
    ExpectedSoup(lineFeedFirst));
  // The same with a blank after "ply": its line still ends with the "\r".
  EXPECT_EQ(Soup(this->Read(this->Write("cr-blank.ply", "ply " + WithLineEnds(binary, "\r", body).substr(3)))),
    ExpectedSoup(lineFeedFirst));
}

TEST_F(TriangleSources, LinesEndAnyWayWhereverTheBufferEnds)
{
  // Lines, tokens and their line numbers, with a buffer so small that its end falls at every
  // place of the text in turn: in a "\r\n", right after a lone "\r", or with a "\r" last in a
  // full buffer (refused as a line too long, though the line had ended).
  const std::string text = "ab\r\ncd\ref\ngh\r\r\nij\r";
  const std::vector<std::string> lines = { "ab", "cd", "ef", "gh", "", "ij" };
  const std::vector<std::pair<std::string, std::uint64_t>> tokens = { { "ab", 1 }, { "cd", 2 },
    { "ef", 3 }, { "gh", 4 }, { "ij", 6 } };
  const atp::InputFile file(this->Write("lines.txt", text));
  for (std::size_t capacity = 3; capacity <= text.size() + 1; ++capacity)
  {
    SCOPED_TRACE("capacity " + std::to_string(capacity));
    atp::BufferedReader reader(file, 0, 1, capacity);
    std::vector<std::string> read;
    std::vector<std::uint64_t> numbers;
    std::string_view line;
    while (reader.NextLine(line))
    {
      read.emplace_back(line);
      numbers.push_back(reader.Line());
    }
    EXPECT_EQ(read, lines);
    EXPECT_EQ(numbers, (std::vector<std::uint64_t>{ 1, 2, 3, 4, 5, 6 }));
    reader.Seek(0);
    std::vector<std::pair<std::string, std::uint64_t>> words;
    std::string_view token;
    while (reader.NextToken(token))
    {
      words.emplace_back(std::string(token), reader.Line());
    }
    EXPECT_EQ(words, tokens);
  }
  const atp::InputFile full(this->Write("full.txt", "aaaaaaa\rbb\n"));
  atp::BufferedReader reader(full, 0, 1, 8);
  std::string_view line;
  ASSERT_TRUE(reader.NextLine(line));
  EXPECT_EQ(line, "aaaaaaa");
  ASSERT_TRUE(reader.NextLine(line));
  EXPECT_EQ(line, "bb");
  EXPECT_EQ(reader.Line(), 2u);
  const atp::InputFile crlf(this->Write("crlf.txt", "aaaaaaa\r\nbb\n"));
  atp::BufferedReader split(crlf, 0, 1, 8);
  ASSERT_TRUE(split.NextLine(line));
  EXPECT_EQ(line, "aaaaaaa");
  ASSERT_TRUE(split.NextLine(line));
  EXPECT_EQ(line, "bb") << "the \n of a \r\n split by the buffer is no line of its own";
  EXPECT_FALSE(split.NextLine(line));
}

TEST_F(TriangleSources, AsciiPlyRecordsStandOneToALine)
{
  // Read as a stream of values, a record with a value too many shifted every value after it
  // into the wrong property, and the mesh came out wrong without a word.
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                             "end_header\n";
  const Result spaced = this->Read(
    this->Write("spaced.ply", header + "0 0 0 \t\n\n1 0 0\r\n+0\t1 0\n\n3 0 1 2   \n\n"));
  ASSERT_EQ(spaced.Triangles.size(), 1u);
  EXPECT_EQ(spaced.Triangles[0].V[2][1], 1.0f);
  this->ExpectError(this->Write("extra.ply", header + "0 0 0\n1 0 0 7\n0 1 0\n3 0 1 2\n"),
    "line 11: vertex 1 has more values on its line than the header's properties");
  this->ExpectError(this->Write("fewer.ply", header + "0 0 0\n1 0\n0 0 1 0\n3 0 1 2\n"),
    "line 11: vertex 1 has fewer values on its line than the header's properties");
  this->ExpectError(this->Write("corner.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 2\n"),
    "line 13: face 0 has more values on its line than the header's properties");
  this->ExpectError(this->Write("split.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n2\n"),
    "line 13: face 0 has fewer values on its line than the header's properties");
  // Elements the mesh does not use are read by the same rule.
  const std::string other = "ply\nformat ascii 1.0\nelement note 1\nproperty int a\nelement vertex 3\n"
                            "property float x\nproperty float y\nproperty float z\nend_header\n";
  this->ExpectError(this->Write("note.ply", other + "5 6\n0 0 0\n1 0 0\n0 1 0\n"),
    "line 10: note 0 has more values on its line than the header's properties");
}

// A seam of copied vertices (each side's faces on their own copies, as exporters write texture
// seams) is one line of vertices in the model: its edges are no boundary, and the copies of a
// vertex give their corners one normal (that of all their faces), one color (the first copy's)
// and one count of the triangles that use the position.
TEST_F(TriangleSources, CopiesOfAVertexOnASeamShareOneNormalColorAndCount)
{
  Mesh mesh = Colored(Grid(4, 2, false), false);
  for (auto& p : mesh.Points)
  {
    p[2] = 0.25 * p[0] * p[0]; // bent, so that each side's faces face another way
  }
  const std::size_t originals = mesh.Points.size();
  std::map<std::size_t, std::int64_t> copyOf;
  for (std::size_t i = 0; i < originals; ++i)
  {
    if (mesh.Points[i][0] == 2)
    {
      copyOf[i] = std::int64_t(mesh.Points.size());
      mesh.Points.push_back(mesh.Points[i]);
      mesh.Colors.push_back({ { 1, 2, 3, 255 } });
    }
  }
  for (auto& face : mesh.Faces)
  {
    const bool right = std::all_of(face.begin(), face.end(), [&](std::int64_t v) { return mesh.Points[std::size_t(v)][0] >= 2; });
    for (auto& v : face)
    {
      v = right && copyOf.count(std::size_t(v)) ? copyOf[std::size_t(v)] : v;
    }
  }
  PlyOptions options;
  options.ColorType = "uchar";
  const Result result = this->Read(this->Write("seam.ply", PlyBytes(mesh, options)));
  EXPECT_EQ(result.Stats.BoundaryEdges, 2u * (4 + 2)) << "the grid's outline alone";
  std::size_t seamCorners = 0;
  std::map<double, std::tuple<std::array<std::int16_t, 2>, std::array<std::uint8_t, 4>, int>> atSeam;
  for (const atp::SoupTriangle& t : result.Triangles)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (t.V[c][0] != 2)
      {
        continue;
      }
      ++seamCorners;
      const auto corner = std::make_tuple(std::array<std::int16_t, 2>{ { t.Normals[c][0], t.Normals[c][1] } },
        std::array<std::uint8_t, 4>{ { t.Colors[c][0], t.Colors[c][1], t.Colors[c][2], t.Colors[c][3] } },
        int(t.InputUses[c]));
      const auto [it, added] = atSeam.emplace(double(t.V[c][1]), corner);
      EXPECT_TRUE(added || it->second == corner) << "another normal, color or count at y = " << t.V[c][1];
    }
  }
  ASSERT_EQ(atSeam.size(), 3u);
  EXPECT_EQ(seamCorners, 3u + 6u + 3u);
  EXPECT_EQ(std::get<2>(atSeam[1.0]), 6) << "the middle vertex of the seam has 6 triangles";
  EXPECT_NE(std::get<1>(atSeam[1.0]), (std::array<std::uint8_t, 4>{ { 1, 2, 3, 255 } })) << "the first copy's color";
  float normal[3];
  const std::int16_t stored[2] = { std::get<0>(atSeam[1.0])[0], std::get<0>(atSeam[1.0])[1] };
  atp::DecodeNormal(stored, normal);
  EXPECT_NEAR(normal[0], -std::sin(std::atan(1.0)), 0.03) << "the normal of both sides' faces: the slope there is 1";
}

TEST_F(TriangleSources, VerticesNoFaceUsesLeaveTheBoxAndThePrecisionAlone)
{
  // A vertex no face uses set the model's box, and with it the grid its precision comes from:
  // one at 1e6 beside a grid of 0.01 spacing made its triangles too thin for that grid, one
  // at 1e30 all of them, and either way the box framed a point that is not drawn.
  Mesh mesh = Grid(40, 40, false);
  for (auto& p : mesh.Points)
  {
    p[0] *= 0.01;
    p[1] *= 0.01;
  }
  const std::vector<std::array<float, 9>> alone = Soup(this->Read(this->Write("alone.ply", PlyBytes(mesh))));
  for (const double far : { 1e6, 1e30, -1e12 })
  {
    SCOPED_TRACE(far);
    Mesh stray = mesh;
    stray.Points.push_back({ far, 0.5, far });
    const Result result = this->Read(this->Write("stray.ply", PlyBytes(stray)));
    EXPECT_EQ(Soup(result), alone);
    EXPECT_EQ(result.Stats.DegenerateDropped, 0u);
    EXPECT_EQ(result.Stats.VerticesRead, stray.Points.size());
    EXPECT_EQ(result.Bounds.Min, (std::array<double, 3>{ { 0, 0, 0 } }));
    EXPECT_EQ(result.Bounds.Max, (std::array<double, 3>{ { double(0.4f), double(0.4f), 0 } }));
  }
}

/// An OBJ of one polygon with these corners.
std::string OnePolygonObj(const std::vector<std::array<double, 3>>& corners)
{
  std::ostringstream obj;
  obj.precision(17);
  for (const auto& p : corners)
  {
    obj << "v " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  }
  obj << 'f';
  for (std::size_t k = 1; k <= corners.size(); ++k)
  {
    obj << ' ' << k;
  }
  obj << '\n';
  return obj.str();
}

/// Whether (x, y) lies inside the polygon's projection on z = 0 (crossings of a ray along +x).
bool InsideXY(const std::vector<std::array<double, 3>>& polygon, double x, double y)
{
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
  {
    const auto& a = polygon[i];
    const auto& b = polygon[j];
    if ((a[1] > y) != (b[1] > y) && x < (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]) + a[0])
    {
      inside = !inside;
    }
  }
  return inside;
}

TEST_F(TriangleSources, ConcavePolygonsAreTriangulatedInsideThemselves)
{
  // A fan from the first corner covers a convex polygon only: an L, a star or a dart came out
  // with triangles outside the polygon, overlapping each other, some facing the other way.
  const std::vector<std::vector<std::array<double, 3>>> shapes = {
    { { 0, 0, 0 }, { 2, 0, 0 }, { 2, 1, 0 }, { 1, 1, 0 }, { 1, 2, 0 }, { 0, 2, 0 } }, // an L
    { { 1, 1, 0 }, { 2, 1, 0 }, { 2, 2, 0 }, { 0, 2, 0 }, { 0, 0, 0 }, { 1, 0, 0 } }, // an L from its notch
    { { 0, 0, 0 }, { 2, 1, 0 }, { 0, 2, 0 }, { 0.5, 1, 0 } },                         // a dart
    { { 0, 0, 0 }, { 3, 0, 0 }, { 3, 3, 0 }, { 2, 3, 0 }, { 2, 1, 0 }, { 1, 1, 0 }, { 1, 3, 0 },
      { 0, 3, 0 } }, // a U
  };
  std::vector<std::vector<std::array<double, 3>>> cases = shapes;
  // Corners written twice, as exporters do: the one beside the repeat turned nowhere, so the
  // L's reflex corner went unseen and the fan spilled outside it.
  cases.push_back({ { 2, 1, 0 }, { 1, 1, 0 }, { 1, 1, 0 }, { 1, 2, 0 }, { 0, 2, 0 }, { 0, 0, 0 }, { 2, 0, 0 },
    { 2, 1, 0 } });
  // A star of ten corners.
  std::vector<std::array<double, 3>> star;
  for (int k = 0; k < 10; ++k)
  {
    const double angle = k * 3.14159265358979 / 5, radius = k % 2 ? 0.4 : 1.0;
    star.push_back({ radius * std::cos(angle), radius * std::sin(angle), 0 });
  }
  cases.push_back(star);
  for (std::size_t c = 0; c < cases.size(); ++c)
  {
    for (const bool reversed : { false, true })
    {
      SCOPED_TRACE("shape " + std::to_string(c) + (reversed ? ", wound clockwise" : ""));
      std::vector<std::array<double, 3>> polygon = cases[c];
      if (reversed)
      {
        std::reverse(polygon.begin(), polygon.end());
      }
      double area = 0; // signed, twice, about +z
      for (std::size_t i = 0; i < polygon.size(); ++i)
      {
        const auto& a = polygon[i];
        const auto& b = polygon[(i + 1) % polygon.size()];
        area += a[0] * b[1] - b[0] * a[1];
      }
      const Result result = this->Read(this->Write("polygon.obj", OnePolygonObj(polygon)));
      std::size_t distinct = 0;
      for (std::size_t i = 0; i < polygon.size(); ++i)
      {
        distinct += polygon[i] != polygon[(i + 1) % polygon.size()];
      }
      ASSERT_EQ(result.Triangles.size(), distinct - 2);
      double covered = 0;
      for (const atp::SoupTriangle& t : result.Triangles)
      {
        const double twice = (t.V[1][0] - t.V[0][0]) * (t.V[2][1] - t.V[0][1]) -
          (t.V[1][1] - t.V[0][1]) * (t.V[2][0] - t.V[0][0]);
        EXPECT_GT(twice * area, 0) << "a triangle faces against its polygon";
        covered += twice;
        const double x = (t.V[0][0] + t.V[1][0] + t.V[2][0]) / 3, y = (t.V[0][1] + t.V[1][1] + t.V[2][1]) / 3;
        EXPECT_TRUE(InsideXY(polygon, x, y)) << "a triangle outside its polygon";
      }
      EXPECT_NEAR(covered, area, 1e-5 * std::fabs(area)) << "the triangles overlap";
    }
  }

  // In a plane across x, bent a little out of it: the same, about x.
  std::vector<std::array<double, 3>> upright;
  for (const auto& p : shapes[0])
  {
    upright.push_back({ 0.01 * p[0] * p[1], p[0], p[1] });
  }
  const Result bent = this->Read(this->Write("upright.obj", OnePolygonObj(upright)));
  ASSERT_EQ(bent.Triangles.size(), 4u);
  double covered = 0;
  for (const atp::SoupTriangle& t : bent.Triangles)
  {
    covered += (t.V[1][1] - t.V[0][1]) * (t.V[2][2] - t.V[0][2]) - (t.V[1][2] - t.V[0][2]) * (t.V[2][1] - t.V[0][1]);
  }
  EXPECT_NEAR(covered, 2 * 3.0, 1e-5);

  // A polygon with no inside keeps the fan: crossing itself (a bow tie), or coming back to a
  // corner.
  const Result bowtie = this->Read(this->Write("bowtie.obj", "v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 4\n"));
  ASSERT_EQ(bowtie.Triangles.size(), 2u);
  EXPECT_EQ(bowtie.Triangles[0].V[1][0], 1.0f); // (1, 2, 3): the fan's first triangle
  EXPECT_EQ(bowtie.Triangles[0].V[1][1], 1.0f);
  const Result back = this->Read(
    this->Write("back.obj", "v 0 0 0\nv 2 0 0\nv 1 1 0\nv 2 2 0\nv 0 2 0\nf 1 2 3 4 5 3\n"));
  ASSERT_EQ(back.Triangles.size(), 3u); // the fan's (1, 3, 4) has no area
  EXPECT_EQ(back.Triangles[2].V[1][1], 2.0f); // (1, 5, 3): the fan's last triangle
  EXPECT_EQ(back.Triangles[2].V[2][0], 1.0f);
}

TEST_F(TriangleSources, UppercaseExtension)
{
  const Mesh mesh = Tetrahedron();
  ExpectMesh(this->Read(this->Write("TET.PLY", PlyBytes(mesh))), mesh, 0);
}

TEST_F(TriangleSources, PlyVertexColors)
{
  // Read in place (little-endian float coordinates, byte colors) or copied (any other layout);
  // ushort and real colors are converted to bytes.
  struct Case
  {
    const char* Format;
    const char* Coordinates;
    const char* Colors;
    const char* Prefix;
    bool Alpha;
  };
  const Case cases[] = {
    { "binary_little_endian", "float", "uchar", "", true },
    { "binary_little_endian", "float", "uchar", "", false },
    { "binary_little_endian", "double", "uchar", "", true },
    { "binary_little_endian", "float", "float", "diffuse_", false },
    { "binary_big_endian", "float", "uchar", "", true },
    { "binary_big_endian", "double", "ushort", "diffuse_", true },
    { "ascii", "float", "uchar", "", false },
    { "ascii", "double", "float", "", true },
  };
  for (const Case& c : cases)
  {
    const Mesh mesh = Colored(Grid(4, 3, true), c.Alpha);
    PlyOptions options;
    options.Format = c.Format;
    options.CoordinateType = c.Coordinates;
    options.ColorType = c.Colors;
    options.ColorPrefix = c.Prefix;
    options.Alpha = c.Alpha;
    SCOPED_TRACE(std::string(c.Format) + " " + c.Coordinates + " " + c.Colors + " " + c.Prefix +
      (c.Alpha ? " with alpha" : ""));
    const Result result = this->Read(this->Write("colors.ply", PlyBytes(mesh, options)));
    ExpectMesh(result, mesh, 14);
    ExpectColors(result, mesh);
  }
}

// ---------------------------------------------------------------------------------------------
// OBJ

TEST_F(TriangleSources, ObjTriangles)
{
  const Mesh mesh = Grid(4, 4, false);
  ExpectMesh(this->Read(this->Write("grid.obj", ObjBytes(mesh))), mesh, 16);
}

TEST_F(TriangleSources, CornersCarryAreaWeightedVertexNormals)
{
  // A flat grid: every normal is +z. A closed tetrahedron: each corner's normal is the
  // area-weighted mean of its three faces, and a vertex has the same bits in every triangle.
  const Result flat = this->Read(this->Write("flat.obj", ObjBytes(Grid(3, 3, true))));
  for (const atp::SoupTriangle& t : flat.Triangles)
  {
    for (int c = 0; c < 3; ++c)
    {
      float n[3];
      atp::DecodeNormal(t.Normals[c], n);
      EXPECT_NEAR(n[2], 1.0f, 1e-6f);
    }
  }
  const Mesh tetra = Tetrahedron();
  std::map<std::array<float, 3>, std::array<std::int16_t, 2>> seen;
  const Result closed = this->Read(this->Write("tetra.obj", ObjBytes(tetra)));
  for (const atp::SoupTriangle& t : closed.Triangles)
  {
    for (int c = 0; c < 3; ++c)
    {
      const std::array<float, 3> p{ { t.V[c][0], t.V[c][1], t.V[c][2] } };
      const std::array<std::int16_t, 2> bits{ { t.Normals[c][0], t.Normals[c][1] } };
      EXPECT_EQ(seen.emplace(p, bits).first->second, bits) << "one normal per vertex";
      // At the origin: faces -z, -y, -x of area 1/2 each. At (1,0,0): -z and -y of area 1/2 and
      // the slanted face, (1,1,1)/sqrt(3) with area sqrt(3)/2: they sum to (1/2, 0, 0).
      float n[3];
      atp::DecodeNormal(t.Normals[c], n);
      const float expected[4][3] = { { -1, -1, -1 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
      const int vertex = int(p[0]) + 2 * int(p[1]) + 3 * int(p[2]);
      const float* e = expected[vertex];
      const float length = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_NEAR(n[a], e[a] / length, 1e-4f) << "vertex " << vertex;
      }
    }
  }
  EXPECT_EQ(seen.size(), 4u);
}

TEST_F(TriangleSources, ObjCornerFormsNegativeIndicesPolygonsAndInterleaving)
{
  // A unit square as a quad written with relative indices after its vertices, then a triangle
  // whose vertex comes after it with i/t/n and i//n corners, and lines to ignore.
  const std::string text = "# comment\nmtllib x.mtl\nv 0 0 0\nv 1 0 0\nvt 0 0\nvn 0 0 1\n"
                           "v 1 1 0\nv 0 1 0\ng group\nusemtl m\ns off\n"
                           "f -4/1 -3/1 -2/1 -1/1\n"
                           "f 2/1/1 5//1 3\n"
                           "v 2 0.5 0\n"
                           "l 1 2\n";
  Mesh mesh;
  mesh.Points = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 2, 0.5, 0 } };
  mesh.Faces = { { 0, 1, 2, 3 }, { 1, 4, 2 } };
  ExpectMesh(this->Read(this->Write("mixed.obj", text)), mesh, 5);
}

TEST_F(TriangleSources, ObjVertexColors)
{
  const Mesh mesh = Colored(Grid(3, 3, true), false);
  const Result result = this->Read(this->Write("colors.obj", ObjBytes(mesh)));
  ExpectMesh(result, mesh, 12);
  ExpectColors(result, mesh);
}

TEST_F(TriangleSources, ObjRelativeIndicesCountOnlyEarlierVertices)
{
  const std::string text =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 5 5 5\nv 6 5 5\nv 5 6 5\nf -3 -2 -1\n";
  const Result result = this->Read(this->Write("rel.obj", text));
  ASSERT_EQ(result.Triangles.size(), 2u);
  EXPECT_EQ(result.Triangles[0].V[1][0], 1.0f);
  EXPECT_EQ(result.Triangles[1].V[0][0], 5.0f);
}

// ---------------------------------------------------------------------------------------------
// STL

TEST_F(TriangleSources, BinaryStlIsWelded)
{
  const Mesh closed = Tetrahedron();
  ExpectMesh(this->Read(this->Write("tet.stl", BinaryStlBytes(closed, "binary"))), closed, 0);
  const Mesh open = Grid(3, 2, false);
  const Result result = this->Read(this->Write("grid.stl", BinaryStlBytes(open, "made by x")));
  EXPECT_EQ(Soup(result), ExpectedSoup(open));
  EXPECT_EQ(result.Stats.VerticesRead, open.Points.size()) << "welded";
  EXPECT_EQ(result.Stats.BoundaryEdges, 10u);
}

TEST_F(TriangleSources, BinaryStlWhoseHeaderSaysSolid)
{
  const Mesh mesh = Tetrahedron();
  ExpectMesh(this->Read(this->Write("solid.stl", BinaryStlBytes(mesh, "solid tet"))), mesh, 0);
}

TEST_F(TriangleSources, AsciiStl)
{
  const Mesh mesh = Grid(2, 2, false);
  const Result result = this->Read(this->Write("grid.stl", AsciiStlBytes(mesh)));
  EXPECT_EQ(Soup(result), ExpectedSoup(mesh));
  EXPECT_EQ(result.Stats.BoundaryEdges, 8u);
  EXPECT_EQ(result.Stats.VerticesRead, 9u);
}

TEST_F(TriangleSources, ByteOrderMarksAndTrailingCommentsAreNoContent)
{
  // A byte-order mark before the first word used to hide an OBJ's first vertex and make an ASCII
  // STL look binary; a comment after a face's corners was read as a corner.
  const std::string mark = "\xEF\xBB\xBF";
  const Result obj = this->Read(
    this->Write("marked.obj", mark + "v 0 0 0 # origin\nv 1 0 0\nv 0 1 0\nf 1 2 3 # the only face\n"));
  EXPECT_EQ(obj.Triangles.size(), 1u);
  EXPECT_EQ(obj.Stats.VerticesRead, 3u);
  const Mesh mesh = Grid(2, 2, false);
  const Result stl = this->Read(this->Write("marked.stl", mark + AsciiStlBytes(mesh)));
  EXPECT_EQ(Soup(stl), ExpectedSoup(mesh));
}

TEST_F(TriangleSources, AsciiStlInCapitals)
{
  // Some writers capitalize the keywords; it was taken for a corrupt binary STL.
  const Mesh mesh = Grid(2, 2, false);
  std::string bytes = AsciiStlBytes(mesh);
  std::transform(bytes.begin(), bytes.end(), bytes.begin(),
    [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  const Result result = this->Read(this->Write("capitals.stl", bytes));
  EXPECT_EQ(Soup(result), ExpectedSoup(mesh));
}

TEST_F(TriangleSources, AsciiStlFacetsOfOtherSizesAreFanned)
{
  // STL's facets are triangles, but an ASCII loop may list more corners: from the second facet
  // on, the reader keeps each facet's size.
  Mesh mesh = Grid(2, 1, true); // two quads
  mesh.Faces.insert(mesh.Faces.begin(), { 0, 1, 4 });
  mesh.Faces.push_back({ 1, 2, 5 });
  const Result result = this->Read(this->Write("quads.stl", AsciiStlBytes(mesh)));
  EXPECT_EQ(Soup(result), ExpectedSoup(mesh));
  EXPECT_EQ(result.Triangles.size(), 6u);
}

TEST_F(TriangleSources, StlWeldsNegativeAndPositiveZero)
{
  Mesh mesh;
  mesh.Points = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { -0.0, 0, 0 } };
  mesh.Faces = { { 0, 1, 2 }, { 3, 2, 1 } };
  const Result result = this->Read(this->Write("zero.stl", BinaryStlBytes(mesh, "")));
  EXPECT_EQ(result.Stats.VerticesRead, 3u);
  EXPECT_EQ(result.Stats.BoundaryEdges, 0u) << "the two triangles are the same, reversed";
}

// ---------------------------------------------------------------------------------------------
// VTP

TEST_F(TriangleSources, VtpPolygonsAndStrips)
{
  vtkNew<vtkPoints> points;
  for (int j = 0; j <= 1; ++j)
  {
    for (int i = 0; i <= 3; ++i)
    {
      points->InsertNextPoint(i, j, 0);
    }
  }
  vtkNew<vtkCellArray> polys;
  const vtkIdType quad[4] = { 0, 1, 5, 4 };
  polys->InsertNextCell(4, quad);
  vtkNew<vtkCellArray> strips;
  const vtkIdType strip[6] = { 1, 5, 2, 6, 3, 7 };
  strips->InsertNextCell(6, strip);
  vtkNew<vtkCellArray> lines;
  const vtkIdType line[2] = { 0, 7 };
  lines->InsertNextCell(2, line);
  vtkNew<vtkPolyData> polyData;
  polyData->SetPoints(points);
  polyData->SetPolys(polys);
  polyData->SetStrips(strips);
  polyData->SetLines(lines);
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(polyData);
  writer->SetFileName(this->Path("strip.vtp").c_str());
  ASSERT_EQ(writer->Write(), 1);

  Mesh mesh;
  for (int j = 0; j <= 1; ++j)
  {
    for (int i = 0; i <= 3; ++i)
    {
      mesh.Points.push_back({ double(i), double(j), 0 });
    }
  }
  // Strip triangles alternate orientation so that all face the same way.
  mesh.Faces = { { 0, 1, 5, 4 }, { 1, 5, 2 }, { 5, 6, 2 }, { 2, 6, 3 }, { 6, 7, 3 } };
  const Result result = this->Read(this->Path("strip.vtp"));
  EXPECT_EQ(Soup(result), ExpectedSoup(mesh));
  EXPECT_EQ(result.Stats.BoundaryEdges, 8u);
  EXPECT_EQ(result.Stats.TrianglesEmitted, 6u);
}

/// `mesh` as points and triangles.
vtkSmartPointer<vtkPolyData> PolyDataOf(const Mesh& mesh)
{
  vtkNew<vtkPoints> points;
  for (const auto& p : mesh.Points)
  {
    points->InsertNextPoint(p.data());
  }
  vtkNew<vtkCellArray> polys;
  for (const auto& face : mesh.Faces)
  {
    const vtkIdType ids[3] = { face[0], face[1], face[2] };
    polys->InsertNextCell(3, ids);
  }
  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->SetPoints(points);
  polyData->SetPolys(polys);
  return polyData;
}

/// `mesh` as a .vtp at `path`, with `colors` (its own name set) added to the point data, as the
/// active scalars or beside a float array that is.
void WriteVtp(const Mesh& mesh, vtkDataArray* colors, bool colorsAreScalars, const std::string& path)
{
  vtkSmartPointer<vtkPolyData> polyData = PolyDataOf(mesh);
  vtkNew<vtkFloatArray> other;
  other->SetName("temperature");
  other->SetNumberOfValues(polyData->GetNumberOfPoints());
  other->Fill(1);
  if (colorsAreScalars)
  {
    polyData->GetPointData()->SetScalars(colors);
  }
  else
  {
    polyData->GetPointData()->AddArray(colors);
    polyData->GetPointData()->SetScalars(other);
  }
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(polyData);
  writer->SetFileName(path.c_str());
  ASSERT_EQ(writer->Write(), 1);
}

TEST_F(TriangleSources, VtpPointColors)
{
  // Unsigned char colors as the active scalars (any name), or in an array named RGB, RGBA or
  // Colors of any type, read as PLY colors are: reals fractions of 1, unsigned shorts of 65535.
  struct Case
  {
    const char* Name;
    int Type;
    double Full; ///< the stored value of a full component
    bool Alpha, Scalars;
  };
  for (const Case& c : { Case{ "paint", VTK_UNSIGNED_CHAR, 255, true, true },
         Case{ "RGB", VTK_UNSIGNED_CHAR, 255, false, false },
         Case{ "RGBA", VTK_FLOAT, 1, true, false }, Case{ "Colors", VTK_DOUBLE, 1, false, false },
         Case{ "RGB", VTK_UNSIGNED_SHORT, 65535, false, false },
         Case{ "Colors", VTK_INT, 255, true, false } })
  {
    SCOPED_TRACE(std::string(c.Name) + " " + vtkImageScalarTypeNameMacro(c.Type));
    const Mesh mesh = Colored(Grid(3, 2, false), c.Alpha);
    vtkSmartPointer<vtkDataArray> colors = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(c.Type));
    colors->SetName(c.Name);
    colors->SetNumberOfComponents(c.Alpha ? 4 : 3);
    for (const auto& color : mesh.Colors)
    {
      double tuple[4];
      for (int k = 0; k < 4; ++k)
      {
        tuple[k] = color[std::size_t(k)] / 255.0 * c.Full;
      }
      colors->InsertNextTuple(tuple);
    }
    WriteVtp(mesh, colors, c.Scalars, this->Path("colors.vtp"));
    const Result result = this->Read(this->Path("colors.vtp"));
    ExpectMesh(result, mesh, 10);
    ExpectColors(result, mesh);
  }
}

TEST_F(TriangleSources, VtpColorsOfTwoComponentsAreRefused)
{
  const Mesh mesh = Grid(3, 2, false);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("RGB");
  colors->SetNumberOfComponents(2);
  colors->SetNumberOfTuples(vtkIdType(mesh.Points.size()));
  colors->Fill(7);
  WriteVtp(mesh, colors, false, this->Path("two.vtp"));
  this->ExpectError(this->Path("two.vtp"), "the point array RGB has 2 components; colors have 3 (RGB) or 4 (RGBA)");
  // Too few tuples for the points (no file holds that, a pipeline can): read past its end, it
  // would be colors of other memory. As the active scalars it is no color array.
  vtkNew<vtkPolyData> polyData;
  vtkNew<vtkPoints> points;
  for (const auto& p : mesh.Points)
  {
    points->InsertNextPoint(p.data());
  }
  vtkNew<vtkCellArray> polys;
  const vtkIdType triangle[3] = { 0, 1, 4 };
  polys->InsertNextCell(3, triangle);
  polyData->SetPoints(points);
  polyData->SetPolys(polys);
  vtkNew<vtkUnsignedCharArray> short3;
  short3->SetName("Colors");
  short3->SetNumberOfComponents(3);
  short3->SetNumberOfTuples(vtkIdType(mesh.Points.size()) - 1);
  short3->Fill(9);
  polyData->GetPointData()->AddArray(short3);
  try
  {
    atp::OpenPolyDataTriangleSource(polyData, "short colors");
    ADD_FAILURE() << "a color array shorter than the points was accepted";
  }
  catch (const atp::InputError& error)
  {
    EXPECT_NE(std::string(error.what()).find("the point array Colors has 11 tuples for 12 points"), std::string::npos)
      << error.what();
  }
  short3->SetName("paint");
  polyData->GetPointData()->SetScalars(short3);
  EXPECT_FALSE(atp::OpenPolyDataTriangleSource(polyData, "short scalars")->HasColors());
  // Active scalars of two unsigned chars under another name are data, not colors.
  colors->SetName("uv");
  WriteVtp(mesh, colors, true, this->Path("two-scalars.vtp"));
  ExpectColors(this->Read(this->Path("two-scalars.vtp")), mesh);
}

TEST_F(TriangleSources, WithoutColorsCornersAreOpaqueWhite)
{
  const Mesh mesh = Grid(3, 2, false);
  PlyOptions loneRed;
  loneRed.ExtraProperties = true; // a red without green and blue is no color
  for (const std::string& path : { this->Write("plain.ply", PlyBytes(mesh)),
         this->Write("red.ply", PlyBytes(mesh, loneRed)), this->Write("plain.obj", ObjBytes(mesh)),
         this->Write("plain.stl", BinaryStlBytes(mesh, "")) })
  {
    SCOPED_TRACE(path);
    ExpectColors(this->Read(path), mesh);
  }
  // OBJ colors count only when every vertex has them.
  Mesh triangle;
  triangle.Points = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } };
  triangle.Faces = { { 0, 1, 2 } };
  ExpectColors(this->Read(this->Write("partial.obj", "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0 1\nf 1 2 3\n")),
    triangle);
}

// ---------------------------------------------------------------------------------------------
// Degenerate triangles and boundary flags

using atp::testing::StatusKiB;

namespace
{
/// Opens `path` into `source`; returns how much the process's peak resident memory grew doing
/// it (KiB), or -1 when this kernel cannot start the peak again from the current memory.
long OpenMeasuringPeak(
  const std::string& path, const std::string& scratch, std::unique_ptr<atp::TriangleSource>& source)
{
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5"; // the peak resident memory starts again from the current one
  clear.close();
  if (!clear)
  {
    return -1;
  }
  const long before = StatusKiB("VmHWM");
  source = atp::OpenTriangleSource(path, scratch);
  return StatusKiB("VmHWM") - before;
}
} // namespace

TEST_F(TriangleSources, OpeningLetsGoOfTheVertexPagesItHasRead)
{
  // Opening reads every vertex once (bounds, finiteness): with 144 MiB of positions and a
  // single face, nearly all of its peak memory would be those pages if it kept them.
  constexpr std::uint32_t vertices = 12u << 20;
  constexpr std::uint32_t block = 1u << 16;
  const std::string path = (this->Dir / "many-vertices.ply").string();
  {
    std::ofstream out(path, std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\nelement vertex " << vertices
        << "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
           "property list uchar int vertex_indices\nend_header\n";
    std::vector<float> positions(3 * block);
    for (std::uint32_t first = 0; first < vertices; first += block)
    {
      for (std::uint32_t i = 0; i < block; ++i)
      {
        const std::uint32_t v = first + i;
        positions[3 * i] = float(v);
        positions[3 * i + 1] = float(v % 7);
        positions[3 * i + 2] = float(v * v % 5);
      }
      out.write(reinterpret_cast<const char*>(positions.data()), std::streamsize(positions.size() * sizeof(float)));
    }
    const unsigned char count = 3;
    const std::int32_t face[3] = { 0, 1, 2 };
    out.write(reinterpret_cast<const char*>(&count), 1);
    out.write(reinterpret_cast<const char*>(face), sizeof(face));
    ASSERT_TRUE(out.good());
  }
  std::unique_ptr<atp::TriangleSource> source;
  const long grown = OpenMeasuringPeak(path, this->Scratch(), source);
  if (grown < 0)
  {
    GTEST_SKIP() << "this kernel does not reset the peak resident memory (clear_refs)";
  }
  EXPECT_LT(grown, 96L << 10) << "KiB of peak resident memory added by opening";
  EXPECT_EQ(source->Bounds().Max[0], 2.0) << "the box of the vertices the face uses";
  EXPECT_EQ(source->ExpectedTriangles(), 1u);
}

TEST_F(TriangleSources, OpeningAnStlHoldsLittleOfIt)
{
  // STL is a soup, welded on opening: 4M triangles of a grid, 200 MB of file. Welded in memory,
  // the vertices, the corners and a table of positions added 226 MiB; welded out of core, 75 MiB
  // (122 MiB under AddressSanitizer), about what opening the same grid as a PLY file adds.
  constexpr int columns = 2000, rows = 1000;
  const std::string path = (this->Dir / "big.stl").string();
  {
    std::ofstream out(path, std::ios::binary);
    std::string header(80, ' ');
    out.write(header.data(), 80);
    const std::uint32_t count = 2u * columns * rows;
    out.write(reinterpret_cast<const char*>(&count), 4);
    std::vector<char> records;
    for (int j = 0; j < rows; ++j)
    {
      records.clear();
      for (int i = 0; i < columns; ++i)
      {
        const auto z = [](int u, int v) { return float((u * 7 + v * 3) % 11); }; // a rough sheet
        const float x = float(i), y = float(j);
        const float a = z(i, j), b = z(i + 1, j), c = z(i + 1, j + 1), d = z(i, j + 1);
        const float quad[2][12] = { { 0, 0, 1, x, y, a, x + 1, y, b, x + 1, y + 1, c },
          { 0, 0, 1, x, y, a, x + 1, y + 1, c, x, y + 1, d } };
        for (const auto& record : quad)
        {
          records.insert(records.end(), reinterpret_cast<const char*>(record),
            reinterpret_cast<const char*>(record) + sizeof(record));
          records.insert(records.end(), 2, '\0');
        }
      }
      out.write(records.data(), std::streamsize(records.size()));
    }
    ASSERT_TRUE(out.good());
  }
  std::unique_ptr<atp::TriangleSource> source;
  const long grown = OpenMeasuringPeak(path, this->Scratch(), source);
  if (grown < 0)
  {
    GTEST_SKIP() << "this kernel does not reset the peak resident memory (clear_refs)";
  }
  std::printf("opening added %ld KiB of peak resident memory\n", grown);
  EXPECT_LT(grown, 160L << 10) << "KiB of peak resident memory added by opening";
  EXPECT_EQ(source->ExpectedTriangles(), 2u * columns * rows);
  EXPECT_EQ(source->Stats().VerticesRead, std::uint64_t(columns + 1) * (rows + 1)) << "welded";
  EXPECT_EQ(source->Bounds().Max[0], double(columns));
  std::filesystem::remove(path);
}

TEST_F(TriangleSources, DegenerateTrianglesAreDroppedAndCounted)
{
  Mesh mesh = Grid(2, 1, false);        // 4 triangles, 6 points
  mesh.Points.push_back({ 0.5, 0, 0 }); // 6: on the edge from 0 to 1
  mesh.Faces.push_back({ 0, 0, 3 });    // repeated corner
  mesh.Faces.push_back({ 0, 6, 1 });    // collinear: zero area
  mesh.Faces.push_back({ 4, 3 });       // two corners
  for (const char* format : { "binary_little_endian", "ascii" })
  {
    PlyOptions options;
    options.Format = format;
    const Result result = this->Read(this->Write("degenerate.ply", PlyBytes(mesh, options)));
    EXPECT_EQ(result.Triangles.size(), 4u);
    EXPECT_EQ(result.Expected, 4u);
    EXPECT_EQ(result.Stats.FacesRead, 7u);
    EXPECT_EQ(result.Stats.DegenerateDropped, 3u);
    EXPECT_EQ(result.Stats.BoundaryEdges, 6u) << "the dropped triangles do not count";
  }
}

TEST_F(TriangleSources, ThinnerThanTheModelsGridIsDegenerate)
{
  // The leaves store corners on one grid whose step is the float spacing at the largest
  // coordinate (here 1: 2^-23). A sliver one step wide keeps its area there; one whose apex
  // rounds onto its base does not, however exact its area in float, nor does a needle far out
  // along x, where the step is 2^-23 of 2^20.
  Mesh mesh;
  const double step = std::ldexp(1.0, -23);
  mesh.Points = { { 0, 0, 0 }, { 1, 0, 0 }, { 0.5, step, 0 }, { 0.5, 1e-30, 0 }, { 0.5, 0.4 * step, 0 },
    { 0.75, 0.5, 0 } };
  mesh.Faces = { { 0, 1, 2 }, { 0, 1, 3 }, { 0, 1, 4 }, { 0, 1, 5 } };
  const Result result = this->Read(this->Write("sliver.ply", PlyBytes(mesh)));
  EXPECT_EQ(result.Triangles.size(), 2u);
  EXPECT_EQ(result.Stats.DegenerateDropped, 2u);

  Mesh far;
  far.Points = { { 0, 0, 0 }, { 1048576, 0, 0 }, { 524288, 0.01, 0 }, { 0, 1, 0 } };
  far.Faces = { { 0, 1, 2 }, { 0, 1, 3 } };
  const Result needle = this->Read(this->Write("needle.ply", PlyBytes(far)));
  EXPECT_EQ(needle.Triangles.size(), 1u) << "0.01 wide where the step is 0.125";
  EXPECT_EQ(needle.Stats.DegenerateDropped, 1u);
  far.Faces = { { 0, 1, 2 } };
  this->ExpectError(this->Write("needle-only.ply", PlyBytes(far)),
    "empty mesh (no triangles: all 1 are degenerate; coordinates are kept as 32-bit floats on a "
    "grid of step 0.125, the float spacing at the largest coordinate)");
}

TEST_F(TriangleSources, BoundaryFlagsMarkTheRightEdges)
{
  // Two triangles sharing the diagonal 0-2 of a square: every edge but the diagonal is boundary.
  Mesh mesh;
  mesh.Points = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } };
  mesh.Faces = { { 0, 1, 2 }, { 0, 2, 3 } };
  const Result result = this->Read(this->Write("square.ply", PlyBytes(mesh)));
  ASSERT_EQ(result.Triangles.size(), 2u);
  EXPECT_EQ(result.Triangles[0].BoundaryEdges & 7, 0b011); // 0-1, 1-2 boundary; 2-0 shared
  EXPECT_EQ(result.Triangles[1].BoundaryEdges & 7, 0b110); // 0-2 shared; 2-3, 3-0 boundary
  // Each corner carries the triangles that use its vertex.
  EXPECT_EQ(std::vector<int>(result.Triangles[0].InputUses, result.Triangles[0].InputUses + 3), std::vector<int>({ 2, 1, 2 }));
  EXPECT_EQ(std::vector<int>(result.Triangles[1].InputUses, result.Triangles[1].InputUses + 3), std::vector<int>({ 2, 2, 1 }));
}

// How many triangles use each vertex travels with its corners: degenerate triangles do not count,
// and the count stops at 255.
TEST_F(TriangleSources, CornersCarryTheTrianglesOfTheirVertex)
{
  Mesh fan;
  fan.Points = { { 0, 0, 0 } };
  const int rim = 300;
  for (int i = 0; i < rim; ++i)
  {
    fan.Points.push_back({ std::cos(2 * M_PI * i / rim), std::sin(2 * M_PI * i / rim), 0 });
  }
  for (int i = 1; i <= rim; ++i)
  {
    fan.Faces.push_back({ 0, i, i % rim + 1 });
  }
  fan.Faces.push_back({ 1, 1, 2 }); // degenerate: dropped, and not counted at 1 and 2
  const Result result = this->Read(this->Write("fan.ply", PlyBytes(fan)));
  ASSERT_EQ(result.Triangles.size(), std::size_t(rim));
  for (const atp::SoupTriangle& t : result.Triangles)
  {
    EXPECT_EQ(int(t.InputUses[0]), 255) << "300 triangles at the center";
    EXPECT_EQ(int(t.InputUses[1]), 2);
    EXPECT_EQ(int(t.InputUses[2]), 2);
  }
}

TEST_F(TriangleSources, ClosedMeshWithAHole)
{
  // A cube of 12 triangles is closed; without one triangle it has a 3-edge hole.
  Mesh cube;
  for (int k = 0; k < 8; ++k)
  {
    cube.Points.push_back({ double(k & 1), double((k >> 1) & 1), double((k >> 2) & 1) });
  }
  cube.Faces = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 }, { 0, 4, 6, 2 },
    { 1, 3, 7, 5 } };
  EXPECT_EQ(this->Read(this->Write("cube.obj", ObjBytes(cube))).Stats.BoundaryEdges, 0u);
  cube.Faces[0] = { 0, 2, 3 };
  EXPECT_EQ(this->Read(this->Write("holed.obj", ObjBytes(cube))).Stats.BoundaryEdges, 3u);
}

// ---------------------------------------------------------------------------------------------
// Bad input

TEST_F(TriangleSources, FileErrors)
{
  this->ExpectError(this->Path("missing.ply"), "cannot open");
  this->ExpectError(this->Write("mesh.xyz", "hello"), "unsupported file type '.xyz'");
  this->ExpectError(this->Write("noextension", "hello"), "unsupported file type");
  fs::create_directory(this->Path("folder.obj"));
  this->ExpectError(this->Path("folder.obj"), "not a regular file");
  this->ExpectError(this->Path("missing.vtp"), "cannot open");
}

TEST_F(TriangleSources, BadPlyHeaders)
{
  const std::string v = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string f = "element face 1\nproperty list uchar int vertex_indices\n";
  this->ExpectError(this->Write("a.ply", ""), "bad PLY header");
  this->ExpectError(
    this->Write("b.ply", "PLY\nformat ascii 1.0\nend_header\n"), "does not start with 'ply'");
  this->ExpectError(this->Write("c.ply", "ply\nformat ascii 1.0\n" + v + f), "no end_header");
  this->ExpectError(
    this->Write("d.ply", "ply\nformat xml 1.0\n" + v + f + "end_header\n"), "unknown format 'xml'");
  this->ExpectError(this->Write("e.ply", "ply\n" + v + f + "end_header\n"), "no format line");
  this->ExpectError(this->Write("f.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n"),
    "property before any element");
  this->ExpectError(
    this->Write("g.ply", "ply\nformat ascii 1.0\nelement vertex many\nend_header\n"),
    "expected 'element <name> <count>'");
  // 2^64: out of range, not read as zero (an extra element so counted was skipped unread).
  this->ExpectError(this->Write("g2.ply",
                      "ply\nformat ascii 1.0\n" + v + f + "element extra 18446744073709551616\nend_header\n"),
    "expected 'element <name> <count>'");
  this->ExpectError(
    this->Write("h.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty int64 x\nend_header\n"),
    "unsupported PLY property type 'int64'");
  this->ExpectError(
    this->Write("i.ply", "ply\nformat ascii 1.0\n" + f + "end_header\n"), "no vertex element");
  this->ExpectError(
    this->Write("j.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n" + f +
        "end_header\n"),
    "no 'z' property");
  this->ExpectError(this->Write("k.ply",
                      "ply\nformat ascii 1.0\n" + v +
                        "element face 1\nproperty list uchar int corners\nend_header\n"),
    "no vertex_indices list");
  this->ExpectError(this->Write("l.ply",
                      "ply\nformat ascii 1.0\n" + v +
                        "element face 1\nproperty list uchar float vertex_indices\nend_header\n"),
    "must have an integer type");
  this->ExpectError(
    this->Write("m.ply", "ply\nformat ascii 1.0\nbogus line\nend_header\n"), "unexpected 'bogus'");
  this->ExpectError(
    this->Write(
      "n.ply", std::string("ply\nformat binary_little_endian 1.0\n") + std::string(2 << 20, 'x')),
    "no end_header");
}

TEST_F(TriangleSources, PlyDataErrors)
{
  const Mesh mesh = Grid(1, 1, false);
  std::string bytes = PlyBytes(mesh);
  this->ExpectError(this->Write("short.ply", bytes.substr(0, bytes.size() - 3)),
    "truncated: face 1 of 2 ends past the end of the file");

  Mesh nan = mesh;
  nan.Points[2][1] = std::numeric_limits<double>::quiet_NaN();
  this->ExpectError(
    this->Write("nan.ply", PlyBytes(nan)), "vertex 2 has a non-finite coordinate (nan)");
  PlyOptions ascii;
  ascii.Format = "ascii";
  this->ExpectError(this->Write("nan-ascii.ply", PlyBytes(nan, ascii)),
    "vertex 2 has a non-finite coordinate (nan)");
  Mesh huge = mesh;
  huge.Points[1][0] = 1e300;
  PlyOptions doubles;
  doubles.CoordinateType = "double";
  this->ExpectError(
    this->Write("huge.ply", PlyBytes(huge, doubles)), "vertex 1 has a non-finite coordinate (inf)");

  Mesh outOfRange = mesh;
  outOfRange.Faces[1][2] = 9;
  this->ExpectError(this->Write("range.ply", PlyBytes(outOfRange)),
    "face 1 has vertex index 9, out of range (file has 4 vertices)");
  outOfRange.Faces[1][2] = -1;
  this->ExpectError(
    this->Write("negative.ply", PlyBytes(outOfRange)), "face 1 has vertex index -1");

  this->ExpectError(
    this->Write("word.ply",
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n0 zero 0\n"),
    "line 8: expected a number, found 'zero'");
  // Text can say what no binary file could: a value outside its property's type.
  const std::string small = "ply\nformat ascii 1.0\nelement vertex 3\nproperty uchar x\nproperty uchar y\n"
                            "property uchar z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  this->ExpectError(this->Write("uchar.ply", small + "300 0 0\n0 1 0\n0 0 1\n3 0 1 2\n"),
    "line 10: '300' is not a value of its property's type, uchar");
  this->ExpectError(this->Write("minus.ply", small + "0 0 0\n0 1 0\n0 -5 1\n3 0 1 2\n"),
    "line 12: '-5' is not a value of its property's type, uchar");
  this->ExpectError(this->Write("half.ply", small + "0 0 0\n0 1.5 0\n0 0 1\n3 0 1 2\n"),
    "line 11: '1.5' is not a value of its property's type, uchar");
  EXPECT_EQ(this->Read(this->Write("fits.ply", small + "255 0 0\n0 1 0\n0 0 1\n3 0 1 2\n")).Triangles.size(), 1u);
  this->ExpectError(
    this->Write("count.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list int int vertex_indices\n"
      "end_header\n0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n"),
    "face 0 has a list of negative length -3");
  this->ExpectError(
    this->Write("corners.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list int int vertex_indices\n"
      "end_header\n0 0 0\n1 0 0\n0 1 0\n100000000 0 1 2\n"),
    "face 0 has 100000000 corners");
}

TEST_F(TriangleSources, PlyHeaderClaimsAreCheckedBeforeAllocating)
{
  const std::string v = "property float x\nproperty float y\nproperty float z\n";
  const std::string f = "element face 1\nproperty list uchar int vertex_indices\n";
  this->ExpectError(this->Write("billions.ply",
                      "ply\nformat binary_little_endian 1.0\nelement vertex 3000000000\n" + v + f +
                        "end_header\n" + std::string(100, '\0')),
    "the header claims 3000000000 vertices but only 100 bytes are left in the file");
  this->ExpectError(
    this->Write("billions-ascii.ply",
      "ply\nformat ascii 1.0\nelement vertex 3000000000\n" + v + f + "end_header\n0 0 0\n"),
    "claims 3000000000 vertices");
  this->ExpectError(
    this->Write("too-many.ply",
      "ply\nformat binary_little_endian 1.0\nelement vertex 5000000000\n" + v + f + "end_header\n"),
    "too many vertices (5000000000; at most 4294967295 are supported)");
  this->ExpectError(this->Write("faces.ply",
                      "ply\nformat binary_little_endian 1.0\nelement vertex 3\n" + v +
                        "element face 4000000000\nproperty list uchar int vertex_indices\n"
                        "end_header\n" +
                        std::string(36, '\0')),
    "truncated: face 0 of 4000000000 ends past the end of the file");
  this->ExpectError(
    this->Write("other.ply",
      "ply\nformat binary_little_endian 1.0\nelement junk 999999999999\nproperty double a\n"
      "element vertex 3\n" +
        v + f + "end_header\n" + std::string(64, '\0')),
    "the header claims 999999999999 'junk' records");
}

TEST_F(TriangleSources, EmptyMeshes)
{
  Mesh noFaces = Grid(1, 1, false);
  noFaces.Faces.clear();
  this->ExpectError(this->Write("nofaces.ply", PlyBytes(noFaces)), "empty mesh (no triangles");
  this->ExpectError(
    this->Write("noface-element.ply",
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n1 2 3\n"),
    "empty mesh (no triangles: it has no faces)");
  Mesh degenerate;
  degenerate.Points = { { 0, 0, 0 }, { 1, 1, 1 }, { 2, 2, 2 } };
  degenerate.Faces = { { 0, 1, 2 }, { 0, 0, 1 } };
  this->ExpectError(this->Write("flat.ply", PlyBytes(degenerate)),
    "empty mesh (no triangles: all 2 are degenerate; coordinates are kept as 32-bit floats");
  this->ExpectError(this->Write("empty.obj", "# nothing\n"), "empty mesh (no triangles");
  this->ExpectError(
    this->Write("empty.stl", BinaryStlBytes(Mesh(), "binary")), "empty mesh (no triangles");
  this->ExpectError(
    this->Write("empty-ascii.stl", "solid x\nendsolid x\n"), "empty mesh (no triangles");
  this->ExpectError(this->Write("flat.obj", ObjBytes(degenerate)), "empty mesh");
}

TEST_F(TriangleSources, ObjErrors)
{
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\n";
  this->ExpectError(this->Write("range.obj", square + "f 1 2 3\n\nf 1 2 99\n"),
    "range.obj line 6: face index 99 out of range (file has 3 vertices)");
  this->ExpectError(
    this->Write("zero.obj", square + "f 0 1 2\n"), "line 4: face index 0 out of range");
  this->ExpectError(this->Write("relative.obj", "v 0 0 0\nf -1 -2 -3\n" + square),
    "line 2: face index -2 out of range (file has 4 vertices, 1 before this line)");
  this->ExpectError(
    this->Write("corner.obj", square + "f 1 2 x3\n"), "line 4: bad face corner 'x3'");
  this->ExpectError(this->Write("slash.obj", square + "f 1 2 3x/1\n"), "bad face corner '3x/1'");
  this->ExpectError(
    this->Write("short.obj", "v 0 0\n"), "line 1: a vertex needs three coordinates");
  this->ExpectError(this->Write("edge.obj", square + "f 1 2\n"), "line 4: a face needs 3 corners or more, this one has 2");
  this->ExpectError(
    this->Write("word.obj", "v 0 zero 0\n"), "line 1: expected a coordinate, found 'zero'");
  // Bytes no message can print are escaped: a NUL used to end the message where it stood.
  this->ExpectError(this->Write("nul.obj", std::string("v 0 0 0\0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 30)),
    "line 1: expected a coordinate, found '0\\x00'");
  this->ExpectError(this->Write("long.obj", "v 0 " + std::string(100, 'y') + " 0\n"),
    "found '" + std::string(40, 'y') + "...'");
  this->ExpectError(
    this->Write("nan.obj", square + "v 0 nan 0\nf 1 2 3\n"), "line 4: non-finite coordinate (nan)");
  this->ExpectError(this->Write("long.obj", "v 0 0 0\n# " + std::string(5 << 20, 'x') + "\n"),
    "line 2: line longer than");
}

TEST_F(TriangleSources, StlErrors)
{
  const Mesh mesh = Tetrahedron();
  std::string binary = BinaryStlBytes(mesh, "binary");
  this->ExpectError(this->Write("cut.stl", binary.substr(0, binary.size() - 10)),
    "truncated or corrupt binary STL: the header claims 4 triangles (284 bytes) but the file has "
    "274 bytes");
  this->ExpectError(this->Write("tiny.stl", "abc"), "not an STL file");
  std::string solidCut = BinaryStlBytes(mesh, "solid but binary");
  this->ExpectError(this->Write("solidcut.stl", solidCut.substr(0, solidCut.size() - 1)),
    "truncated or corrupt binary STL");
  Mesh nan = mesh;
  nan.Points[1][0] = std::numeric_limits<double>::quiet_NaN();
  this->ExpectError(this->Write("nan.stl", BinaryStlBytes(nan, "x")),
    "triangle 0 has a non-finite coordinate (nan)");
  this->ExpectError(
    this->Write("word.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 zero\n"),
    "word.stl line 4: expected a coordinate, found 'zero'");
  this->ExpectError(
    this->Write("open.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"),
    "truncated: the file ends inside a facet");
  // Every token has its place: a fourth coordinate or a word out of place is said, not skipped.
  const std::string facet = "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n";
  this->ExpectError(this->Write("four.stl", facet + "vertex 0 1 0 9\nendloop\nendfacet\nendsolid x\n"),
    "four.stl line 6: unexpected '9'");
  this->ExpectError(this->Write("normal.stl", "solid x\nfacet normal 0 0\nouter loop\n"),
    "normal.stl line 3: a facet normal needs three numbers");
  this->ExpectError(this->Write("outer.stl", "solid x\nfacet normal 0 0 1\nouter lop\n"),
    "outer.stl line 3: expected 'loop' after 'outer'");
  this->ExpectError(
    this->Write("cutvertex.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0"),
    "truncated: the file ends inside a vertex");
  // Corners are welded as they are read: one outside a loop would belong to no facet.
  this->ExpectError(this->Write("stray.stl",
                      "solid x\nfacet normal 0 0 1\nvertex 0 0 0\nouter loop\nvertex 0 0 0\n"
                      "vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid x\n"),
    "stray.stl line 3: a vertex outside 'outer loop' ... 'endloop'");
  this->ExpectError(this->Write("unopened.stl", "solid x\nfacet normal 0 0 1\nendloop\n"),
    "unopened.stl line 3: 'endloop' without 'outer loop'");
  this->ExpectError(this->Write("unclosed.stl",
                      "solid x\nfacet normal 0 0 1\nouter loop\nvertex 9 9 9\nvertex 8 8 8\n"
                      "outer loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"),
    "unclosed.stl line 6: 'outer loop' inside a loop (no 'endloop' before it)");
}

TEST_F(TriangleSources, VtpErrors)
{
  this->ExpectError(
    this->Write("junk.vtp", "this is not xml"), "not a readable VTK XML PolyData file");
  this->ExpectError(this->Write("other.vtp",
                      "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\">\n"
                      "<ImageData WholeExtent=\"0 1 0 1 0 1\"/></VTKFile>\n"),
    "not a readable VTK XML PolyData file");
}

TEST_F(TriangleSources, VtpInEveryEncodingAndCompressionReads)
{
  // Small blocks: many of them, so that compressed headers of every length are read.
  const Mesh mesh = Grid(7, 5, false);
  for (const int compressor : { vtkXMLWriter::NONE, vtkXMLWriter::ZLIB, vtkXMLWriter::LZ4, vtkXMLWriter::LZMA })
  {
    for (const int mode : { 0, 1, 2, 3 }) // ASCII, inline binary, appended base64, appended raw
    {
      for (const bool wide : { false, true })
      {
        SCOPED_TRACE("compressor " + std::to_string(compressor) + ", mode " + std::to_string(mode) +
          (wide ? ", 64-bit headers" : ", 32-bit headers"));
        vtkNew<vtkXMLPolyDataWriter> writer; // one reused across modes wrote raw bytes inline
        writer->SetInputData(PolyDataOf(mesh));
        writer->SetBlockSize(40);
        writer->SetCompressorType(compressor);
        writer->SetDataMode(mode == 0 ? vtkXMLWriter::Ascii : mode == 1 ? vtkXMLWriter::Binary : vtkXMLWriter::Appended);
        writer->SetEncodeAppendedData(mode != 3); // inline binary is base64 only when this is on
        writer->SetHeaderType(wide ? vtkXMLWriter::UInt64 : vtkXMLWriter::UInt32);
        writer->SetFileName(this->Path("written.vtp").c_str());
        ASSERT_EQ(writer->Write(), 1);
        EXPECT_EQ(this->Read(this->Path("written.vtp")).Triangles.size(), mesh.Faces.size());
      }
    }
  }
}

TEST_F(TriangleSources, VtpHeadersClaimingMoreThanTheFileHoldsAreRefusedBeforeVtkAllocates)
{
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(PolyDataOf(Grid(7, 5, false)));
  const atp::testing::CompressedXmlFile written = atp::testing::WriteCompressed(writer, this->Path("good.vtp"), true);
  ASSERT_NE(written.Header, std::string::npos);
  const std::string& good = written.Bytes;
  const std::size_t header = written.Header;
  const auto withWord = [&](std::size_t word, std::uint64_t value) {
    std::string bytes = good;
    std::memcpy(&bytes[header + 8 * word], &value, 8);
    return bytes;
  };
  const long before = atp::testing::StatusKiB("VmRSS");
  // VTK 9.1 allocates a size for every block the header claims: 2 GiB for these 2^28.
  this->ExpectError(this->Write("blocks.vtp", withWord(0, std::uint64_t(1) << 28)),
    "its compressed array 'Points' claims 268435456 blocks, more than the file holds");
  std::string huge = withWord(1, std::uint64_t(1) << 40);
  std::memcpy(&huge[header + 16], &huge[header + 8], 8);
  this->ExpectError(this->Write("block.vtp", huge), "claims a block of 1099511627776 bytes stored in");
  EXPECT_LT(atp::testing::StatusKiB("VmHWM") - before, 200 * 1024) << "KiB more at the peak";

  std::string points = good;
  const std::size_t count = points.find("NumberOfPoints=\"");
  ASSERT_NE(count, std::string::npos);
  points.insert(count + 16, "99999999");
  this->ExpectError(this->Write("points.vtp", points), "more than its");
  // A string array rides along, unless it is to be the active scalars (VTK 9.1 crashes on that).
  const auto labelled = [](const std::string& pointData) {
    return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\">\n<PolyData>"
           "<Piece NumberOfPoints=\"3\" NumberOfPolys=\"1\"><PointData" +
      pointData +
      "><DataArray type=\"String\" Name=\"label\" format=\"ascii\">97 0 98 0 99 0</DataArray>"
      "</PointData><Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">"
      "0 0 0 1 0 0 0 1 0</DataArray></Points><Polys><DataArray type=\"Int32\" "
      "Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray><DataArray type=\"Int32\" "
      "Name=\"offsets\" format=\"ascii\">3</DataArray></Polys></Piece></PolyData></VTKFile>\n";
  };
  EXPECT_EQ(this->Read(this->Write("labels.vtp", labelled(""))).Triangles.size(), 1u);
  this->ExpectError(this->Write("text.vtp", labelled(" Scalars=\"label\"")), "its array 'label' has type 'String'");
}

/// Counts what VTK would print, while installed as its output window.
class CountingOutputWindow : public vtkOutputWindow
{
public:
  static CountingOutputWindow* New() { return new CountingOutputWindow; }
  void DisplayText(const char*) override { ++this->Texts; }
  int Texts = 0;
};

TEST_F(TriangleSources, VtpPointsOfTwoComponentsAreRefusedBeforeVtkReadsThem)
{
  const std::string path = this->Write("flat.vtp",
    "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\">\n<PolyData>"
    "<Piece NumberOfPoints=\"3\" NumberOfPolys=\"1\"><Points>"
    "<DataArray type=\"Float32\" NumberOfComponents=\"2\" format=\"ascii\">0 0 1 0 0 1</DataArray>"
    "</Points><Polys><DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>"
    "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">3</DataArray></Polys>"
    "</Piece></PolyData></VTKFile>\n");
  vtkSmartPointer<vtkOutputWindow> previous = vtkOutputWindow::GetInstance();
  vtkNew<CountingOutputWindow> counting;
  vtkOutputWindow::SetInstance(counting);
  this->ExpectError(path, "points with 2 components (a point has 3)");
  vtkOutputWindow::SetInstance(previous);
  EXPECT_EQ(counting->Texts, 0) << "VTK printed its own error too";
}

TEST_F(TriangleSources, BinaryPlyTruncatedAnywhereIsAnInputError)
{
  Mesh mesh = Grid(2, 1, true);
  PlyOptions options;
  options.ExtraProperties = true;
  options.ExtraElement = true;
  for (bool inPlace : { true, false })
  {
    options.CoordinateType = inPlace ? "float" : "double";
    const std::string bytes = PlyBytes(mesh, options);
    ASSERT_NO_THROW(this->Read(this->Write("whole.ply", bytes)));
    for (std::size_t length = 0; length < bytes.size(); ++length)
    {
      const std::string path = this->Write("cut.ply", bytes.substr(0, length));
      EXPECT_THROW(this->Read(path), atp::InputError) << "length " << length;
    }
  }
}

TEST_F(TriangleSources, BinaryStlTruncatedAnywhereIsAnInputError)
{
  const std::string bytes = BinaryStlBytes(Tetrahedron(), "solid looks like text");
  for (std::size_t length = 0; length < bytes.size(); ++length)
  {
    EXPECT_THROW(this->Read(this->Write("cut.stl", bytes.substr(0, length))), atp::InputError)
      << "length " << length;
  }
}

TEST_F(TriangleSources, GarbageNeverCrashes)
{
  // Random bytes after valid headers: errors, never crashes or hangs.
  std::uint32_t state = 12345;
  auto next = [&]()
  {
    state = state * 1664525u + 1013904223u;
    return char(state >> 24);
  };
  const std::string header =
    "ply\nformat binary_big_endian 1.0\nelement vertex 20\nproperty float x\n"
    "property float y\nproperty float z\nelement face 30\n"
    "property list uchar uint vertex_indices\nend_header\n";
  for (int trial = 0; trial < 200; ++trial)
  {
    std::string bytes = header;
    const int length = 200 + trial * 3;
    for (int i = 0; i < length; ++i)
    {
      bytes += next();
    }
    const std::string path = this->Write("garbage.ply", bytes);
    try
    {
      this->Read(path);
    }
    catch (const atp::InputError&)
    {
    }
  }
}
} // namespace
