#include "atpModelEdit.h"

#include "atpFileDescriptor.h"

#include "atpChecksum.h"
#include "atpModelFile.h"

#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace atp
{
namespace
{
[[noreturn]] void Fail(const std::string& path, const std::string& problem)
{
  throw ModelError(path + ": " + problem);
}

} // namespace

void SetModelErrorScale(const std::string& path, float scale)
{
  if (!std::isfinite(scale) || !(scale >= 0))
  {
    Fail(path, "error scale " + std::to_string(scale) + " is not finite and non-negative");
  }
  // Open for writing first and validate after: the header we write is then the one of the
  // file we validated, unless the path was replaced in between, which the inode check catches.
  const FileDescriptor fd{ ::open(path.c_str(), O_WRONLY | O_CLOEXEC) };
  struct stat opened;
  if (fd.Fd < 0 || ::fstat(fd.Fd, &opened) != 0)
  {
    Fail(path, std::string("cannot open for writing: ") + std::strerror(errno));
  }
  ModelHeader header;
  {
    const ModelFile model = ModelFile::Open(path);
    header = model.Header();
  }
  struct stat validated;
  if (::stat(path.c_str(), &validated) != 0 || validated.st_dev != opened.st_dev ||
    validated.st_ino != opened.st_ino)
  {
    Fail(path, "the file was replaced while it was being edited");
  }

  header.ErrorScale = scale;
  header.HeaderChecksum = Checksum(&header, offsetof(ModelHeader, HeaderChecksum));
  ssize_t written;
  do
  {
    written = ::pwrite(fd.Fd, &header, sizeof(header), 0);
  } while (written < 0 && errno == EINTR);
  if (written != ssize_t(sizeof(header)))
  {
    Fail(path, written < 0 ? std::string("cannot write the header: ") + std::strerror(errno)
                           : std::string("short write of the header"));
  }
  if (::fsync(fd.Fd) != 0)
  {
    Fail(path, std::string("cannot sync the header: ") + std::strerror(errno));
  }
}

} // namespace atp
