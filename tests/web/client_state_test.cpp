// Back-pressure and subscriptions of one client, without sockets.
#include <gtest/gtest.h>

#include "web/client_state.hpp"

#include <algorithm>
#include <atomic>
#include <thread>

namespace fsd::web {
namespace {

std::shared_ptr<const std::string> text(const std::string& s) { return std::make_shared<const std::string>(s); }

TEST(ClientState, OnlySubscribedChannelsAreQueuedWithTheirSubscriptionId) {
  ClientState c(8, 8);
  EXPECT_FALSE(c.offer(1, 0, text("x")));  // not subscribed
  EXPECT_EQ(c.depth(), 0u);
  ASSERT_EQ(c.subscribe(10, 1), ClientState::SubscribeResult::Ok);
  EXPECT_EQ(c.subscribe(10, 2), ClientState::SubscribeResult::IdInUse);
  EXPECT_EQ(c.subscribe(11, 1), ClientState::SubscribeResult::ChannelAlreadySubscribed);
  EXPECT_TRUE(c.offer(1, 5, text("a")));   // the writer was idle: wake it
  EXPECT_FALSE(c.offer(1, 6, text("b")));  // already woken
  auto m = c.next();
  ASSERT_TRUE(m);
  EXPECT_TRUE(m->binary);
  EXPECT_EQ(m->header, foxglove::message_data_header(10, 5));
  EXPECT_EQ(*m->body, "a");
}

TEST(ClientState, FullQueueDropsTheOldest) {
  Counter drops;
  ClientState c(3, 8, &drops);
  ASSERT_EQ(c.subscribe(1, 1), ClientState::SubscribeResult::Ok);
  for (int i = 0; i < 7; ++i) c.offer(1, i, text(std::to_string(i)));
  EXPECT_EQ(c.dropped(), 4u);
  EXPECT_EQ(drops.value(), 4u);
  EXPECT_EQ(c.depth(), 3u);
  std::string got;
  while (auto m = c.next()) got += *m->body;
  EXPECT_EQ(got, "456");
}

TEST(ClientState, RepliesGoFirstAndAreNeverDroppedButOverflowIsFlagged) {
  ClientState c(2, 2);
  ASSERT_EQ(c.subscribe(1, 1), ClientState::SubscribeResult::Ok);
  c.offer(1, 0, text("t"));
  c.push_control("r1");
  auto m = c.next();
  ASSERT_TRUE(m);
  EXPECT_FALSE(m->binary);
  EXPECT_EQ(*m->body, "r1");
  c.push_control("r2");
  c.push_control("r3");
  EXPECT_FALSE(c.overflowed());
  c.push_control("r4");
  EXPECT_TRUE(c.overflowed());
}

TEST(ClientState, WriterIsWokenAgainOnlyAfterItWentIdle) {
  ClientState c(4, 4);
  EXPECT_TRUE(c.push_control("a"));
  EXPECT_FALSE(c.push_control("b"));
  EXPECT_TRUE(c.next());
  EXPECT_TRUE(c.next());
  EXPECT_FALSE(c.next());  // idle now
  EXPECT_TRUE(c.push_control("c"));
}

TEST(ClientState, UnsubscribeDropsQueuedMessagesOfThatSubscription) {
  ClientState c(8, 8);
  ASSERT_EQ(c.subscribe(1, 1), ClientState::SubscribeResult::Ok);
  ASSERT_EQ(c.subscribe(2, 2), ClientState::SubscribeResult::Ok);
  c.offer(1, 0, text("a"));
  c.offer(2, 0, text("b"));
  EXPECT_EQ(c.unsubscribe(1), 1u);
  EXPECT_FALSE(c.unsubscribe(1));
  auto m = c.next();
  ASSERT_TRUE(m);
  EXPECT_EQ(*m->body, "b");
  EXPECT_FALSE(c.next());
  EXPECT_EQ(c.subscribe(1, 1), ClientState::SubscribeResult::Ok);  // ids are reusable after unsubscribing
}

TEST(ClientState, ParameterSubscriptions) {
  ClientState c(1, 1);
  EXPECT_FALSE(c.wants_param("a"));
  c.subscribe_params({"a"});
  EXPECT_TRUE(c.wants_param("a"));
  EXPECT_FALSE(c.wants_param("b"));
  c.subscribe_params({});
  EXPECT_TRUE(c.wants_param("b"));
  c.unsubscribe_params({});
  EXPECT_FALSE(c.wants_param("a"));
}

TEST(ClientState, ClosedRefusesEverything) {
  ClientState c(4, 4);
  ASSERT_EQ(c.subscribe(1, 1), ClientState::SubscribeResult::Ok);
  c.offer(1, 0, text("a"));
  c.close();
  EXPECT_FALSE(c.offer(1, 0, text("b")));
  EXPECT_FALSE(c.push_control("c"));
  EXPECT_FALSE(c.next());
}

}  // namespace
}  // namespace fsd::web

namespace fsd::web {
namespace {

TEST(ClientState, UnsubscribedAndOutOfRangeChannelsCostNoDrop) {
  Counter drops;
  ClientState c(8, 8, &drops);
  EXPECT_FALSE(c.offer(2, 0, text("x")));
  EXPECT_FALSE(c.offer(0, 0, text("x")));
  EXPECT_FALSE(c.offer(ClientState::kMaxChannels + 1, 0, text("x")));
  EXPECT_EQ(drops.value(), 0u);
}

// A fan-out thread and a writer racing: every offered message is either delivered, in order, or counted.
TEST(ClientState, ConcurrentOffersAreDeliveredInOrderOrCounted) {
  Counter drops;
  ClientState c(64, 8, &drops);
  ASSERT_EQ(c.subscribe(1, 1), ClientState::SubscribeResult::Ok);
  constexpr int kN = 50000;
  std::atomic<bool> done{false};
  std::vector<int> got;
  std::thread writer([&] {
    while (true) {
      if (auto m = c.next())
        got.push_back(std::stoi(*m->body));
      else if (done)
        break;
    }
    while (auto m = c.next()) got.push_back(std::stoi(*m->body));
  });
  for (int i = 0; i < kN; ++i) c.offer(1, 0, text(std::to_string(i)));
  done = true;
  writer.join();
  EXPECT_EQ(got.size() + drops.value(), static_cast<std::size_t>(kN));
  EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
  EXPECT_EQ(std::adjacent_find(got.begin(), got.end()), got.end());  // no duplicates
  EXPECT_EQ(got.back(), kN - 1);  // the newest survives, the oldest are the ones dropped
}

}  // namespace
}  // namespace fsd::web
