#include "atpMpiBuild.h"

#include "atpCpuTime.h"
#include "atpPatchJobMessages.h"

#include <chrono>
#include <climits>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <sys/resource.h>
#include <thread>

namespace atp
{
namespace
{

enum Tag : int
{
  TagContext = 1, ///< coordinator -> worker: the build's context
  TagJob,         ///< coordinator -> worker: one job with its inputs
  TagStop,        ///< coordinator -> worker: no more jobs; answered by TagStats
  TagResult,      ///< worker -> coordinator: the job's patches
  TagFailure,     ///< worker -> coordinator: why the job failed
  TagStats,       ///< worker -> coordinator: its peak memory
};

/// Jobs a worker holds: the one it works on and the next.
constexpr std::size_t JobsPerWorker = 2;
/// Jobs handed out beyond those stored, per worker: enough to keep workers busy when one job is
/// slow, few enough to keep the coordinator's reorder buffer small.
constexpr std::size_t JobsAheadPerWorker = 4;

void Check(int code, const char* what)
{
  if (code != MPI_SUCCESS)
  {
    char text[MPI_MAX_ERROR_STRING];
    int length = 0;
    MPI_Error_string(code, text, &length);
    throw std::runtime_error(std::string("MPI ") + what + " failed: " + std::string(text, length));
  }
}

/// MPI counts are ints.
int MessageSize(const std::vector<std::uint8_t>& bytes)
{
  if (bytes.size() > std::size_t(INT_MAX))
  {
    throw std::runtime_error("a message of " + std::to_string(bytes.size() >> 20) +
      " MiB is too large for MPI (2 GiB at most): lower --leaf-capacity");
  }
  return int(bytes.size());
}

void Send(MPI_Comm comm, int rank, Tag tag, const std::vector<std::uint8_t>& bytes)
{
  Check(MPI_Send(bytes.data(), MessageSize(bytes), MPI_BYTE, rank, tag, comm), "send");
}

/// Waits for a message without spinning: an idle rank sleeps between polls, so on a machine
/// with fewer cores than ranks the coordinator and idle workers leave the cores to busy ones
/// (Open MPI's blocking receive polls at full speed).
MPI_Status WaitForMessage(MPI_Comm comm, int source)
{
  auto pause = std::chrono::microseconds(10);
  for (;;)
  {
    int arrived = 0;
    MPI_Status status;
    Check(MPI_Iprobe(source, MPI_ANY_TAG, comm, &arrived, &status), "probe");
    if (arrived)
    {
      return status;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(250));
  }
}

/// Receives the message `status` announced into `bytes`.
void Receive(MPI_Comm comm, const MPI_Status& status, std::vector<std::uint8_t>& bytes)
{
  int count = 0;
  Check(MPI_Get_count(&status, MPI_BYTE, &count), "get count");
  bytes.resize(std::size_t(count));
  Check(MPI_Recv(bytes.data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, comm,
          MPI_STATUS_IGNORE),
    "receive");
}

std::uint64_t PeakResidentBytes()
{
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return std::uint64_t(usage.ru_maxrss) * 1024; // Linux reports KiB
}

/// ATP_MPI_TEST_FAULT=kill:K or throw:K (see RunMpiWorker).
struct InjectedFault
{
  bool Kill = false;
  std::uint64_t AtJob = 0;

