#include "atpPlyMesh.h"

#include "atpBufferedReader.h"
#include "atpInputFile.h"
#include "atpPlyHeader.h"
#include "atpScratchArray.h"
#include "atpTextParsing.h"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <optional>
#include <vector>

namespace atp
{
namespace
{
// A polygon's corners are read in one piece; real polygons have a handful.
constexpr std::int64_t MaxCorners = 65536;

enum class Role : std::uint8_t
{
  None,
  X,
  Y,
  Z,
  Red,
  Green,
  Blue,
  Alpha,
  Corners
};

/// A property as the readers need it: how to decode it and what it is for.
struct Field
{
  PlyType Type;
  PlyType CountType;
  bool IsList;
  Role Use;
};

/// Binary face records whose only list is the corner list: the scalars around it have fixed
/// sizes, so a record is two reads, without walking its properties.
struct FaceLayout
{
  bool Applies = false;
  std::size_t BytesBefore = 0;
  std::size_t BytesAfter = 0;
  PlyType CountType = PlyType::UInt8;
  PlyType IndexType = PlyType::Int32;
};

/// One record's values that matter: x, y, z and the color of a vertex (indexed by Role - 1), the
/// corners of a face.
struct Record
{
  double Values[7] = { 0, 0, 0, 0, 0, 0, 0 };
  std::vector<std::int64_t> Corners = std::vector<std::int64_t>(MaxCorners); // allocated once
  std::size_t CornerCount = 0;
};

template<typename T, bool Swap>
T Load(const unsigned char* p)
{
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, p, sizeof(T));
  if (Swap)
  {
    std::reverse(bytes, bytes + sizeof(T));
  }
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

template<typename Out, bool Swap>
Out LoadAs(const unsigned char* p, PlyType type)
{
  switch (type)
  {
    case PlyType::Int8:
      return static_cast<Out>(Load<std::int8_t, Swap>(p));
    case PlyType::UInt8:
      return static_cast<Out>(Load<std::uint8_t, Swap>(p));
    case PlyType::Int16:
      return static_cast<Out>(Load<std::int16_t, Swap>(p));
    case PlyType::UInt16:
      return static_cast<Out>(Load<std::uint16_t, Swap>(p));
    case PlyType::Int32:
      return static_cast<Out>(Load<std::int32_t, Swap>(p));
    case PlyType::UInt32:
      return static_cast<Out>(Load<std::uint32_t, Swap>(p));
    case PlyType::Float32:
      return static_cast<Out>(Load<float, Swap>(p));
    case PlyType::Float64:
      return static_cast<Out>(Load<double, Swap>(p));
  }
  return Out();
}

constexpr bool HostIsLittleEndian = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;

/// Binary values; `false` from a read means the file ended first.
template<bool Swap>
class BinaryDecoder
{
public:
  explicit BinaryDecoder(BufferedReader& reader)
    : Reader(reader)
  {
  }

  bool Integer(PlyType type, std::int64_t& value)
  {
    const unsigned char* p = this->Reader.Take(PlyTypeSize(type));
    if (p)
    {
      value = LoadAs<std::int64_t, Swap>(p, type);
    }
    return p != nullptr;
  }

  bool Real(PlyType type, double& value)
  {
    const unsigned char* p = this->Reader.Take(PlyTypeSize(type));
    if (p)
    {
      value = LoadAs<double, Swap>(p, type);
    }
    return p != nullptr;
  }

  /// n <= MaxCorners, so the bytes fit the reader's buffer.
  bool Integers(PlyType type, std::size_t n, std::int64_t* values)
  {
    const std::size_t size = PlyTypeSize(type);
    const unsigned char* p = this->Reader.Take(n * size);
    if (!p)
    {
      return false;
    }
    // One dispatch per list, not per value.
    switch (type)
    {
      case PlyType::Int8:
        return LoadList<std::int8_t>(p, n, values);
      case PlyType::UInt8:
        return LoadList<std::uint8_t>(p, n, values);
      case PlyType::Int16:
        return LoadList<std::int16_t>(p, n, values);
      case PlyType::UInt16:
        return LoadList<std::uint16_t>(p, n, values);
      case PlyType::Int32:
        return LoadList<std::int32_t>(p, n, values);
      case PlyType::UInt32:
        return LoadList<std::uint32_t>(p, n, values);
      case PlyType::Float32:
      case PlyType::Float64:
        break; // rejected with the header
    }
    return false;
  }

