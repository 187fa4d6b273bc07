// A VTK XML file written zlib-compressed with its data appended raw, for tests that forge the
// compressed-array headers VTK's readers trust.
#ifndef CompressedXmlFile_h
#define CompressedXmlFile_h

#include <vtkXMLWriter.h>

#include <fstream>
#include <iterator>
#include <string>

namespace atp
{
namespace testing
{

struct CompressedXmlFile
{
  std::string Bytes;
  /// Where the first appended array's header starts: its block count, block size and last
  /// block's size, little-endian words of the header type's width.
  std::size_t Header = std::string::npos;
};

/// Writes `writer`'s input to `path` (zlib, appended raw, 32- or 64-bit header words) and reads
/// the file back.
inline CompressedXmlFile WriteCompressed(vtkXMLWriter* writer, const std::string& path, bool wideHeaders)
{
  writer->SetCompressorTypeToZLib();
  writer->SetDataModeToAppended();
  writer->SetEncodeAppendedData(false);
  writer->SetHeaderType(wideHeaders ? vtkXMLWriter::UInt64 : vtkXMLWriter::UInt32);
  writer->SetFileName(path.c_str());
  CompressedXmlFile file;
  if (writer->Write() != 1)
  {
    return file;
  }
  std::ifstream in(path, std::ios::binary);
  file.Bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  const std::size_t appended = file.Bytes.find("<AppendedData");
  const std::size_t mark = appended == std::string::npos ? appended : file.Bytes.find('_', appended);
  file.Header = mark == std::string::npos ? mark : mark + 1;
  return file;
}

} // namespace testing
} // namespace atp

#endif
