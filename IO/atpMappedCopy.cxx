#include "atpMappedCopy.h"

#include <atomic>
#include <csetjmp>
#include <csignal>
#include <cstring>
#include <mutex>

namespace atp
{
namespace
{
// The copy this thread is inside, if any. Only memcpy runs between the jump point and the
// return, so leaving it with siglongjmp skips no destructor.
thread_local sigjmp_buf* CopyInProgress = nullptr;
struct sigaction PreviousBusAction;

void PassOn(int signal, siginfo_t* info, void* context)
{
  if (PreviousBusAction.sa_flags & SA_SIGINFO)
  {
    PreviousBusAction.sa_sigaction(signal, info, context);
    return;
  }
  if (PreviousBusAction.sa_handler != SIG_IGN && PreviousBusAction.sa_handler != SIG_DFL)
  {
    PreviousBusAction.sa_handler(signal);
    return;
  }
  // The default action: returning re-runs the faulting access, which now terminates the process
  // as it would have without this handler.
  ::signal(signal, SIG_DFL);
}

void OnBusError(int signal, siginfo_t* info, void* context)
{
  if (sigjmp_buf* copy = CopyInProgress)
  {
    CopyInProgress = nullptr;
    siglongjmp(*copy, 1);
  }
  PassOn(signal, info, context);
}

void InstallHandler()
{
  struct sigaction action = {};
  action.sa_sigaction = OnBusError;
  action.sa_flags = SA_SIGINFO | SA_NODEFER;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGBUS, &action, &PreviousBusAction);
}

} // namespace

bool CopyFromMapping(void* destination, const void* source, std::size_t bytes)
{
  if (bytes == 0)
  {
    return true; // an empty vector's data() may be null, which memcpy must not see
  }
  static std::once_flag installed;
  std::call_once(installed, InstallHandler);
  sigjmp_buf jump;
  if (sigsetjmp(jump, 1) != 0)
  {
    return false;
  }
  CopyInProgress = &jump;
  std::atomic_signal_fence(std::memory_order_seq_cst);
  std::memcpy(destination, source, bytes);
  std::atomic_signal_fence(std::memory_order_seq_cst);
  CopyInProgress = nullptr;
  return true;
}

} // namespace atp