  bool Skip(PlyType type, std::uint64_t n)
  {
    // Bounded chunks: a claimed length can be anything.
    std::uint64_t bytes = n * PlyTypeSize(type);
    while (bytes > 0)
    {
      const std::size_t chunk =
        static_cast<std::size_t>(std::min<std::uint64_t>(bytes, BufferedReader::DefaultCapacity));
      if (!this->Reader.Take(chunk))
      {
        return false;
      }
      bytes -= chunk;
    }
    return true;
  }

  /// Binary records have no layout beyond their bytes.
  void BeginRecord(const char*, std::uint64_t) {}
  void EndRecord() {}

  [[noreturn]] void Fail(const std::string& problem) const { this->Reader.File().Fail(problem); }

private:
  template<typename T>
  static bool LoadList(const unsigned char* p, std::size_t n, std::int64_t* values)
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      values[i] = Load<T, Swap>(p + i * sizeof(T));
    }
    return true;
  }

  BufferedReader& Reader;
};

/// ASCII values: whitespace-separated tokens, a record to a line; `false` from a read means the
/// file ended first.
class AsciiDecoder
{
public:
  explicit AsciiDecoder(BufferedReader& reader)
    : Reader(reader)
  {
  }

  /// A record's values stand on one line, and nothing else does: read across lines, a value
  /// too many or too few would shift every value after it into the wrong property.
  void BeginRecord(const char* element, std::uint64_t index)
  {
    this->RecordElement = element;
    this->RecordIndex = index;
    this->RecordLine = 0;
  }
  void EndRecord()
  {
    if (!this->Reader.RestOfLineIsBlank())
    {
      this->FailRecord(this->Reader.Line(), "has more values on its line than the header's properties");
    }
  }

  bool Integer(PlyType type, std::int64_t& value)
  {
    std::string_view token;
    if (!this->NextValue(token))
    {
      return false;
    }
    if (!ParseInteger(token, value))
    {
      this->Fail("expected an integer, found " + Quoted(token));
    }
    this->CheckRange(type, double(value), token);
    return true;
  }

  bool Real(PlyType type, double& value)
  {
    std::string_view token;
    if (!this->NextValue(token))
    {
      return false;
    }
    if (!ParseReal(token, value))
    {
      this->Fail("expected a number, found " + Quoted(token));
    }
    this->CheckRange(type, value, token);
    return true;
  }

  bool Integers(PlyType type, std::size_t n, std::int64_t* values)
  {
    for (std::size_t i = 0; i < n; ++i)
    {
      if (!this->Integer(type, values[i]))
      {
        return false;
      }
    }
    return true;
  }

  bool Skip(PlyType, std::uint64_t n)
  {
    std::string_view token;
    for (std::uint64_t i = 0; i < n; ++i)
    {
      if (!this->NextValue(token))
      {
        return false;
      }
    }
    return true;
  }

  [[noreturn]] void Fail(const std::string& problem) const
  {
    this->Reader.File().FailAtLine(this->Reader.Line(), problem);
  }

private:
  /// The record's next value; it must be on the line of the record's first.
  bool NextValue(std::string_view& token)
  {
    if (!this->Reader.NextToken(token))
    {
      return false;
    }
    if (this->RecordLine == 0)
    {
      this->RecordLine = this->Reader.Line();
    }
    else if (this->Reader.Line() != this->RecordLine)
    {
      this->FailRecord(this->RecordLine, "has fewer values on its line than the header's properties");
    }
    return true;
  }

  [[noreturn]] void FailRecord(std::uint64_t line, const std::string& problem) const
  {
    this->Reader.File().FailAtLine(
      line, std::string(this->RecordElement) + " " + std::to_string(this->RecordIndex) + " " + problem);
  }

