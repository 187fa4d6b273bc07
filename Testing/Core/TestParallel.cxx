// The ordered pipeline behind construction's threads: loads and stores in index order on the
// caller, work on every thread, a bounded window, errors in index order, no deadlock.
#include "atpParallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

TEST(OrderedPipeline, LoadsAndStoresInOrderOnTheCallerWithinTheWindow)
{
  for (const int threads : { 1, 2, 4 })
  {
    for (const std::size_t window : { std::size_t(1), std::size_t(3), std::size_t(16) })
    {
      const std::size_t count = 200;
      const std::thread::id caller = std::this_thread::get_id();
      std::vector<std::size_t> loads, stores;
      std::vector<int> results(count, -1);
      std::atomic<std::size_t> worked{ 0 };
      std::size_t inFlight = 0, mostInFlight = 0;
      atp::OrderedPipeline(
        count, threads, window,
        [&](std::size_t i) {
          EXPECT_EQ(std::this_thread::get_id(), caller);
          loads.push_back(i);
          mostInFlight = std::max(mostInFlight, ++inFlight);
        },
        [&](std::size_t i) {
          // Uneven work, so later jobs often finish first.
          std::this_thread::sleep_for(std::chrono::microseconds((i * 37) % 200));
          results[i] = int(i) * 2;
          ++worked;
        },
        [&](std::size_t i) {
          EXPECT_EQ(std::this_thread::get_id(), caller);
          EXPECT_EQ(results[i], int(i) * 2) << "stored before its work was done";
          stores.push_back(i);
          --inFlight;
        });
      ASSERT_EQ(loads.size(), count);
      ASSERT_EQ(stores.size(), count);
      for (std::size_t i = 0; i < count; ++i)
      {
        EXPECT_EQ(loads[i], i);
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
    64, 2, 8, [](std::size_t) {},
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
        100, threads, 8, [](std::size_t) {},
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

TEST(OrderedPipeline, ALoadOrStoreErrorStopsAtOnce)
{
  EXPECT_THROW(atp::OrderedPipeline(
                 1000, 2, 4,
                 [](std::size_t i) {
                   if (i == 10)
                   {
                     throw std::runtime_error("load");
                   }
                 },
                 [](std::size_t) {}, [](std::size_t) {}),
    std::runtime_error);
  EXPECT_THROW(atp::OrderedPipeline(
                 1000, 2, 4, [](std::size_t) {}, [](std::size_t) {},
                 [](std::size_t i) {
                   if (i == 10)
                   {
                     throw std::runtime_error("store");
                   }
                 }),
    std::runtime_error);
  EXPECT_NO_THROW(atp::OrderedPipeline(
    0, 2, 4, [](std::size_t) {}, [](std::size_t) {}, [](std::size_t) {}));
}
