// Construction's jobs on their own, as the MPI build ships them: a build whose every job and
// result travels as bytes, made in reverse order, writes the same model as the threaded build;
// malformed messages are refused, never read past. Threads read the jobs they make.
#include "atpConstruction.h"
#include "atpPartitioner.h"
#include "atpPatchJob.h"
#include "atpPatchJobMessages.h"
#include "atpPatchJobRunner.h"
#include "vtkATPBuilder.h"

#include "vtkNew.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <unistd.h>

namespace
{

std::string TempPath(const std::string& name)
{
  return "/tmp/atp-test-patchjob-" + std::to_string(::getpid()) + "-" + name;
}

std::string ReadBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// A remote runner without the network: the context, every job and every result go through
/// their messages; a batch's jobs are made last to first and stored first to last.
class ByteTripRunner : public atp::PatchJobRunner
{
public:
  void Begin(const atp::PatchJobContext& context) override
  {
    const std::vector<std::uint8_t> bytes = atp::EncodeContext(context);
    Context.emplace(atp::DecodeContext(bytes.data(), bytes.size()));
  }

  void Run(std::size_t count, const LoadJob& load, const StoreResult& store) override
  {
    std::vector<std::vector<std::uint8_t>> messages(count);
    for (std::size_t i = 0; i < count; ++i)
    {
      atp::PatchJob job;
      load(i, job);
      atp::EncodeJob(job, messages[i]);
      LeafJobs += job.IsLeaf();
      DiamondJobs += !job.IsLeaf();
    }
    for (std::size_t i = count; i-- > 0;)
    {
      atp::PatchJob job;
      atp::DecodeJob(messages[i].data(), messages[i].size(), job);
      atp::EncodeResult(atp::MakePatches(*Context, std::move(job)), messages[i]);
    }
    for (std::size_t i = 0; i < count; ++i)
    {
      atp::PatchJobResult result;
      atp::DecodeResult(messages[i].data(), messages[i].size(), result);
      store(i, result);
    }
  }

  std::optional<atp::PatchJobContext> Context;
  std::size_t LeafJobs = 0, DiamondJobs = 0;
};

/// `bucketMiB` 1 puts nearly every bucket page in the scratch file: leaves are read from disk.
int Build(const std::string& out, atp::PatchJobRunner* runner, atp::ConstructionStats& stats,
  int bucketMiB = 256, std::uint64_t* bucketBytesSpilled = nullptr)
{
  vtkNew<vtkATPBuilder> builder;
  builder->SetInputFileName(ATP_DATA_DIR "/bumpy-torus.ply");
  builder->SetFileName(out.c_str());
  builder->SetLeafCapacity(1000); // a deeper hierarchy: many leaf and diamond jobs
  builder->SetPatchBudget(500);
  builder->SetNumberOfThreads(2);
  builder->SetBucketMemoryMiB(bucketMiB);
  builder->SetJobRunner(runner);
  const int ok = builder->Build();
  stats = builder->GetConstructionStats();
  if (bucketBytesSpilled)
  {
    *bucketBytesSpilled = builder->GetPartitionStats().Buckets.BytesWritten;
  }
  return ok;
}

/// The threads of this process, counting the leaf and diamond jobs loaded off the calling thread.
class LoadWatchingRunner : public atp::PatchJobRunner
{
public:
  void Begin(const atp::PatchJobContext& context) override { Threads->Begin(context); }

  void Run(std::size_t count, const LoadJob& load, const StoreResult& store) override
  {
    const std::thread::id caller = std::this_thread::get_id();
    Threads->Run(
      count,
      [&](std::size_t i, atp::PatchJob& job) {
        load(i, job);
        const std::lock_guard<std::mutex> lock(Mutex);
        (job.IsLeaf() ? Leaves : Diamonds) += 1;
        (job.IsLeaf() ? LeavesElsewhere : DiamondsElsewhere) += std::this_thread::get_id() != caller;
      },
      store);
  }

