// The ordered pipeline behind construction's threads: work on every thread, stores in index
// order on the caller, a bounded window, errors in index order, no deadlock.
#include "atpParallel.h"
#include "atpProduceConsume.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

TEST(OrderedPipeline, StoresInOrderOnTheCallerWithinTheWindow)
{
  for (const int threads : { 1, 2, 4 })
  {
    for (const std::size_t window : { std::size_t(1), std::size_t(3), std::size_t(16) })
    {
      const std::size_t count = 200;
      const std::thread::id caller = std::this_thread::get_id();
      std::vector<std::size_t> stores;
      std::vector<int> results(count, -1);
      std::atomic<std::size_t> worked{ 0 };
      std::mutex mutex;
      std::size_t inFlight = 0, mostInFlight = 0; // between the start of a work and its store
      atp::OrderedPipeline(
        count, threads, window,
        [&](std::size_t i) {
          {
            std::lock_guard<std::mutex> lock(mutex);
            mostInFlight = std::max(mostInFlight, ++inFlight);
          }
          // Uneven work, so later jobs often finish first.
          std::this_thread::sleep_for(std::chrono::microseconds((i * 37) % 200));
          results[i] = int(i) * 2;
          ++worked;
        },
        [&](std::size_t i) {
          EXPECT_EQ(std::this_thread::get_id(), caller);
          EXPECT_EQ(results[i], int(i) * 2) << "stored before its work was done";
          stores.push_back(i);
          std::lock_guard<std::mutex> lock(mutex);
          --inFlight;
        });
      ASSERT_EQ(stores.size(), count);
      for (std::size_t i = 0; i < count; ++i)
      {
        EXPECT_EQ(stores[i], i);
      }
      EXPECT_EQ(worked.load(), count);
      EXPECT_LE(mostInFlight, window) << threads << " threads";
    }
  }
}

TEST(OrderedPipeline, WorkRunsOnSeveralThreads)
{
  std::mutex mutex;
  std::set<std::thread::id> workers;
  atp::OrderedPipeline(
    64, 2, 8,
    [&](std::size_t) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      std::lock_guard<std::mutex> lock(mutex);
      workers.insert(std::this_thread::get_id());
    },
    [](std::size_t) {});
  EXPECT_EQ(workers.size(), 2u);
}

TEST(OrderedPipeline, TheFirstErrorInIndexOrderIsRethrownAndNothingAfterItIsStored)
{
  for (const int threads : { 1, 3 })
  {
    std::vector<std::size_t> stores;
    try
    {
      atp::OrderedPipeline(
        100, threads, 8,
        [](std::size_t i) {
          if (i == 40 || i == 41 || i == 90)
          {
            // The later failure finishes first: index order still decides.
            std::this_thread::sleep_for(std::chrono::milliseconds(i == 40 ? 5 : 0));
            throw std::runtime_error("job " + std::to_string(i));
          }
        },
        [&](std::size_t i) { stores.push_back(i); });
      ADD_FAILURE() << "no exception";
    }
    catch (const std::runtime_error& e)
    {
      EXPECT_STREQ(e.what(), "job 40");
    }
    EXPECT_EQ(stores.size(), 40u);
  }
}

TEST(OrderedPipeline, AStoreErrorStopsAtOnce)
{
  EXPECT_THROW(atp::OrderedPipeline(
                 1000, 2, 4, [](std::size_t) {},
                 [](std::size_t i) {
                   if (i == 10)
                   {
                     throw std::runtime_error("store");
                   }
                 }),
    std::runtime_error);
  EXPECT_NO_THROW(atp::OrderedPipeline(0, 2, 4, [](std::size_t) {}, [](std::size_t) {}));
}

// ProduceConsume: the two-thread hand-off of input reading (first pass, partitioning).
namespace
{
struct Numbers
{
  std::vector<int> Values;
};
} // namespace

TEST(ProduceConsume, ConsumesEveryBatchInOrderOnTheCallerWithBoundedBatches)
{
  const std::thread::id caller = std::this_thread::get_id();
  std::set<const Numbers*> batchesSeen;
  std::atomic<int> produced{ 0 };
  int consumed = 0, next = 0;
  std::vector<int> values;
  atp::ProduceConsume<Numbers>(
    2,
    [&](Numbers& batch) {
      EXPECT_NE(std::this_thread::get_id(), caller);
      if (produced == 100)
      {
        return false;
      }
      batch.Values.assign(3, 0);
      for (int& v : batch.Values)
      {
        v = next++;
      }
      ++produced;
      return true;
    },
    [&](const Numbers& batch) {
      EXPECT_EQ(std::this_thread::get_id(), caller);
      batchesSeen.insert(&batch);
      // The producer waits for a batch back: it is never more than two ahead.
      EXPECT_LE(produced.load(), consumed + 2);
      values.insert(values.end(), batch.Values.begin(), batch.Values.end());
      ++consumed;
      std::this_thread::sleep_for(std::chrono::microseconds(consumed % 7 * 50));
    });
  EXPECT_EQ(consumed, 100);
  EXPECT_EQ(batchesSeen.size(), 2u) << "batches are recycled";
  ASSERT_EQ(values.size(), 300u);
  for (int i = 0; i < 300; ++i)
  {
    EXPECT_EQ(values[std::size_t(i)], i);
  }
}

TEST(ProduceConsume, AProducerErrorReachesTheCallerAfterTheBatchesBeforeIt)
{
  int produced = 0;
  std::vector<int> consumed;
  EXPECT_THROW(atp::ProduceConsume<Numbers>(
                 3,
                 [&](Numbers& batch) {
                   if (produced == 5)
                   {
                     throw std::runtime_error("malformed input");
                   }
                   batch.Values = { produced++ };
                   return true;
                 },
                 [&](const Numbers& batch) { consumed.push_back(batch.Values[0]); }),
    std::runtime_error);
  EXPECT_EQ(consumed, std::vector<int>({ 0, 1, 2, 3, 4 }));
}

TEST(ProduceConsume, AConsumerErrorStopsAnEndlessProducer)
{
  // The producer never ends by itself: only the consumer's error can stop it, and must.
  std::atomic<bool> producerRan{ false };
  int consumed = 0;
  try
  {
    atp::ProduceConsume<Numbers>(
      2,
      [&](Numbers& batch) {
        producerRan = true;
        batch.Values = { 1 };
        return true;
      },
      [&](const Numbers&) {
        if (++consumed == 10)
        {
          throw std::runtime_error("disk full");
        }
      });
    ADD_FAILURE() << "no exception";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_EQ(std::string(e.what()), "disk full");
  }
  EXPECT_TRUE(producerRan);
  EXPECT_EQ(consumed, 10);
}

TEST(ProduceConsume, TheConsumersErrorWinsWhenBothFail)
{
  std::atomic<int> produced{ 0 };
  std::atomic<bool> producerFailed{ false };
  try
  {
    atp::ProduceConsume<Numbers>(
      2,
      [&](Numbers&) {
        if (++produced == 2)
        {
          producerFailed = true;
          throw std::runtime_error("producer");
        }
        return true;
      },
      [&](const Numbers&) {
        while (!producerFailed)
        {
          std::this_thread::yield();
        }
        throw std::runtime_error("consumer");
      });
    ADD_FAILURE() << "no exception";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_EQ(std::string(e.what()), "consumer");
  }
}
