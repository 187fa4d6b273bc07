#include "atpVtkXmlCheck.h"

#include "atpInputFile.h"

#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLReader.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

namespace atp
{
namespace
{

bool Is(const char* text, const char* expected)
{
  return text && std::strcmp(text, expected) == 0;
}

/// The most a compressor's block can grow by decompressing (deflate's limit is about 1032:1,
/// LZ4's about 255:1; LZMA and anything else are given a loose bound).
double MostExpansion(const char* compressor)
{
  if (Is(compressor, "vtkZLibDataCompressor"))
  {
    return 1032;
  }
  if (Is(compressor, "vtkLZ4DataCompressor"))
  {
    return 256;
  }
  return 65536;
}

/// The file's layout of binary data, read from its root element.
struct Layout
{
  const char* Compressor = nullptr; ///< null when not compressed
  int Word = 4;                     ///< bytes of a header word (header_type)
  bool BigEndian = false;
  bool AppendedBase64 = false;      ///< the AppendedData section is base64
  std::uint64_t AppendedStart = 0;  ///< the file offset of the appended data
};

/// Decodes base64 text up to the first character that is not base64 (padding, or what follows),
/// a last group of 2 or 3 characters giving its 1 or 2 bytes.
std::vector<unsigned char> DecodeBase64(const std::string& text)
{
  std::vector<unsigned char> bytes;
  std::uint32_t bits = 0;
  int count = 0;
  for (const char c : text)
  {
    int value = -1;
    if (c >= 'A' && c <= 'Z')
      value = c - 'A';
    else if (c >= 'a' && c <= 'z')
      value = c - 'a' + 26;
    else if (c >= '0' && c <= '9')
      value = c - '0' + 52;
    else if (c == '+')
      value = 62;
    else if (c == '/')
      value = 63;
    if (value < 0)
    {
      break;
    }
    bits = (bits << 6) | std::uint32_t(value);
    if (++count == 4)
    {
      bytes.push_back(static_cast<unsigned char>(bits >> 16));
      bytes.push_back(static_cast<unsigned char>(bits >> 8));
      bytes.push_back(static_cast<unsigned char>(bits));
      bits = 0;
      count = 0;
    }
  }
  if (count >= 2)
  {
    bits <<= 6 * (4 - count);
    bytes.push_back(static_cast<unsigned char>(bits >> 16));
    if (count == 3)
    {
      bytes.push_back(static_cast<unsigned char>(bits >> 8));
    }
  }
  return bytes;
}

class Checker
{
public:
  Checker(vtkXMLReader* reader, const InputFile& file)
    : File(file)
    , Parser(reader->GetXMLParser())
  {
  }

  void Run()
  {
    vtkXMLDataElement* root = this->Parser ? this->Parser->GetRootElement() : nullptr;
    const char* type = root ? root->GetAttribute("type") : nullptr;
    vtkXMLDataElement* dataset = type ? root->FindNestedElementWithName(type) : nullptr;
    if (!dataset)
    {
      return; // VTK reports what is wrong with such a file
    }
    this->Format.Compressor = root->GetAttribute("compressor");
    if (this->Format.Compressor && !*this->Format.Compressor)
    {
      this->Format.Compressor = nullptr;
    }
    this->Format.Word = Is(root->GetAttribute("header_type"), "UInt64") ? 8 : 4;
    this->Format.BigEndian = Is(root->GetAttribute("byte_order"), "BigEndian");
    if (vtkXMLDataElement* appended = root->FindNestedElementWithName("AppendedData"))
    {
      this->Format.AppendedBase64 = !Is(appended->GetAttribute("encoding"), "raw");
      this->Format.AppendedStart = std::uint64_t(std::max<vtkTypeInt64>(0, this->Parser->GetAppendedDataPosition()));
    }
    if (Is(type, "ImageData"))
    {
      for (const char* attribute : { "Origin", "Spacing", "Direction" })
      {
        this->CheckFinite(dataset, attribute);
      }
    }
    for (int i = 0; i < dataset->GetNumberOfNestedElements(); ++i)
    {
      vtkXMLDataElement* piece = dataset->GetNestedElement(i);
      if (Is(piece->GetName(), "Piece"))
      {
        this->CheckCounts(piece);
        this->CheckArrays(piece);
      }
    }
  }

private:
  [[noreturn]] void Fail(const std::string& problem) const { this->File.Fail(problem); }

  std::string NameOf(vtkXMLDataElement* array, vtkXMLDataElement* parent) const
  {
    const char* name = array->GetAttribute("Name");
    return name ? std::string("array '") + name + "'" : std::string("array of ") + parent->GetName();
  }

