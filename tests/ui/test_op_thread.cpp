// OpThread: every job on one long-lived thread, one at a time; run() waits and rethrows.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "sutura/ui/op_thread.hpp"

namespace {

using sutura::ui::OpThread;

TEST(OpThread, EveryJobRunsOnTheSameOtherThread) {
  OpThread ops;
  std::thread::id first, second, third;
  ops.run([&] { first = std::this_thread::get_id(); });
  ops.run([&] { second = std::this_thread::get_id(); });
  ops.post([&] { third = std::this_thread::get_id(); });
  ops.wait();
  EXPECT_NE(first, std::this_thread::get_id());
  EXPECT_EQ(first, second);
  EXPECT_EQ(first, third);
}

TEST(OpThread, RunRethrowsAndTheThreadGoesOn) {
  OpThread ops;
  EXPECT_THROW(ops.run([] { throw std::runtime_error("no"); }), std::runtime_error);
  int ran = 0;
  ops.run([&] { ran = 1; });
  EXPECT_EQ(ran, 1);
  EXPECT_TRUE(ops.idle());
}

TEST(OpThread, APostedJobThatThrowsIsRethrownByWait) {
  OpThread ops;
  ops.post([] { throw std::runtime_error("broken"); });
  EXPECT_THROW(ops.wait(), std::runtime_error);
  EXPECT_NO_THROW(ops.wait());  // rethrown once
  int ran = 0;
  ops.run([&] { ran = 1; });
  EXPECT_EQ(ran, 1);
}

TEST(OpThread, PostReturnsAtOnceAndOneJobAtATime) {
  OpThread ops;
  std::atomic<bool> release{false}, done{false};
  ops.post([&] {
    while (!release.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    done = true;
  });
  EXPECT_FALSE(ops.idle());
  EXPECT_THROW(ops.post([] {}), std::logic_error);
  release = true;
  ops.wait();
  EXPECT_TRUE(done.load());
  EXPECT_TRUE(ops.idle());
}

TEST(OpThread, DestructionWaitsForTheJobInHand) {
  std::atomic<bool> done{false};
  {
    OpThread ops;
    ops.post([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      done = true;
    });
  }
  EXPECT_TRUE(done.load());
}

}  // namespace
