#include "meshwave/client/session.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <boost/asio/io_context.hpp>
#include <future>
#include <set>
#include <thread>

#include "client_test_stream.h"
#include "fake_transport_testonly.h"
#include "meshwave/container.h"
#include "meshwave/progression.h"

namespace meshwave::client {
namespace {

using testing::ClientTestStream;
using testing::FakeFaults;
using testing::FakeServerLog;
using testing::FakeTransport;

struct Harness {
  boost::asio::io_context io;
  std::shared_ptr<FakeServerLog> log = std::make_shared<FakeServerLog>();
  std::shared_ptr<FakeFaults> faults = std::make_shared<FakeFaults>();
  SessionOptions options;  // the base of NewSession's

  std::unique_ptr<Session> NewSession(Progression order, int max_level = -1) {
    SessionOptions o = options;
    o.order = order;
    o.max_level = max_level;
    o.retry.initial_delay = std::chrono::milliseconds(1);
    o.retry.max_attempts = 4;
    return std::make_unique<Session>(
        std::make_unique<FakeTransport>(io.get_executor(), ClientTestStream(),
                                        log, faults),
        o);
  }
  Status Run(Session& s, Budget b, ProgressHandler h = {}) {
    Status result(StatusCode::kInternal, "not run");
    s.AsyncFetch(b, std::move(h), [&](Status st) { result = st; });
    io.restart();
    io.run();
    return result;
  }
};

std::string LocalTruncation(Progression p, uint64_t budget,
                            int max_level = -1) {
  const auto& s = ClientTestStream();
  const auto order = PacketOrder(s.header, p, max_level);
  return SerializeContainer(s, SelectPackets(s.header, order, budget).ids);
}

TEST(SessionTest, ByteBudgetGivesTheLocalTruncationInEveryOrder) {
  for (Progression p :
       {Progression::kQuality, Progression::kResolution, Progression::kRd}) {
    for (uint64_t budget : {2000u, 6000u, 1u << 30}) {
      Harness h;
      auto s = h.NewSession(p);
      int calls = 0;
      ASSERT_TRUE(
          h.Run(*s, Budget::Bytes(budget),
                [&](const Progress&, const ProgressiveDecoder&) { ++calls; })
              .ok());
      EXPECT_EQ(s->Container(), LocalTruncation(p, budget))
          << ProgressionName(p) << " " << budget;
      EXPECT_EQ(calls, static_cast<int>(s->progress().packets) +
                           1);  // base mesh + each packet
      EXPECT_EQ(h.log->requests, 1);
    }
  }
}

TEST(SessionTest, MaxLevelLimitsTheOrder) {
  Harness h;
  auto s = h.NewSession(Progression::kResolution, 1);
  ASSERT_TRUE(h.Run(*s, Budget::All()).ok());
  EXPECT_EQ(s->Container(),
            LocalTruncation(Progression::kResolution, 1u << 30, 1));
  EXPECT_TRUE(s->progress().complete());
}

TEST(SessionTest, RefineEqualsOneLargerFetchAndNeverRepeatsAPacket) {
  Harness h;
  auto first = h.NewSession(Progression::kRd);
  ASSERT_TRUE(h.Run(*first, Budget::Bytes(2500)).ok());
  const std::string state = first->Container();
  // A new session (a new process) restored from the container.
  auto second = h.NewSession(Progression::kRd);
  ASSERT_TRUE(second->Restore(state, first->budget_bytes()).ok());
  ASSERT_TRUE(h.Run(*second, Budget::Bytes(2500 + 3000)).ok());
  ASSERT_TRUE(h.Run(*second, Budget::Bytes(2500 + 3000 + 4000)).ok());
  EXPECT_EQ(second->Container(), LocalTruncation(Progression::kRd, 9500));
  std::set<uint32_t> unique(h.log->packets_sent.begin(),
                            h.log->packets_sent.end());
  EXPECT_EQ(unique.size(), h.log->packets_sent.size());
  EXPECT_EQ(h.log->packets_sent.size(), second->progress().packets);
}

TEST(SessionTest, PsnrBudgetFetchesTheHeaderThenPacketsByCursor) {
  Harness h;
  auto s = h.NewSession(Progression::kQuality);
  const auto& st = ClientTestStream();
  const auto order = PacketOrder(st.header, Progression::kQuality);
  const auto curve = EstimatedPsnrCurve(st.header, order);
  const double target = curve[order.size() / 2];
  ASSERT_TRUE(h.Run(*s, Budget::Psnr(target)).ok());
  EXPECT_GE(s->progress().estimated_psnr_db, target);
  EXPECT_EQ(s->progress().packets,
            TargetCursor(st.header, order, Budget::Psnr(target)));
  EXPECT_EQ(h.log->requests, 3);  // header, first packet, the rest by cursor
  std::set<uint32_t> unique(h.log->packets_sent.begin(),
                            h.log->packets_sent.end());
  EXPECT_EQ(unique.size(), h.log->packets_sent.size());
}

TEST(SessionTest, ResumesFromTheCursorAfterDroppedConnections) {
  Harness h;
  h.faults->drops = 2;
  h.faults->drop_after = SerializeFullContainer(ClientTestStream()).size() / 3;
  auto s = h.NewSession(Progression::kQuality);
  ASSERT_TRUE(h.Run(*s, Budget::All()).ok());
  EXPECT_EQ(s->Container(), LocalTruncation(Progression::kQuality, 1u << 30));
  EXPECT_EQ(s->progress().retries, 2);
}

TEST(SessionTest, GivesUpAfterTheRetriesWithoutProgress) {
  Harness h;
  h.faults->drops = 100;
  h.faults->drop_after = 5;  // never even the preamble
  auto s = h.NewSession(Progression::kQuality);
  const Status st = h.Run(*s, Budget::All());
  EXPECT_EQ(st.code(), StatusCode::kIoError);
  EXPECT_NE(st.message().find("gave up after 4 attempts"), std::string::npos)
      << st.message();
}

TEST(SessionTest, RefusesACorruptPacket) {
  Harness h;
  auto s = h.NewSession(Progression::kQuality);
  const size_t head = ContainerSize(ClientTestStream().header, {});
  h.faults->corrupt_at = static_cast<int64_t>(head + 40);  // inside a payload
  const Status st = h.Run(*s, Budget::All());
  EXPECT_EQ(st.code(), StatusCode::kParseError) << st.ToString();
  EXPECT_NE(st.message().find("packet"), std::string::npos) << st.message();
  EXPECT_EQ(h.log->requests, 1);  // no retry of a corrupt response
}

TEST(SessionTest, RefusesACorruptHeader) {
  Harness h;
  auto s = h.NewSession(Progression::kQuality);
  h.faults->corrupt_at = 1;  // the magic
  const Status st = h.Run(*s, Budget::All());
  EXPECT_EQ(st.code(), StatusCode::kParseError) << st.ToString();
}

// The client's own limits on what a server may make it allocate: a header
// longer than max_header_bytes, or one describing a mesh over the decoder's
// max_faces, is refused without a retry and leaves the session empty.
TEST(SessionTest, RefusesAHeaderOverTheClientsLimits) {
  const auto& stream = ClientTestStream();
  const StreamHeader& header = stream.header;
  // The header's length field (bytes 4-7) of what the server sends for
  // Budget::All: its `present` field lists every packet.
  const std::string all =
      SerializeContainer(stream, PacketOrder(header, Progression::kQuality));
  const uint64_t header_bytes = testing::HeaderLengthField(all);
  {
    Harness h;
    h.options.max_header_bytes = header_bytes - 1;
    auto s = h.NewSession(Progression::kQuality);
    const Status st = h.Run(*s, Budget::All());
    EXPECT_EQ(st.code(), StatusCode::kParseError) << st.ToString();
    EXPECT_NE(st.message().find("over this client's limit"), std::string::npos)
        << st.message();
    EXPECT_EQ(h.log->requests, 1);
    EXPECT_FALSE(s->has_header());
  }
  {
    Harness h;
    h.options.decoder.max_faces = header.faces - 1;
    auto s = h.NewSession(Progression::kQuality);
    const Status st = h.Run(*s, Budget::All());
    EXPECT_FALSE(st.ok());
    EXPECT_NE(st.message().find("faces"), std::string::npos) << st.message();
    EXPECT_EQ(h.log->requests, 1);
    EXPECT_FALSE(s->has_header());
  }
  {  // at the limits: the whole stream
    Harness h;
    h.options.max_header_bytes = header_bytes;
    h.options.decoder.max_faces = header.faces;
    auto s = h.NewSession(Progression::kQuality);
    const Status st = h.Run(*s, Budget::All());
    ASSERT_TRUE(st.ok()) << st.ToString();
    EXPECT_TRUE(s->progress().complete());
  }
}

TEST(SessionTest, RefusesAServerThatDisagreesOnTheCursor) {
  Harness h;
  h.faults->cursor_skew = 1;
  auto s = h.NewSession(Progression::kRd);
  const Status st = h.Run(*s, Budget::Bytes(4000));
  EXPECT_EQ(st.code(), StatusCode::kParseError);
  EXPECT_NE(st.message().find("cursor"), std::string::npos) << st.message();
}

TEST(SessionTest, RestoreRefusesAForeignOrCorruptContainer) {
  Harness h;
  const std::string rd = LocalTruncation(Progression::kRd, 5000);
  const auto& st = ClientTestStream();
  const auto quality_order = PacketOrder(st.header, Progression::kQuality);
  const uint32_t second[] = {quality_order[1]};
  auto quality = h.NewSession(Progression::kQuality);
  const Status not_prefix = quality->Restore(SerializeContainer(st, second), 0);
  EXPECT_EQ(not_prefix.code(), StatusCode::kParseError)
      << not_prefix.ToString();
  EXPECT_FALSE(quality->has_header());
  std::string corrupt = rd;
  corrupt[corrupt.size() - 3] ^= 1;
  auto s = h.NewSession(Progression::kRd);
  EXPECT_FALSE(s->Restore(corrupt, 0).ok());
  EXPECT_FALSE(s->Restore(rd.substr(0, rd.size() - 1), 0).ok());
  EXPECT_TRUE(s->Restore(rd, 0).ok());
}

TEST(SessionTest, AsyncFetchRunsOnTheIoThreadNotTheCaller) {
  Harness h;
  auto s = h.NewSession(Progression::kQuality);
  auto guard = boost::asio::make_work_guard(h.io);
  std::thread io_thread([&] { h.io.run(); });
  std::promise<Status> done;
  std::set<std::thread::id> callback_threads;
  s->AsyncFetch(
      Budget::All(),
      [&](const Progress&, const ProgressiveDecoder&) {
        callback_threads.insert(std::this_thread::get_id());
      },
      [&](Status st) { done.set_value(st); });
  const Status st = done.get_future().get();
  guard.reset();
  io_thread.join();
  EXPECT_TRUE(st.ok()) << st.ToString();
  ASSERT_EQ(callback_threads.size(), 1u);
  EXPECT_NE(*callback_threads.begin(), std::this_thread::get_id());
}

}  // namespace
}  // namespace meshwave::client
