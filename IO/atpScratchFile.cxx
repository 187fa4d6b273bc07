#include "atpScratchFile.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <utility>
#include <fcntl.h>
#include <stdexcept>
#include <unistd.h>
#include <vector>

namespace atp
{
namespace
{
std::string DefaultDirectory()
{
  const char* tmp = std::getenv("TMPDIR");
  return (tmp && *tmp) ? tmp : "/tmp";
}
} // namespace

ScratchFile::ScratchFile(const std::string& directory)
  : Directory(directory.empty() ? DefaultDirectory() : directory)
{
  // A file that never has a name: a build killed at any point, even between creating a file
  // and unlinking it, leaves nothing behind. File systems without O_TMPFILE get a named file,
  // unlinked at once.
  Fd = ::open(Directory.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
  if (Fd < 0 && (errno == EOPNOTSUPP || errno == EISDIR || errno == EINVAL))
  {
    std::string name = Directory + "/atp-scratch-XXXXXX";
    std::vector<char> buffer(name.begin(), name.end());
    buffer.push_back('\0');
    Fd = ::mkstemp(buffer.data());
    if (Fd >= 0)
    {
      ::unlink(buffer.data());
    }
  }
  if (Fd < 0)
  {
    throw std::runtime_error(
      "cannot create a scratch file in " + Directory + ": " + std::strerror(errno));
  }
}

ScratchFile::ScratchFile(ScratchFile&& other) noexcept
  : Fd(std::exchange(other.Fd, -1))
  , Directory(std::move(other.Directory))
{
}

ScratchFile& ScratchFile::operator=(ScratchFile&& other) noexcept
{
  if (this != &other)
  {
    if (Fd >= 0)
    {
      ::close(Fd);
    }
    Fd = std::exchange(other.Fd, -1);
    Directory = std::move(other.Directory);
  }
  return *this;
}

ScratchFile::~ScratchFile()
{
  if (Fd >= 0)
  {
    ::close(Fd);
  }
}

void ScratchFile::WriteAt(std::uint64_t offset, const void* data, std::size_t bytes)
{
  const char* p = static_cast<const char*>(data);
  while (bytes > 0)
  {
    const ssize_t n = ::pwrite(Fd, p, bytes, off_t(offset));
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    if (n <= 0)
    {
      throw std::runtime_error("cannot write scratch data in " + Directory + ": " +
        (n < 0 ? std::strerror(errno) : "no space left"));
    }
    p += n;
    offset += std::uint64_t(n);
    bytes -= std::size_t(n);
  }
}

void ScratchFile::ReadAt(std::uint64_t offset, void* data, std::size_t bytes) const
{
  char* p = static_cast<char*>(data);
  while (bytes > 0)
  {
    const ssize_t n = ::pread(Fd, p, bytes, off_t(offset));
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    if (n <= 0)
    {
      throw std::runtime_error("cannot read scratch data in " + Directory + ": " +
        (n < 0 ? std::strerror(errno) : "unexpected end of file"));
    }
    p += n;
    offset += std::uint64_t(n);
    bytes -= std::size_t(n);
  }
}

void ScratchFile::Resize(std::uint64_t bytes)
{
  if (::ftruncate(Fd, off_t(bytes)) != 0)
  {
    throw std::runtime_error("cannot resize scratch file in " + Directory + ": " + std::strerror(errno));
  }
  if (bytes > 0)
  {
    const int err = ::posix_fallocate(Fd, 0, off_t(bytes));
    if (err != 0 && err != EOPNOTSUPP && err != EINVAL)
    {
      throw std::runtime_error(
        "cannot reserve scratch space in " + Directory + ": " + std::strerror(err));
    }
  }
}

void ScratchFile::Release(std::uint64_t offset, std::uint64_t bytes)
{
  ::fallocate(Fd, FALLOC_FL_PUNCH_HOLE | FALLOC_FL_KEEP_SIZE, off_t(offset), off_t(bytes));
}

} // namespace atp
