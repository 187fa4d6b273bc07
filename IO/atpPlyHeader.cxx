#include "atpPlyHeader.h"

#include "atpTextParsing.h"

#include <algorithm>
#include <charconv>
#include <string_view>

namespace atp
{
namespace
{
// Real headers are a few hundred bytes; this bounds what a file without end_header costs us.
constexpr std::size_t MaxHeaderBytes = std::size_t(1) << 20;

std::vector<std::string_view> SplitWords(std::string_view line)
{
  std::vector<std::string_view> words;
  for (std::string_view word = NextWord(line); !word.empty(); word = NextWord(line))
  {
    words.push_back(word);
  }
  return words;
}

bool ParseType(std::string_view name, PlyType& type)
{
  static const struct
  {
    const char* Name;
    PlyType Type;
  } names[] = { { "char", PlyType::Int8 }, { "int8", PlyType::Int8 }, { "uchar", PlyType::UInt8 },
    { "uint8", PlyType::UInt8 }, { "short", PlyType::Int16 }, { "int16", PlyType::Int16 },
    { "ushort", PlyType::UInt16 }, { "uint16", PlyType::UInt16 }, { "int", PlyType::Int32 },
    { "int32", PlyType::Int32 }, { "uint", PlyType::UInt32 }, { "uint32", PlyType::UInt32 },
    { "float", PlyType::Float32 }, { "float32", PlyType::Float32 }, { "double", PlyType::Float64 },
    { "float64", PlyType::Float64 } };
  for (const auto& entry : names)
  {
    if (name == entry.Name)
    {
      type = entry.Type;
      return true;
    }
  }
  return false;
}
} // namespace

PlyHeader ReadPlyHeader(const InputFile& file)
{
  std::string text(
    static_cast<std::size_t>(std::min<std::uint64_t>(file.Size(), MaxHeaderBytes)), '\0');
  text.resize(file.ReadAt(0, text.data(), text.size()));

  PlyHeader header;
  auto fail = [&](std::uint64_t line, const std::string& problem)
  { file.Fail("bad PLY header, line " + std::to_string(line) + ": " + problem); };
  auto type = [&](std::uint64_t line, std::string_view name)
  {
    PlyType t;
    if (!ParseType(name, t))
    {
      file.Fail("unsupported PLY property type " + Quoted(name) + " (line " +
        std::to_string(line) + ")");
    }
    return t;
  };

  // Lines end with "\n" or "\r\n" (NextWord reads the "\r" as a blank), or with a lone "\r"
  // (classic Mac OS) when the first one does: a binary body may start with any byte.
  const std::size_t firstEnd = text.find_first_of("\r\n");
  const char lineEnd = firstEnd != std::string::npos && text[firstEnd] == '\r' &&
      (firstEnd + 1 == text.size() || text[firstEnd + 1] != '\n')
    ? '\r'
    : '\n';
  std::size_t lineStart = 0;
  bool formatSeen = false;
  for (std::uint64_t line = 1;; ++line)
  {
    std::size_t newline = text.find(lineEnd, lineStart);
    if (newline == std::string::npos)
    {
      if (line == 1 && text.compare(0, 3, "ply") != 0)
      {
        file.Fail("bad PLY header: the file does not start with 'ply'");
      }
      file.Fail("bad PLY header: no end_header line" +
        std::string(text.size() == MaxHeaderBytes ? " in the first MiB" : ""));
    }
    std::vector<std::string_view> words =
      SplitWords(std::string_view(text).substr(lineStart, newline - lineStart));
    lineStart = newline + 1;

    if (line == 1)
    {
      if (words.size() != 1 || words[0] != "ply")
      {
        file.Fail("bad PLY header: the file does not start with 'ply'");
      }
      continue;
    }
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info")
    {
      continue;
    }
    if (words[0] == "end_header")
    {
      if (!formatSeen)
      {
        fail(line, "no format line");
      }
      header.DataOffset = lineStart;
      header.DataLine = line + 1;
      return header;
    }
    if (words[0] == "format")
    {
      if (words.size() != 3 || words[2] != "1.0")
      {
        fail(line, "expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
      }
      if (words[1] == "ascii")
      {
        header.Format = PlyFormat::Ascii;
      }
      else if (words[1] == "binary_little_endian")
      {
        header.Format = PlyFormat::BinaryLittleEndian;
      }
      else if (words[1] == "binary_big_endian")
      {
        header.Format = PlyFormat::BinaryBigEndian;
      }
      else
      {
        fail(line, "unknown format " + Quoted(words[1]));
      }
      formatSeen = true;
    }
    else if (words[0] == "element")
    {
      PlyElement element;
      const char* end = words.size() == 3 ? words[2].data() + words[2].size() : nullptr;
      // A count past 2^64 is out of range, not zero.
      const std::from_chars_result count =
        end ? std::from_chars(words[2].data(), end, element.Count) : std::from_chars_result{};
      if (!end || count.ptr != end || count.ec != std::errc())
      {
        fail(line, "expected 'element <name> <count>'");
      }
      element.Name = std::string(words[1]);
      header.Elements.push_back(std::move(element));
    }
    else if (words[0] == "property")
    {
      if (header.Elements.empty())
      {
        fail(line, "property before any element");
      }
      PlyProperty property;
      if (words.size() == 5 && words[1] == "list")
      {
        property.IsList = true;
        property.CountType = type(line, words[2]);
        property.Type = type(line, words[3]);
        property.Name = std::string(words[4]);
        if (!IsPlyIntegerType(property.CountType))
        {
          fail(line, "list count type must be an integer type");
        }
      }
      else if (words.size() == 3 && words[1] != "list")
      {
        property.Type = type(line, words[1]);
        property.Name = std::string(words[2]);
      }
      else
      {
        fail(line, "expected 'property <type> <name>' or 'property list <type> <type> <name>'");
      }
      header.Elements.back().Properties.push_back(std::move(property));
    }
    else
    {
      fail(line, "unexpected " + Quoted(words[0]));
    }
  }
}

} // namespace atp