  void CheckFinite(vtkXMLDataElement* element, const char* attribute) const
  {
    const char* text = element->GetAttribute(attribute);
    std::istringstream values(text ? text : "");
    std::string token;
    while (values >> token)
    {
      char* end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (!std::isfinite(value) || *end != '\0')
      {
        this->Fail(std::string("its ") + attribute + " '" + text + "' is not finite numbers");
      }
    }
  }

  /// A piece's points and cells each take a byte of the file at the very least (an ASCII digit,
  /// an Int8), times what decompression can make of a byte.
  void CheckCounts(vtkXMLDataElement* piece) const
  {
    const double most = double(this->File.Size()) * (this->Format.Compressor ? MostExpansion(this->Format.Compressor) : 1);
    for (const char* attribute : { "NumberOfPoints", "NumberOfVerts", "NumberOfLines", "NumberOfStrips", "NumberOfPolys" })
    {
      const char* text = piece->GetAttribute(attribute);
      if (text && std::strtod(text, nullptr) > most)
      {
        this->Fail(std::string("it declares ") + attribute + "=\"" + text + "\", more than its " +
          std::to_string(this->File.Size()) + " bytes can hold");
      }
    }
    // An image's points are implicit: only arrays over them take bytes.
    vtkXMLDataElement* pointData = piece->FindNestedElementWithName("PointData");
    int extent[6];
    if (pointData && pointData->FindNestedElementWithName("DataArray") &&
      piece->GetVectorAttribute("Extent", 6, extent) == 6)
    {
      double points = 1;
      for (int axis = 0; axis < 3; ++axis)
      {
        points *= std::max(0.0, double(extent[2 * axis + 1]) - extent[2 * axis] + 1);
      }
      if (points > most)
      {
        this->Fail("its extent holds " + std::to_string(std::uint64_t(points)) + " points, more than its " +
          std::to_string(this->File.Size()) + " bytes can hold");
      }
    }
  }

  void CheckArrays(vtkXMLDataElement* element)
  {
    for (int i = 0; i < element->GetNumberOfNestedElements(); ++i)
    {
      vtkXMLDataElement* child = element->GetNestedElement(i);
      if (Is(child->GetName(), "FieldData"))
      {
        continue; // not read as points, cells or attributes
      }
      if (Is(child->GetName(), "DataArray"))
      {
        this->CheckArray(child, element);
      }
      else
      {
        this->CheckArrays(child);
      }
    }
  }

  void CheckArray(vtkXMLDataElement* array, vtkXMLDataElement* parent)
  {
    static const char* const numeric[] = { "Int8", "UInt8", "Int16", "UInt16", "Int32", "UInt32",
      "Int64", "UInt64", "Float32", "Float64" };
    const char* type = array->GetAttribute("type");
    if (std::none_of(std::begin(numeric), std::end(numeric), [&](const char* t) { return Is(type, t); }) &&
      this->MustBeNumeric(array, parent))
    {
      this->Fail("its " + this->NameOf(array, parent) + " has type '" + (type ? type : "") +
        "' (expected one of Int8 to UInt64, Float32, Float64)");
    }
    if (Is(parent->GetName(), "Points"))
    {
      int components = 1; // VTK's default for an array that does not say
      array->GetScalarAttribute("NumberOfComponents", components);
      if (components != 3)
      {
        this->Fail("points with " + std::to_string(components) + " components (a point has 3)");
      }
    }
    const char* format = array->GetAttribute("format");
    if (this->Format.Compressor && (Is(format, "appended") || Is(format, "binary")))
    {
      this->CheckCompressedHeader(array, parent, Is(format, "appended"));
    }
  }

  /// Points and cells are numbers; so is an array of point or cell data that its parent names as
  /// an attribute (Scalars="name", ...): VTK 9.1 crashes setting a string array as the active
  /// scalars. Other arrays of strings or bits ride along unread.
  bool MustBeNumeric(vtkXMLDataElement* array, vtkXMLDataElement* parent) const
  {
    if (!Is(parent->GetName(), "PointData") && !Is(parent->GetName(), "CellData"))
    {
      return true;
    }
    const char* name = array->GetAttribute("Name");
    for (const char* attribute : { "Scalars", "Vectors", "Normals", "Tensors", "TCoords", "GlobalIds", "PedigreeIds", "EdgeFlag", "Tangents", "RationalWeights", "HigherOrderDegrees" })
    {
      if (name && Is(parent->GetAttribute(attribute), name))
      {
        return true;
      }
    }
    return false;
  }

