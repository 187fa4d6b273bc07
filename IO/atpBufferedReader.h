// Sequential reading of an InputFile through one large buffer (pread of a few MiB at a time),
// for binary records and for text tokens and lines. Resident memory stays at the buffer size
// whatever the file size, and the hot loops see plain pointers, not streams.
#ifndef atpBufferedReader_h
#define atpBufferedReader_h

#include "atpInputFile.h"

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace atp
{

class BufferedReader
{
public:
  static constexpr std::size_t DefaultCapacity = std::size_t(4) << 20;

  BufferedReader(const InputFile& file, std::uint64_t offset, std::uint64_t line = 1,
    std::size_t capacity = DefaultCapacity);

  /// Restarts at a file offset; `line` is the line number there, for messages.
  void Seek(std::uint64_t offset, std::uint64_t line = 1);

  /// File offset of the next unread byte.
  std::uint64_t Position() const { return this->BufferOffset + this->Next; }

  /// The next `n` bytes (n <= capacity), or nullptr when the file ends first.
  const unsigned char* Take(std::size_t n)
  {
    if (this->End - this->Next < n && !this->Fill(n))
    {
      return nullptr;
    }
    const unsigned char* p = this->Buffer.data() + this->Next;
    this->Next += n;
    return p;
  }

  /// Lines end with "\n", "\r\n" or a lone "\r" (classic Mac OS text), for lines and for the
  /// line numbers of tokens alike.

  /// The next whitespace-separated token; false at the end of the file.
  bool NextToken(std::string_view& token);

  /// Whether only blanks are left on the current line (the file's end ends it too). Reads past
  /// the blanks, not the line's end.
  bool RestOfLineIsBlank();

  /// The rest of the current line without its line ending; false at the end of the file.
  bool NextLine(std::string_view& line);

  /// Line number of the last token or line returned.
  std::uint64_t Line() const { return this->ReturnedLine; }

  /// Line number of the next unread byte.
  std::uint64_t NextLineNumber() const { return this->CurrentLine; }

  const InputFile& File() const { return this->Input; }

private:
  /// Makes at least `need` unread bytes available if the file has them; false if it has not.
  bool Fill(std::size_t need);
  [[noreturn]] void FailTooLong(const char* what) const;

  const InputFile& Input;
  std::vector<unsigned char> Buffer;
  std::uint64_t BufferOffset = 0; // file offset of Buffer[0]
  std::size_t Next = 0;           // first unread byte in Buffer
  std::size_t End = 0;            // end of valid bytes in Buffer
  bool AtEndOfFile = false;
  std::uint64_t CurrentLine = 1;
  std::uint64_t ReturnedLine = 1;
  /// The last byte read between tokens was a carriage return, which counted as a line end: a
  /// "\n" right after it belongs to the same one.
  bool AfterCarriageReturn = false;
};

} // namespace atp

#endif
