#include "atpPendingFile.h"

#include "atpCommandLine.h"
#include "atpOutputPath.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace atp
{

PendingFile::PendingFile(std::string path, std::string what, const std::vector<std::string>& inputs)
  : FinalPath(std::move(path))
  , What(std::move(what))
{
  const std::string problem = OutputPathProblem(FinalPath, inputs);
  if (!problem.empty())
  {
    throw Failure(problem); // found now, not when renaming after the work
  }
  Partial = FinalPath + ".partial-" + std::to_string(::getpid()) + FileExtension(FinalPath);
  const int fd = ::open(Partial.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0)
  {
    throw Failure(std::strerror(errno));
  }
  ::close(fd);
}

PendingFile::~PendingFile()
{
  if (!Committed)
  {
    std::remove(Partial.c_str());
  }
}

std::runtime_error PendingFile::Failure(const std::string& reason) const
{
  return std::runtime_error(FinalPath + ": cannot write the " + What + (reason.empty() ? "" : ": " + reason));
}

void PendingFile::Commit()
{
  if (std::rename(Partial.c_str(), FinalPath.c_str()) != 0)
  {
    throw Failure(std::strerror(errno));
  }
  Committed = true;
}

}