  /// Reads `bytes` of the array's binary data from its start (decoding base64), or fewer when
  /// the file ends first.
  std::vector<unsigned char> ReadData(std::uint64_t start, bool base64, std::size_t bytes) const
  {
    const std::size_t stored = base64 ? (bytes + 2) / 3 * 4 : bytes;
    std::string text(stored, '\0');
    text.resize(this->File.ReadAt(start, &text[0], stored));
    if (!base64)
    {
      return std::vector<unsigned char>(text.begin(), text.end());
    }
    std::vector<unsigned char> decoded = DecodeBase64(text);
    decoded.resize(std::min(decoded.size(), bytes));
    return decoded;
  }

  std::uint64_t Word(const unsigned char* bytes) const
  {
    std::uint64_t value = 0;
    for (int i = 0; i < this->Format.Word; ++i)
    {
      const int k = this->Format.BigEndian ? i : this->Format.Word - 1 - i;
      value = (value << 8) | bytes[k];
    }
    return value;
  }

  /// VTK reads a compressed array's header (block count, block size, last block's size, then
  /// each block's compressed size) and allocates what it says before it reads the blocks.
  void CheckCompressedHeader(vtkXMLDataElement* array, vtkXMLDataElement* parent, bool appended)
  {
    std::uint64_t start = 0;
    bool base64 = true;
    if (appended)
    {
      vtkTypeInt64 offset = 0;
      if (!array->GetScalarAttribute("offset", offset) || offset < 0)
      {
        return; // VTK reports it
      }
      start = this->Format.AppendedStart + std::uint64_t(offset);
      base64 = this->Format.AppendedBase64;
    }
    else
    {
      // Inline: after the element's opening tag and any white space.
      const std::uint64_t tag = std::uint64_t(std::max<vtkTypeInt64>(0, array->GetXMLByteIndex()));
      char buffer[4096];
      const std::size_t read = this->File.ReadAt(tag, buffer, sizeof buffer);
      const char* close = static_cast<const char*>(std::memchr(buffer, '>', read));
      if (!close)
      {
        return;
      }
      std::size_t at = std::size_t(close - buffer) + 1;
      while (at < read && std::strchr(" \t\r\n", buffer[at]))
      {
        ++at;
      }
      start = tag + at;
    }
    const int word = this->Format.Word;
    const std::vector<unsigned char> first = this->ReadData(start, base64, 3 * std::size_t(word));
    if (first.size() < 3 * std::size_t(word))
    {
      this->Fail("its compressed " + this->NameOf(array, parent) + " has a truncated header");
    }
    const std::uint64_t blocks = this->Word(&first[0]);
    const std::uint64_t blockSize = this->Word(&first[std::size_t(word)]);
    const std::uint64_t lastSize = this->Word(&first[2 * std::size_t(word)]);
    const std::uint64_t left = this->File.Size() > start ? this->File.Size() - start : 0;
    const double headerBytes = (3.0 + double(blocks)) * word * (base64 ? 4.0 / 3 : 1);
    if (headerBytes > double(left))
    {
      this->Fail("its compressed " + this->NameOf(array, parent) + " claims " + std::to_string(blocks) +
        " blocks, more than the file holds");
    }
    const std::size_t words = 3 + std::size_t(blocks);
    const std::vector<unsigned char> header = this->ReadData(start, base64, words * std::size_t(word));
    if (header.size() < words * std::size_t(word))
    {
      this->Fail("its compressed " + this->NameOf(array, parent) + " has a truncated header");
    }
    double compressed = 0;
    const double expansion = MostExpansion(this->Format.Compressor);
    for (std::uint64_t b = 0; b < blocks; ++b)
    {
      const double size = double(this->Word(&header[std::size_t(3 + b) * std::size_t(word)]));
      const double uncompressed = double(b + 1 == blocks && lastSize != 0 ? lastSize : blockSize);
      compressed += size;
      if (uncompressed > expansion * size + 1024)
      {
        this->Fail("its compressed " + this->NameOf(array, parent) + " claims a block of " +
          std::to_string(std::uint64_t(uncompressed)) + " bytes stored in " +
          std::to_string(std::uint64_t(size)));
      }
    }
    if (headerBytes + compressed * (base64 ? 4.0 / 3 : 1) > double(left) + 4)
    {
      this->Fail("its compressed " + this->NameOf(array, parent) + " claims more bytes than the file holds");
    }
  }

  const InputFile& File;
  vtkXMLDataParser* Parser;
  Layout Format;
};

} // namespace

void CheckVtkXmlFile(vtkXMLReader* reader, const InputFile& file)
{
  Checker(reader, file).Run();
}

} // namespace atp
