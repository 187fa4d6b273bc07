#include "atpInputFile.h"

#include "atpTriangleSource.h" // InputError

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace atp
{

MappedRegion::MappedRegion(void* mapping, std::size_t mappedBytes, const unsigned char* data)
  : Mapping(mapping)
  , MappedBytes(mappedBytes)
  , First(data)
{
}

MappedRegion::~MappedRegion()
{
  ::munmap(this->Mapping, this->MappedBytes);
}

InputFile::InputFile(const std::string& path)
  : Name(path)
{
  // Non-blocking: opening a FIFO would wait for a writer before the check below refuses it.
  // Reads of a regular file ignore the flag.
  this->Descriptor = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (this->Descriptor < 0)
  {
    this->Fail(std::string("cannot open: ") + std::strerror(errno));
  }
  struct stat info;
  if (::fstat(this->Descriptor, &info) != 0)
  {
    int error = errno;
    ::close(this->Descriptor);
    this->Fail(std::string("cannot read: ") + std::strerror(error));
  }
  if (!S_ISREG(info.st_mode))
  {
    ::close(this->Descriptor);
    this->Fail("not a regular file");
  }
  this->Bytes = static_cast<std::uint64_t>(info.st_size);
  // Readers go front to back: let the kernel read ahead aggressively.
  ::posix_fadvise(this->Descriptor, 0, 0, POSIX_FADV_SEQUENTIAL);
}

InputFile::~InputFile()
{
  ::close(this->Descriptor);
}

std::size_t InputFile::ReadAt(std::uint64_t offset, void* buffer, std::size_t n) const
{
  std::size_t done = 0;
  while (done < n)
  {
    ssize_t got = ::pread(this->Descriptor, static_cast<char*>(buffer) + done, n - done,
      static_cast<off_t>(offset + done));
    if (got < 0)
    {
      if (errno == EINTR)
      {
        continue;
      }
      this->Fail(std::string("read error: ") + std::strerror(errno));
    }
    if (got == 0)
    {
      break;
    }
    done += static_cast<std::size_t>(got);
  }
  return done;
}

std::unique_ptr<MappedRegion> InputFile::Map(std::uint64_t offset, std::size_t n) const
{
  const std::uint64_t page = static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
  const std::uint64_t start = offset - offset % page;
  const std::size_t length = static_cast<std::size_t>(offset - start) + n;
  void* mapping =
    ::mmap(nullptr, length, PROT_READ, MAP_PRIVATE, this->Descriptor, static_cast<off_t>(start));
  if (mapping == MAP_FAILED)
  {
    this->Fail(std::string("cannot map: ") + std::strerror(errno));
  }
  return std::make_unique<MappedRegion>(
    mapping, length, static_cast<const unsigned char*>(mapping) + (offset - start));
}

std::string Quoted(std::string_view text)
{
  constexpr std::size_t Longest = 40;
  std::string quoted = "'";
  for (std::size_t i = 0; i < text.size() && i < Longest; ++i)
  {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f)
    {
      quoted += char(c);
    }
    else
    {
      static const char digits[] = "0123456789abcdef";
      quoted += "\\x";
      quoted += digits[c >> 4];
      quoted += digits[c & 15];
    }
  }
  return quoted + (text.size() > Longest ? "...'" : "'");
}

void InputFile::Fail(const std::string& problem) const
{
  throw InputError(this->Name + ": " + problem);
}

void InputFile::FailAtLine(std::uint64_t line, const std::string& problem) const
{
  throw InputError(this->Name + " line " + std::to_string(line) + ": " + problem);
}

} // namespace atp