  /// A value of an integer property must be one its type holds: text can say anything.
  void CheckRange(PlyType type, double value, std::string_view token) const
  {
    double lo = 0, hi = 0;
    const char* name = "";
    switch (type)
    {
      case PlyType::Int8: lo = INT8_MIN, hi = INT8_MAX, name = "char"; break;
      case PlyType::UInt8: hi = UINT8_MAX, name = "uchar"; break;
      case PlyType::Int16: lo = INT16_MIN, hi = INT16_MAX, name = "short"; break;
      case PlyType::UInt16: hi = UINT16_MAX, name = "ushort"; break;
      case PlyType::Int32: lo = INT32_MIN, hi = INT32_MAX, name = "int"; break;
      case PlyType::UInt32: hi = UINT32_MAX, name = "uint"; break;
      case PlyType::Float32:
      case PlyType::Float64: return;
    }
    if (!(value >= lo && value <= hi && value == std::floor(value)))
    {
      this->Fail(Quoted(token) + " is not a value of its property's type, " + name);
    }
  }

  BufferedReader& Reader;
  const char* RecordElement = "";
  std::uint64_t RecordIndex = 0;
  std::uint64_t RecordLine = 0; ///< of the record's first value; 0 before it
};

/// List lengths come from the file: a negative one is an error, and a corner list must fit in
/// one read.
template<class Decoder>
void CheckListLength(
  Decoder& decoder, std::int64_t count, bool isCorners, const char* element, std::uint64_t index)
{
  if (count < 0)
  {
    decoder.Fail(std::string(element) + " " + std::to_string(index) +
      " has a list of negative length " + std::to_string(count));
  }
  if (isCorners && count > MaxCorners)
  {
    decoder.Fail(std::string(element) + " " + std::to_string(index) + " has " +
      std::to_string(count) + " corners; at most " + std::to_string(MaxCorners) + " are supported");
  }
}

/// Reads one record of an element. `false`: the file ended first.
template<class Decoder>
bool ReadRecord(Decoder& decoder, const std::vector<Field>& fields, Record& record,
  const char* element, std::uint64_t index)
{
  decoder.BeginRecord(element, index);
  for (const Field& field : fields)
  {
    if (!field.IsList)
    {
      bool ok = field.Use == Role::None
        ? decoder.Skip(field.Type, 1)
        : decoder.Real(field.Type, record.Values[static_cast<int>(field.Use) - 1]);
      if (!ok)
      {
        return false;
      }
      continue;
    }
    std::int64_t count;
    if (!decoder.Integer(field.CountType, count))
    {
      return false;
    }
    CheckListLength(decoder, count, field.Use == Role::Corners, element, index);
    if (field.Use != Role::Corners)
    {
      if (!decoder.Skip(field.Type, static_cast<std::uint64_t>(count)))
      {
        return false;
      }
      continue;
    }
    record.CornerCount = static_cast<std::size_t>(count);
    if (!decoder.Integers(field.Type, record.CornerCount, record.Corners.data()))
    {
      return false;
    }
  }
  decoder.EndRecord();
  return true;
}

std::vector<Field> MakeFields(const PlyElement& element)
{
  std::vector<Field> fields;
  for (const PlyProperty& property : element.Properties)
  {
    fields.push_back({ property.Type, property.CountType, property.IsList, Role::None });
  }
  return fields;
}

/// Smallest number of bytes a record can take: the claimed count of an element must fit in
/// the rest of the file before anything is allocated for it. ASCII: one digit and one separator
/// per value.
std::uint64_t MinimumRecordBytes(const PlyElement& element, PlyFormat format)
{
  std::uint64_t bytes = 0;
  for (const PlyProperty& property : element.Properties)
  {
    bytes += format == PlyFormat::Ascii
      ? 2
      : PlyTypeSize(property.IsList ? property.CountType : property.Type);
  }
  return bytes;
}

FaceLayout MakeFaceLayout(const PlyElement& faces, std::size_t corners, PlyFormat format)
{
  FaceLayout layout;
  layout.Applies = format != PlyFormat::Ascii;
  for (std::size_t i = 0; i < faces.Properties.size(); ++i)
  {
    const PlyProperty& property = faces.Properties[i];
    if (i == corners)
    {
      layout.CountType = property.CountType;
      layout.IndexType = property.Type;
    }
    else
    {
      layout.Applies = layout.Applies && !property.IsList;
      (i < corners ? layout.BytesBefore : layout.BytesAfter) += PlyTypeSize(property.Type);
    }
  }
  return layout;
}

