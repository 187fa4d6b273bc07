#include "atpBufferedReader.h"

#include <algorithm>

#include <cstring>

namespace atp
{
namespace
{
bool IsSpace(unsigned char c)
{
  return c == ' ' || c == '\n' || c == '\r' || c == '\t' || c == '\v' || c == '\f';
}
} // namespace

BufferedReader::BufferedReader(
  const InputFile& file, std::uint64_t offset, std::uint64_t line, std::size_t capacity)
  : Input(file)
  // A small file gets a small buffer: no MiBs zeroed to read a few bytes.
  , Buffer(std::size_t(std::min<std::uint64_t>(capacity, file.Size() + 1)))
{
  this->Seek(offset, line);
}

void BufferedReader::Seek(std::uint64_t offset, std::uint64_t line)
{
  this->BufferOffset = offset;
  this->Next = 0;
  this->End = 0;
  this->AtEndOfFile = false;
  this->CurrentLine = line;
  this->ReturnedLine = line;
  this->AfterCarriageReturn = false;
}

bool BufferedReader::Fill(std::size_t need)
{
  if (need > this->Buffer.size())
  {
    return false;
  }
  if (this->Next > 0)
  {
    std::memmove(this->Buffer.data(), this->Buffer.data() + this->Next, this->End - this->Next);
    this->BufferOffset += this->Next;
    this->End -= this->Next;
    this->Next = 0;
  }
  while (this->End < need && !this->AtEndOfFile)
  {
    std::size_t got = this->Input.ReadAt(this->BufferOffset + this->End,
      this->Buffer.data() + this->End, this->Buffer.size() - this->End);
    this->End += got;
    this->AtEndOfFile = got == 0;
  }
  return this->End >= need;
}

void BufferedReader::FailTooLong(const char* what) const
{
  this->Input.FailAtLine(this->CurrentLine,
    std::string(what) + " longer than " + std::to_string(this->Buffer.size()) + " bytes");
}

bool BufferedReader::NextToken(std::string_view& token)
{
  for (;;)
  {
    while (this->Next < this->End && IsSpace(this->Buffer[this->Next]))
    {
      const unsigned char c = this->Buffer[this->Next];
      this->CurrentLine += unsigned(c == '\r') | unsigned(c == '\n' && !this->AfterCarriageReturn);
      this->AfterCarriageReturn = c == '\r';
      ++this->Next;
    }
    if (this->Next == this->End)
    {
      if (!this->Fill(1))
      {
        return false;
      }
      continue;
    }
    std::size_t end = this->Next;
    while (end < this->End && !IsSpace(this->Buffer[end]))
    {
      ++end;
    }
    if (end == this->End && !this->AtEndOfFile)
    {
      // The token may go on past the buffer: read more and look again.
      if (this->End - this->Next == this->Buffer.size())
      {
        this->FailTooLong("token");
      }
      this->Fill(this->End - this->Next + 1);
      continue;
    }
    token = std::string_view(
      reinterpret_cast<const char*>(this->Buffer.data() + this->Next), end - this->Next);
    this->ReturnedLine = this->CurrentLine;
    this->Next = end;
    this->AfterCarriageReturn = false;
    return true;
  }
}

bool BufferedReader::RestOfLineIsBlank()
{
  for (;;)
  {
    while (this->Next < this->End && IsSpace(this->Buffer[this->Next]) &&
      this->Buffer[this->Next] != '\n' && this->Buffer[this->Next] != '\r')
    {
      ++this->Next;
    }
    if (this->Next < this->End)
    {
      return this->Buffer[this->Next] == '\n' || this->Buffer[this->Next] == '\r';
    }
    if (!this->Fill(1))
    {
      return true;
    }
  }
}

bool BufferedReader::NextLine(std::string_view& line)
{
  for (;;)
  {
    if (this->Next == this->End && !this->Fill(1))
    {
      return false;
    }
    const bool restOfLineEnd = this->AfterCarriageReturn && this->Buffer[this->Next] == '\n';
    this->AfterCarriageReturn = false;
    if (restOfLineEnd)
    {
      ++this->Next; // the "\n" of a "\r\n" whose "\r" ended the buffer and the line before
      continue;
    }
    const unsigned char* start = this->Buffer.data() + this->Next;
    const std::size_t available = this->End - this->Next;
    const auto* newline = static_cast<const unsigned char*>(std::memchr(start, '\n', available));
    std::size_t length = newline ? static_cast<std::size_t>(newline - start) : available;
    const auto* carriage = static_cast<const unsigned char*>(std::memchr(start, '\r', length));
    // Read on when the line may go on past the buffer, or when a "\r" is its last byte: whether a
    // "\n" follows decides where the next line starts.
    const bool lastIsCarriage = carriage && carriage + 1 == start + available;
    const bool full = available == this->Buffer.size();
    if (!this->AtEndOfFile && ((lastIsCarriage && !full) || (!carriage && !newline)))
    {
      if (full)
      {
        this->FailTooLong("line");
      }
      this->Fill(available + 1);
      continue;
    }
    std::size_t consumed = length + (newline ? 1 : 0);
    if (carriage)
    {
      length = static_cast<std::size_t>(carriage - start);
      const bool crlf = length + 1 < available && carriage[1] == '\n';
      consumed = length + (crlf ? 2 : 1);
      // A "\r" that ends a full buffer ends its line either way: a "\n" after it, read with the
      // next line, belongs to this one.
      this->AfterCarriageReturn = lastIsCarriage;
    }
    this->Next += consumed;
    line = std::string_view(reinterpret_cast<const char*>(start), length);
    this->ReturnedLine = this->CurrentLine;
    this->CurrentLine += carriage || newline ? 1 : 0;
    return true;
  }
}

} // namespace atp
