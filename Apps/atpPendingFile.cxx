#include "atpPendingFile.h"

#include "atpCommandLine.h"
#include "atpOutputPath.h"

#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <mutex>
#include <unistd.h>

namespace atp
{
namespace
{
/// The partial files of this process, removed by a handler when a signal that ends it by
/// default does (TerminatingSignals; a process killed by SIGKILL leaves them, under their
/// ".partial-PID" names, never the output's). A slot is Free, being Filled by its owner, or
/// Ready for the handler.
enum SlotState : int
{
  Free,
  Filled,
  Ready
};
constexpr std::size_t Slots = 8;
/// Those a user, a terminal, a pipe or a resource limit sends; the rest mean a crash.
constexpr int TerminatingSignals[] = { SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE, SIGALRM, SIGUSR1,
  SIGUSR2, SIGXCPU, SIGXFSZ };
char SlotPath[Slots][PATH_MAX];
std::atomic<int> SlotStates[Slots];

void RemovePartialsAndEnd(int signal)
{
  RemovePendingFiles();
  ::signal(signal, SIG_DFL);
  ::raise(signal);
}

/// The slot holding `path` for the handler, or -1 when none is free (or the path is too long):
/// that partial file is then only removed by the destructor.
int Register(const std::string& path)
{
  static std::once_flag installed;
  std::call_once(installed, [] {
    for (const int signal : TerminatingSignals)
    {
      struct sigaction previous{};
      if (::sigaction(signal, nullptr, &previous) == 0 && previous.sa_handler == SIG_DFL)
      {
        ::signal(signal, RemovePartialsAndEnd); // an ignored signal stays ignored
      }
    }
  });
  for (std::size_t i = 0; i < Slots && path.size() < PATH_MAX; ++i)
  {
    int expected = Free;
    if (SlotStates[i].compare_exchange_strong(expected, Filled))
    {
      std::memcpy(SlotPath[i], path.c_str(), path.size() + 1);
      SlotStates[i].store(Ready);
      return int(i);
    }
  }
  return -1;
}

void Unregister(int slot)
{
  if (slot >= 0)
  {
    SlotStates[std::size_t(slot)].store(Free);
  }
}
} // namespace

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
  // Registered before it exists and until it is gone: no moment when a signal would leave it.
  Slot = Register(Partial);
  const int fd = ::open(Partial.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0)
  {
    const int error = errno;
    Unregister(Slot);
    throw Failure(std::strerror(error));
  }
  ::close(fd);
}

PendingFile::~PendingFile()
{
  if (!Committed)
  {
    std::remove(Partial.c_str());
  }
  Unregister(Slot);
}

void RemovePendingFiles()
{
  for (std::size_t i = 0; i < Slots; ++i)
  {
    if (SlotStates[i].load() == Ready)
    {
      ::unlink(SlotPath[i]);
    }
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
  Unregister(Slot); // the name is the output's now
  Slot = -1;
  Committed = true;
}

}