/// Index of the first property with one of `names`; Properties.size() when there is none.
std::size_t PropertyIndex(
  const PlyElement& element, std::initializer_list<const char*> names, bool wantList)
{
  for (std::size_t i = 0; i < element.Properties.size(); ++i)
  {
    for (const char* name : names)
    {
      if (element.Properties[i].Name == name && element.Properties[i].IsList == wantList)
      {
        return i;
      }
    }
  }
  return element.Properties.size();
}

/// A color component as a byte.
std::uint8_t PlyColorByte(double value, PlyType type)
{
  return ColorByte(value, type == PlyType::UInt16 ? ColorStorage::UInt16
      : (IsPlyIntegerType(type) ? ColorStorage::OtherInteger : ColorStorage::Real));
}

bool HasLists(const PlyElement& element)
{
  return std::any_of(element.Properties.begin(), element.Properties.end(),
    [](const PlyProperty& p) { return p.IsList; });
}

class PlyMesh final : public PolygonMesh
{
public:
  PlyMesh(const std::string& path, const std::string& scratchDirectory);

  VertexView Vertices() const override { return this->View; }
  void Rewind() override;
  bool NextBatch(PolygonBatch& batch) override;

private:
  std::size_t FindElement(const char* name) const;
  /// Index of the first property with one of `names`; fails naming `what` when there is none.
  std::size_t FindProperty(const PlyElement& element, std::initializer_list<const char*> names,
    bool wantList, const std::string& what) const;
  /// Gives the color properties their roles when the vertices have red, green and blue.
  void FindColors(const PlyElement& vertices);
  void CheckClaimedCount(const PlyElement& element, const std::string& what) const;
  void ReadVertexElement(const PlyElement& element, const std::string& scratchDirectory);
  bool ReadVerticesInPlace(const PlyElement& element);
  void SkipElement(const PlyElement& element, const std::vector<Field>& fields);
  /// Runs `action` with the decoder of the file's format: one dispatch per pass or batch,
  /// none per value.
  template<class Action>
  void WithDecoder(Action&& action)
  {
    switch (this->Header.Format)
    {
      case PlyFormat::Ascii:
      {
        AsciiDecoder decoder(this->Reader);
        action(decoder);
        break;
      }
      case PlyFormat::BinaryLittleEndian:
      {
        BinaryDecoder<!HostIsLittleEndian> decoder(this->Reader);
        action(decoder);
        break;
      }
      case PlyFormat::BinaryBigEndian:
      {
        BinaryDecoder<HostIsLittleEndian> decoder(this->Reader);
        action(decoder);
        break;
      }
    }
  }
  template<class Decoder>
  void ReadVertexRecords(Decoder& decoder, std::uint64_t count);
  template<class Decoder>
  void ReadFaceRecords(Decoder& decoder);
  /// Reads the next face into CurrentRecord; `false`: the file ended first.
  template<class Decoder>
  bool ReadFaceRecord(Decoder& decoder);
  template<bool Swap>
  bool ReadFaceRecord(BinaryDecoder<Swap>& decoder);

  InputFile File;
  PlyHeader Header;
  BufferedReader Reader;
  std::vector<Field> VertexFields;
  std::vector<Field> FaceFields;
  FaceLayout Layout;
  std::unique_ptr<MappedRegion> MappedVertices;
  std::optional<ScratchArray<float>> CopiedVertices;
  std::optional<ScratchArray<std::uint8_t>> CopiedColors; ///< RGBA
  int ColorComponents = 0; ///< 0 (no colors), 3 or 4
  PlyType ColorTypes[4] = {};
  VertexView View;
  std::uint64_t FaceCount = 0;
  std::uint64_t FaceOffset = 0;
  std::uint64_t FaceLine = 1;
  std::uint64_t FacesRead = 0;
  Record CurrentRecord;
  std::vector<std::uint32_t> Indices;
  std::vector<std::uint32_t> Sizes;
};