  std::mutex Mutex;
  std::size_t Leaves = 0, LeavesElsewhere = 0, Diamonds = 0, DiamondsElsewhere = 0;

private:
  std::unique_ptr<atp::PatchJobRunner> Threads = atp::MakeThreadJobRunner(3);
};

/// Every way of cutting `message` short, or making it longer, is refused.
template<typename Decode>
void ExpectOnlyTheWholeMessageDecodes(std::vector<std::uint8_t> message, const Decode& decode)
{
  EXPECT_NO_THROW(decode(message));
  const std::vector<std::uint8_t> whole = message;
  for (std::size_t size = 0; size < whole.size(); ++size)
  {
    message.assign(whole.begin(), whole.begin() + std::ptrdiff_t(size));
    EXPECT_THROW(decode(message), std::runtime_error) << "cut to " << size << " bytes";
  }
  message = whole;
  message.push_back(0);
  EXPECT_THROW(decode(message), std::runtime_error) << "one byte too many";
  // A count far beyond the message is refused before anything is allocated.
  message = whole;
  const std::uint64_t huge = std::uint64_t(1) << 60;
  std::memcpy(message.data(), &huge, sizeof(huge));
  EXPECT_THROW(decode(message), std::runtime_error) << "huge count";
}

} // namespace

TEST(PatchJob, ModelIsIdenticalWhenEveryJobTravelsAsBytes)
{
  const std::string threads = TempPath("threads.atp"), shipped = TempPath("shipped.atp");
  atp::ConstructionStats direct, travelled;
  ASSERT_EQ(Build(threads, nullptr, direct), 1);
  ByteTripRunner runner;
  ASSERT_EQ(Build(shipped, &runner, travelled), 1);
  // The figures each result carries besides its patches travel too.
  EXPECT_EQ(travelled.Collapses, direct.Collapses);
  EXPECT_EQ(travelled.TrianglesOverQuotas, direct.TrianglesOverQuotas);
  EXPECT_EQ(travelled.QuotaMisses, direct.QuotaMisses);
  EXPECT_EQ(travelled.PiecesRemoved, direct.PiecesRemoved);
  EXPECT_GT(travelled.Cpu.DiamondSimplify, 0); // the jobs' CPU times travel too (their values differ)
  EXPECT_GT(travelled.Cpu.LeafEncode, 0);
  EXPECT_GT(runner.LeafJobs, 100u);
  EXPECT_GT(runner.DiamondJobs, 50u);
  const std::string reference = ReadBytes(threads);
  EXPECT_GT(reference.size(), 100000u);
  EXPECT_TRUE(ReadBytes(shipped) == reference);
  std::remove(threads.c_str());
  std::remove(shipped.c_str());
}

// The calling thread stores every result in order; the jobs' inputs (buckets, the children's
// patches) are read by the threads that make them, and the model stays the same, with the
// buckets in memory or read back from the scratch file.
TEST(PatchJob, JobsAreLoadedOnTheThreadsThatMakeThem)
{
  const std::string plain = TempPath("plain.atp"), watched = TempPath("watched.atp"),
                    spilled = TempPath("spilled.atp");
  atp::ConstructionStats direct, stats;
  ASSERT_EQ(Build(plain, nullptr, direct), 1);
  const std::string reference = ReadBytes(plain);
  for (const int bucketMiB : { 256, 1 })
  {
    LoadWatchingRunner runner;
    std::uint64_t bucketBytesSpilled = 0;
    const std::string& out = bucketMiB == 1 ? spilled : watched;
    ASSERT_EQ(Build(out, &runner, stats, bucketMiB, &bucketBytesSpilled), 1);
    EXPECT_GT(runner.Leaves, 100u);
    EXPECT_GT(runner.LeavesElsewhere, 0u);
    EXPECT_GT(runner.Diamonds, 50u);
    EXPECT_GT(runner.DiamondsElsewhere, 0u);
    EXPECT_GT(stats.Cpu.LoadJobs, 0);
    EXPECT_TRUE(ReadBytes(out) == reference) << bucketMiB << " MiB of buckets";
    if (bucketMiB == 1)
    {
      EXPECT_GT(bucketBytesSpilled, 1u << 20);
    }
  }
  std::remove(plain.c_str());
  std::remove(watched.c_str());
  std::remove(spilled.c_str());
}

