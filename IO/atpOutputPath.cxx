#include "atpOutputPath.h"

#include <cerrno>
#include <climits>
#include <cstring>
#include <sys/stat.h>
#include <unistd.h>

namespace atp
{

std::string OutputPathProblem(const std::string& path, const std::vector<std::string>& inputs)
{
  if (path.empty() || path.back() == '/')
  {
    return "not a file name";
  }
  struct stat existing{};
  if (::stat(path.c_str(), &existing) == 0)
  {
    if (S_ISDIR(existing.st_mode))
    {
      return "is a directory";
    }
    if (!S_ISREG(existing.st_mode))
    {
      return "exists and is not a regular file: refusing to replace it";
    }
    for (const std::string& input : inputs)
    {
      struct stat in{};
      if (::stat(input.c_str(), &in) == 0 && in.st_dev == existing.st_dev && in.st_ino == existing.st_ino)
      {
        return "is the input " + input + ": refusing to replace it";
      }
    }
  }
  if (path.size() + SideFileSuffixBytes >= PATH_MAX)
  {
    return "path too long: at most " + std::to_string(PATH_MAX - 1 - SideFileSuffixBytes) +
      " bytes leave room for the path of the file written before it";
  }
  const std::size_t slash = path.rfind('/');
  const std::string directory = slash == std::string::npos ? "." : path.substr(0, slash + 1);
  struct stat folder{};
  const int folderError =
    ::stat(directory.c_str(), &folder) != 0 ? errno : (S_ISDIR(folder.st_mode) ? 0 : ENOTDIR);
  if (folderError != 0)
  {
    // Found now, not when the finished output is renamed into place.
    return std::string(std::strerror(folderError)) + " (its directory " + directory + ")";
  }
  // Read-only (EROFS even for root) or not ours to write in: found now, not after the work.
  if (::access(directory.c_str(), W_OK | X_OK) != 0)
  {
    return std::string("cannot write in its directory ") + directory + ": " + std::strerror(errno);
  }
  const std::size_t nameBytes = path.size() - (slash == std::string::npos ? 0 : slash + 1);
  const long limit = ::pathconf(directory.c_str(), _PC_NAME_MAX);
  if (limit > 0 && nameBytes + SideFileSuffixBytes > std::size_t(limit))
  {
    return "file name too long: at most " + std::to_string(std::size_t(limit) - SideFileSuffixBytes) +
      " bytes leave room for the name of the file written before it";
  }
  return std::string();
}

} // namespace atp