PlyMesh::PlyMesh(const std::string& path, const std::string& scratchDirectory)
  : File(path)
  , Header(ReadPlyHeader(this->File))
  , Reader(this->File, this->Header.DataOffset, this->Header.DataLine)
{
  const std::size_t vertexElement = this->FindElement("vertex");
  const std::size_t faceElement = this->FindElement("face");
  if (vertexElement == this->Header.Elements.size())
  {
    this->File.Fail("bad PLY header: no vertex element");
  }
  const PlyElement& vertices = this->Header.Elements[vertexElement];
  this->VertexFields = MakeFields(vertices);
  this->VertexFields[this->FindProperty(vertices, { "x" }, false, "'x' property")].Use = Role::X;
  this->VertexFields[this->FindProperty(vertices, { "y" }, false, "'y' property")].Use = Role::Y;
  this->VertexFields[this->FindProperty(vertices, { "z" }, false, "'z' property")].Use = Role::Z;
  this->FindColors(vertices);
  if (faceElement < this->Header.Elements.size())
  {
    const PlyElement& faces = this->Header.Elements[faceElement];
    this->FaceFields = MakeFields(faces);
    const std::size_t corners =
      this->FindProperty(faces, { "vertex_indices", "vertex_index" }, true, "vertex_indices list");
    if (!IsPlyIntegerType(faces.Properties[corners].Type))
    {
      this->File.Fail("bad PLY header: the face vertex_indices list must have an integer type");
    }
    this->FaceFields[corners].Use = Role::Corners;
    this->Layout = MakeFaceLayout(faces, corners, this->Header.Format);
  }
  if (vertices.Count > MaxVertices)
  {
    this->File.Fail("too many vertices (" + std::to_string(vertices.Count) + "; at most " +
      std::to_string(MaxVertices) + " are supported)");
  }

  // Elements come in file order: read the vertices, find where the faces start, and skip
  // whatever else is in the way.
  bool verticesDone = false;
  bool facesFound = false;
  for (std::size_t e = 0; e < this->Header.Elements.size() && !(verticesDone && facesFound); ++e)
  {
    const PlyElement& element = this->Header.Elements[e];
    if (e == vertexElement)
    {
      this->ReadVertexElement(element, scratchDirectory);
      verticesDone = true;
    }
    else if (e == faceElement)
    {
      this->FaceCount = element.Count;
      this->FaceOffset = this->Reader.Position();
      this->FaceLine = this->Reader.NextLineNumber();
      facesFound = true;
      if (!verticesDone)
      {
        this->SkipElement(element, this->FaceFields);
      }
    }
    else
    {
      this->SkipElement(element, MakeFields(element));
    }
  }
  this->Rewind();
}

std::size_t PlyMesh::FindElement(const char* name) const
{
  const auto& elements = this->Header.Elements;
  return static_cast<std::size_t>(std::find_if(elements.begin(), elements.end(),
                                    [&](const PlyElement& e) { return e.Name == name; }) -
    elements.begin());
}

std::size_t PlyMesh::FindProperty(const PlyElement& element,
  std::initializer_list<const char*> names, bool wantList, const std::string& what) const
{
  const std::size_t i = PropertyIndex(element, names, wantList);
  if (i == element.Properties.size())
  {
    this->File.Fail("bad PLY header: the " + element.Name + " element has no " + what);
  }
  return i;
}

void PlyMesh::FindColors(const PlyElement& vertices)
{
  const std::size_t none = vertices.Properties.size();
  const std::size_t found[4] = { PropertyIndex(vertices, { "red", "diffuse_red" }, false),
    PropertyIndex(vertices, { "green", "diffuse_green" }, false),
    PropertyIndex(vertices, { "blue", "diffuse_blue" }, false),
    PropertyIndex(vertices, { "alpha", "diffuse_alpha" }, false) };
  if (found[0] == none || found[1] == none || found[2] == none)
  {
    return;
  }
  this->ColorComponents = found[3] == none ? 3 : 4;
  for (int k = 0; k < this->ColorComponents; ++k)
  {
    this->VertexFields[found[k]].Use = static_cast<Role>(static_cast<int>(Role::Red) + k);
    this->ColorTypes[k] = vertices.Properties[found[k]].Type;
  }
}

void PlyMesh::CheckClaimedCount(const PlyElement& element, const std::string& what) const
{
  const std::uint64_t left =
    this->File.Size() - std::min(this->File.Size(), this->Reader.Position());
  const std::uint64_t minimum =
    std::max<std::uint64_t>(1, MinimumRecordBytes(element, this->Header.Format));
  // The last ASCII value needs no separator after it.
  const std::uint64_t slack = this->Header.Format == PlyFormat::Ascii ? 1 : 0;
  if (element.Count > (left + slack) / minimum)
  {
    this->File.Fail("truncated: the header claims " + std::to_string(element.Count) + " " + what +
      " but only " + std::to_string(left) + " bytes are left in the file");
  }
}