  static std::optional<InjectedFault> FromEnvironment()
  {
    const char* text = std::getenv("ATP_MPI_TEST_FAULT");
    if (!text || !*text)
    {
      return std::nullopt;
    }
    const std::string spec = text;
    const std::size_t colon = spec.find(':');
    const std::string kind = spec.substr(0, colon);
    if (colon == std::string::npos || (kind != "kill" && kind != "throw"))
    {
      throw std::runtime_error("ATP_MPI_TEST_FAULT must be kill:K or throw:K, not '" + spec + "'");
    }
    return InjectedFault{ kind == "kill", std::stoull(spec.substr(colon + 1)) };
  }
};

} // namespace

MpiSession::MpiSession(int* argc, char*** argv)
{
  MPI_Init(argc, argv);
  // Failures are reported by us as exceptions, not by aborting the whole job.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
}

MpiSession::~MpiSession()
{
  MPI_Finalize();
}

int MpiSession::Rank() const
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

int MpiSession::Size() const
{
  int size = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

bool WantsMpi(int argc, char** argv)
{
  if (argc < 2 || std::strcmp(argv[1], "build") != 0)
  {
    return false;
  }
  for (int i = 2; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--mpi") == 0)
    {
      return true;
    }
  }
  return false;
}

MpiJobRunner::MpiJobRunner(MPI_Comm comm)
  : Comm(comm)
{
  int size = 0;
  Check(MPI_Comm_size(comm, &size), "size");
  if (size < 2)
  {
    throw std::runtime_error("--mpi needs at least 2 processes: mpirun -np N atp build ... --mpi, "
                             "rank 0 coordinates and ranks 1 to N-1 build");
  }
  Queued.resize(std::size_t(size - 1));
  Stats.resize(Queued.size());
}

MpiJobRunner::~MpiJobRunner()
{
  try
  {
    Finish();
  }
  catch (...)
  {
    // Already failing: the first error is the one reported; mpirun ends what is left.
  }
}

void MpiJobRunner::Begin(const PatchJobContext& context)
{
  CoordinatorCpu = -ProcessCpuSeconds();
  const std::vector<std::uint8_t> bytes = EncodeContext(context);
  for (int w = 0; w < Workers(); ++w)
  {
    Send(Comm, w + 1, TagContext, bytes);
  }
}

void MpiJobRunner::Run(std::size_t count, const LoadJob& load, const StoreResult& store)
{
  const std::size_t ahead = JobsAheadPerWorker * Queued.size();
  std::vector<std::uint8_t> buffer;
  std::size_t next = 0, stored = 0;
  while (stored < count)
  {
    ReclaimSends(false);
    // Bottom-up and in diamond order, so consecutive jobs are geometric neighbours; every
    // worker gets one before any gets a second.
    for (std::size_t held = 1; held <= JobsPerWorker; ++held)
    {
      for (std::size_t w = 0; w < Queued.size() && next < count && next < stored + ahead; ++w)
      {
        if (Queued[w].size() < held)
        {
          Dispatch(next++, w, load);
        }
      }
    }
    Collect(buffer);
    for (auto first = Arrived.begin(); first != Arrived.end() && first->first == stored;
         first = Arrived.begin())
    {
      store(stored++, first->second);
      Arrived.erase(first);
    }
  }
}

void MpiJobRunner::Dispatch(std::size_t index, std::size_t worker, const LoadJob& load)
{
  PatchJob job;
  load(index, job);
  PendingSend& send = Sends.emplace_back();
  EncodeJob(job, send.Bytes);
  Check(MPI_Isend(send.Bytes.data(), MessageSize(send.Bytes), MPI_BYTE, int(worker) + 1, TagJob,
          Comm, &send.Request),
    "send");
  Queued[worker].push_back(index);
  Stats[worker].JobBytes += send.Bytes.size();
}

void MpiJobRunner::ReclaimSends(bool all)
{
  for (auto s = Sends.begin(); s != Sends.end();)
  {
    int done = 0;
    Check(all ? MPI_Wait(&s->Request, MPI_STATUS_IGNORE) : MPI_Test(&s->Request, &done,
                                                              MPI_STATUS_IGNORE),
      "send");
    s = (all || done) ? Sends.erase(s) : std::next(s);
  }
}

void MpiJobRunner::Collect(std::vector<std::uint8_t>& buffer)
{
  const MPI_Status status = WaitForMessage(Comm, MPI_ANY_SOURCE);
  Receive(Comm, status, buffer);
  const std::size_t w = std::size_t(status.MPI_SOURCE - 1);
  if (status.MPI_SOURCE < 1 || w >= Queued.size() || Queued[w].empty())
  {
    throw std::runtime_error(
      "unexpected message from MPI rank " + std::to_string(status.MPI_SOURCE));
  }
  const std::size_t job = Queued[w].front();
  Queued[w].pop_front();
  if (status.MPI_TAG == TagFailure)
  {
    throw std::runtime_error("worker " + std::to_string(status.MPI_SOURCE) + " failed on job " +
      std::to_string(job) + ": " + std::string(buffer.begin(), buffer.end()));
  }
  ++Stats[w].Jobs;
  Stats[w].ResultBytes += buffer.size();
  DecodeResult(buffer.data(), buffer.size(), Arrived[job]);
}

std::vector<MpiJobRunner::WorkerStats> MpiJobRunner::Finish()
{
  if (Finished)
  {
    return Stats;
  }
  Finished = true;
  CoordinatorCpu += ProcessCpuSeconds();
  std::vector<std::uint8_t> buffer;
  for (std::size_t w = 0; w < Queued.size(); ++w)
  {
    // A failed build leaves jobs out: their results are received and dropped.
    for (; !Queued[w].empty(); Queued[w].pop_front())
    {
      Receive(Comm, WaitForMessage(Comm, int(w) + 1), buffer);
    }
  }
  ReclaimSends(true);
  Arrived.clear();
  for (std::size_t w = 0; w < Queued.size(); ++w)
  {
    Send(Comm, int(w) + 1, TagStop, {});
  }
  for (std::size_t w = 0; w < Queued.size(); ++w)
  {
    std::uint64_t peak = 0;
    Check(MPI_Recv(&peak, 1, MPI_UINT64_T, int(w) + 1, TagStats, Comm, MPI_STATUS_IGNORE),
      "receive");
    Stats[w].PeakMemoryBytes = peak;
  }
  return Stats;
}

int RunMpiWorker(MPI_Comm comm)
{
  const std::optional<InjectedFault> fault = InjectedFault::FromEnvironment();
  std::optional<PatchJobContext> context;
  std::vector<std::uint8_t> buffer;
  // The last result goes out while the next job is made.
  std::vector<std::uint8_t> result;
  MPI_Request sending = MPI_REQUEST_NULL;
  std::uint64_t jobs = 0;
  for (;;)
  {
    const MPI_Status status = WaitForMessage(comm, 0);
    Receive(comm, status, buffer);
    if (status.MPI_TAG == TagStop)
    {
      Check(MPI_Wait(&sending, MPI_STATUS_IGNORE), "send");
      const std::uint64_t peak = PeakResidentBytes();
      Check(MPI_Send(&peak, 1, MPI_UINT64_T, 0, TagStats, comm), "send");
      return 0;
    }
    if (status.MPI_TAG == TagContext)
    {
      context.emplace(DecodeContext(buffer.data(), buffer.size()));
      continue;
    }
    try
    {
      ++jobs;
      if (fault && fault->AtJob == jobs)
      {
        if (fault->Kill)
        {
          std::raise(SIGKILL);
        }
        throw std::runtime_error("injected fault (ATP_MPI_TEST_FAULT)");
      }
      if (status.MPI_TAG != TagJob || !context)
      {
        throw std::runtime_error("unexpected message from the coordinator");
      }
      PatchJob job;
      DecodeJob(buffer.data(), buffer.size(), job);
      buffer.clear();
      const PatchJobResult made = MakePatches(*context, std::move(job));
      Check(MPI_Wait(&sending, MPI_STATUS_IGNORE), "send");
      EncodeResult(made, result);
      Check(MPI_Isend(result.data(), MessageSize(result), MPI_BYTE, 0, TagResult, comm, &sending),
        "send");
    }
    catch (const std::exception& e)
    {
      Check(MPI_Wait(&sending, MPI_STATUS_IGNORE), "send");
      const std::string message = e.what();
      Send(comm, 0, TagFailure, std::vector<std::uint8_t>(message.begin(), message.end()));
    }
  }
}

} // namespace atp