TEST(PatchJob, MalformedMessagesAreRefused)
{
  atp::Box bounds;
  const float corners[2][3] = { { 0, 0, 0 }, { 1, 2, 3 } };
  bounds.Add(corners[0]);
  bounds.Add(corners[1]);
  const atp::PatchJobContext context(bounds, 100, true, atp::CacheOrder::Fast);

  atp::PatchJob job;
  job.Soup.resize(2);
  for (std::size_t t = 0; t < job.Soup.size(); ++t)
  {
    std::memset(&job.Soup[t], 0, sizeof(atp::SoupTriangle));
    for (int c = 0; c < 3; ++c)
    {
      job.Soup[t].V[c][c] = 1.0f + float(t);
    }
  }
  std::vector<std::uint8_t> message;
  atp::EncodeJob(job, message);
  ExpectOnlyTheWholeMessageDecodes(message, [](const std::vector<std::uint8_t>& m) {
    atp::PatchJob decoded;
    atp::DecodeJob(m.data(), m.size(), decoded);
  });

  atp::PatchJobResult made = atp::MakePatches(context, job);
  made.Collapses = 4321;
  made.TrianglesOverQuotas = 12345;
  made.PiecesRemoved = 678;
  made.FacingAtRandom = true;
  made.RepeatedTrianglesDropped = 91;
  made.Cpu = { 0.25, 1.5, 0.75 };
  atp::EncodeResult(made, message);
  {
    atp::PatchJobResult back;
    atp::DecodeResult(message.data(), message.size(), back);
    EXPECT_EQ(back.Collapses, 4321u);
    EXPECT_EQ(back.TrianglesOverQuotas, 12345u);
    EXPECT_EQ(back.PiecesRemoved, 678u);
    EXPECT_TRUE(back.FacingAtRandom);
    EXPECT_EQ(back.RepeatedTrianglesDropped, 91u);
    EXPECT_EQ(back.Cpu.Prepare, 0.25);
    EXPECT_EQ(back.Cpu.Simplify, 1.5);
    EXPECT_EQ(back.Cpu.Encode, 0.75);
  }
  {
    // The flag is a byte of 0 or 1, before the repeated triangles and the CPU times.
    std::vector<std::uint8_t> corrupt = message;
    std::uint8_t& flag = corrupt[corrupt.size() - sizeof(atp::JobCpuSeconds) - sizeof(std::uint64_t) - 1];
    ASSERT_EQ(flag, 1u);
    flag = 2;
    atp::PatchJobResult back;
    EXPECT_THROW(atp::DecodeResult(corrupt.data(), corrupt.size(), back), std::runtime_error);
  }
  // Decoding past a changed field would fail mid-build: a result's fields change only with
  // MessageVersion in atpPatchJobMessages.cxx (bump it, then this size).
  atp::PatchJobResult empty;
  std::vector<std::uint8_t> emptyMessage;
  atp::EncodeResult(empty, emptyMessage);
  EXPECT_EQ(emptyMessage.size(), 73u);
  ExpectOnlyTheWholeMessageDecodes(message, [](const std::vector<std::uint8_t>& m) {
    atp::PatchJobResult decoded;
    atp::DecodeResult(m.data(), m.size(), decoded);
  });

  message = atp::EncodeContext(context);
  const atp::PatchJobContext back = atp::DecodeContext(message.data(), message.size());
  EXPECT_EQ(back.PatchBudget, 100u);
  EXPECT_TRUE(back.Colors);
  EXPECT_EQ(back.Grid.Step, context.Grid.Step);
  EXPECT_EQ(back.Order, atp::CacheOrder::Fast);
  message.back() = 2; // no such cache order
  EXPECT_THROW(atp::DecodeContext(message.data(), message.size()), std::runtime_error);
  message.back() = std::uint8_t(atp::CacheOrder::Best);
  EXPECT_EQ(atp::DecodeContext(message.data(), message.size()).Order, atp::CacheOrder::Best);
  message[0] ^= 1; // another layout: another atp build
  try
  {
    atp::DecodeContext(message.data(), message.size());
    ADD_FAILURE() << "a context of another layout was accepted";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("different atp build"), std::string::npos) << e.what();
  }
}