void PlyMesh::ReadVertexElement(const PlyElement& element, const std::string& scratchDirectory)
{
  this->CheckClaimedCount(element, "vertices");
  this->View.Count = element.Count;
  this->View.FileBacked = true; // mapped in place from the input, or copied to a ScratchArray
  if (this->ReadVerticesInPlace(element))
  {
    return;
  }
  this->CopiedVertices.emplace(scratchDirectory, static_cast<std::size_t>(3 * element.Count));
  if (this->ColorComponents > 0)
  {
    this->CopiedColors.emplace(scratchDirectory, static_cast<std::size_t>(4 * element.Count));
  }
  this->WithDecoder([&](auto& decoder) { this->ReadVertexRecords(decoder, element.Count); });
  this->View.Base = reinterpret_cast<const unsigned char*>(this->CopiedVertices->Data());
  this->View.Stride = 3 * sizeof(float);
  if (this->CopiedColors)
  {
    this->View.Colors = this->CopiedColors->Data();
    this->View.ColorStride = 4;
    this->View.ColorComponents = 4;
  }
}

bool PlyMesh::ReadVerticesInPlace(const PlyElement& element)
{
  // Zero copy when the records hold x, y, z as consecutive little-endian floats, and the
  // colors (if any) as consecutive bytes.
  if (this->Header.Format != PlyFormat::BinaryLittleEndian || !HostIsLittleEndian ||
    HasLists(element) || element.Count == 0)
  {
    return false;
  }
  std::size_t stride = 0;
  std::size_t offsets[7] = { 0, 0, 0, 0, 0, 0, 0 }; // by Role - 1
  bool typesFit = true;
  for (std::size_t i = 0; i < element.Properties.size(); ++i)
  {
    const Role use = this->VertexFields[i].Use;
    if (use != Role::None)
    {
      offsets[static_cast<int>(use) - 1] = stride;
      typesFit = typesFit &&
        element.Properties[i].Type == (use <= Role::Z ? PlyType::Float32 : PlyType::UInt8);
    }
    stride += PlyTypeSize(element.Properties[i].Type);
  }
  const auto consecutive = [&offsets](int first, int count, std::size_t size)
  {
    for (int k = 1; k < count; ++k)
    {
      if (offsets[first + k] != offsets[first] + std::size_t(k) * size)
      {
        return false;
      }
    }
    return true;
  };
  if (!typesFit || !consecutive(0, 3, sizeof(float)) || !consecutive(3, this->ColorComponents, 1))
  {
    return false;
  }
  const std::uint64_t start = this->Reader.Position();
  const std::uint64_t bytes = element.Count * stride; // fits: CheckClaimedCount passed
  this->MappedVertices = this->File.Map(start, static_cast<std::size_t>(bytes));
  this->View.Base = this->MappedVertices->Data() + offsets[0];
  this->View.Stride = stride;
  if (this->ColorComponents > 0)
  {
    this->View.Colors = this->MappedVertices->Data() + offsets[3];
    this->View.ColorStride = stride;
    this->View.ColorComponents = this->ColorComponents;
  }
  this->Reader.Seek(start + bytes);
  return true;
}

template<class Decoder>
void PlyMesh::ReadVertexRecords(Decoder& decoder, std::uint64_t count)
{
  float* out = this->CopiedVertices->Data();
  std::uint8_t* colors = this->CopiedColors ? this->CopiedColors->Data() : nullptr;
  for (std::uint64_t i = 0; i < count; ++i, out += 3)
  {
    if (!ReadRecord(decoder, this->VertexFields, this->CurrentRecord, "vertex", i))
    {
      decoder.Fail("truncated: vertex " + std::to_string(i) + " of " + std::to_string(count) +
        " ends past the end of the file");
    }
    for (int a = 0; a < 3; ++a)
    {
      out[a] = ToFloatCoordinate(this->CurrentRecord.Values[a]);
    }
    if (colors)
    {
      std::uint8_t* rgba = colors + 4 * i;
      rgba[3] = 255;
      for (int k = 0; k < this->ColorComponents; ++k)
      {
        rgba[k] = PlyColorByte(this->CurrentRecord.Values[3 + k], this->ColorTypes[k]);
      }
    }
  }
}

