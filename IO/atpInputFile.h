// An input mesh file opened for reading, and the one place that formats input error messages
// ("<path>: <problem>", "<path> line <n>: <problem>").
#ifndef atpInputFile_h
#define atpInputFile_h

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

namespace atp
{

/// A read-only memory map of part of a file; unmapped on destruction.
class MappedRegion
{
public:
  MappedRegion(void* mapping, std::size_t mappedBytes, const unsigned char* data);
  ~MappedRegion();
  MappedRegion(const MappedRegion&) = delete;
  MappedRegion& operator=(const MappedRegion&) = delete;

  /// The first byte of the region asked for (the mapping itself starts on a page boundary).
  const unsigned char* Data() const { return this->First; }

private:
  void* Mapping;
  std::size_t MappedBytes;
  const unsigned char* First;
};

/// Text from an input file, quoted for a message: bytes that are not printable ASCII (a NUL
/// would end the message where it is printed) as \xNN, and only the first 40 characters of a
/// longer token.
std::string Quoted(std::string_view text);

class InputFile
{
public:
  /// Opens a regular file; throws InputError when it is missing, unreadable or not a file.
  explicit InputFile(const std::string& path);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  const std::string& Path() const { return this->Name; }
  std::uint64_t Size() const { return this->Bytes; }

  /// Reads up to `n` bytes at `offset`; fewer only at the end of the file.
  std::size_t ReadAt(std::uint64_t offset, void* buffer, std::size_t n) const;

  /// Maps bytes [offset, offset + n), n > 0, read-only; the caller has checked they are in the
  /// file.
  std::unique_ptr<MappedRegion> Map(std::uint64_t offset, std::size_t n) const;

  [[noreturn]] void Fail(const std::string& problem) const;
  [[noreturn]] void FailAtLine(std::uint64_t line, const std::string& problem) const;

private:
  std::string Name;
  int Descriptor = -1;
  std::uint64_t Bytes = 0;
};

} // namespace atp

#endif