void PlyMesh::SkipElement(const PlyElement& element, const std::vector<Field>& fields)
{
  if (this->Header.Format != PlyFormat::Ascii && !HasLists(element))
  {
    this->CheckClaimedCount(element, "'" + element.Name + "' records");
    this->Reader.Seek(
      this->Reader.Position() + element.Count * MinimumRecordBytes(element, this->Header.Format));
    return;
  }
  this->WithDecoder(
    [&](auto& decoder)
    {
      for (std::uint64_t i = 0; i < element.Count; ++i)
      {
        if (!ReadRecord(decoder, fields, this->CurrentRecord, element.Name.c_str(), i))
        {
          decoder.Fail("truncated: " + element.Name + " " + std::to_string(i) + " of " +
            std::to_string(element.Count) + " ends past the end of the file");
        }
      }
    });
}

template<class Decoder>
void PlyMesh::ReadFaceRecords(Decoder& decoder)
{
  while (this->FacesRead < this->FaceCount && this->Sizes.size() < PolygonBatchFaces)
  {
    if (!this->ReadFaceRecord(decoder))
    {
      decoder.Fail("truncated: face " + std::to_string(this->FacesRead) + " of " +
        std::to_string(this->FaceCount) + " ends past the end of the file");
    }
    const Record& face = this->CurrentRecord;
    const std::uint64_t vertexCount = this->View.Count;
    for (std::size_t k = 0; k < face.CornerCount; ++k)
    {
      const std::int64_t corner = face.Corners[k];
      if (static_cast<std::uint64_t>(corner) >= vertexCount) // negative ones too
      {
        decoder.Fail("face " + std::to_string(this->FacesRead) + " has vertex index " +
          std::to_string(corner) + ", out of range (file has " + std::to_string(vertexCount) +
          " vertices)");
      }
      this->Indices.push_back(static_cast<std::uint32_t>(corner));
    }
    this->Sizes.push_back(static_cast<std::uint32_t>(face.CornerCount));
    ++this->FacesRead;
  }
}

template<class Decoder>
bool PlyMesh::ReadFaceRecord(Decoder& decoder)
{
  return ReadRecord(decoder, this->FaceFields, this->CurrentRecord, "face", this->FacesRead);
}

template<bool Swap>
bool PlyMesh::ReadFaceRecord(BinaryDecoder<Swap>& decoder)
{
  const FaceLayout& layout = this->Layout;
  if (!layout.Applies)
  {
    return ReadRecord(decoder, this->FaceFields, this->CurrentRecord, "face", this->FacesRead);
  }
  const unsigned char* head = this->Reader.Take(layout.BytesBefore + PlyTypeSize(layout.CountType));
  if (!head)
  {
    return false;
  }
  const std::int64_t count =
    LoadAs<std::int64_t, Swap>(head + layout.BytesBefore, layout.CountType);
  CheckListLength(decoder, count, true, "face", this->FacesRead);
  this->CurrentRecord.CornerCount = static_cast<std::size_t>(count);
  return decoder.Integers(
           layout.IndexType, this->CurrentRecord.CornerCount, this->CurrentRecord.Corners.data()) &&
    this->Reader.Take(layout.BytesAfter);
}

void PlyMesh::Rewind()
{
  this->Reader.Seek(this->FaceOffset, this->FaceLine);
  this->FacesRead = 0;
}

bool PlyMesh::NextBatch(PolygonBatch& batch)
{
  this->Indices.clear();
  this->Sizes.clear();
  this->WithDecoder([&](auto& decoder) { this->ReadFaceRecords(decoder); });
  batch.Indices = this->Indices.data();
  batch.Sizes = this->Sizes.data();
  batch.Count = this->Sizes.size();
  return batch.Count > 0;
}

} // namespace

std::unique_ptr<PolygonMesh> OpenPlyMesh(
  const std::string& path, const std::string& scratchDirectory)
{
  return std::make_unique<PlyMesh>(path, scratchDirectory);
}

} // namespace atp
