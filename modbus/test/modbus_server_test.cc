// modbus::Server: client slots (at most 8, the 9th refused, others unaffected), idle connections,
// deadlines.
#include "modbus/server.h"

#include <gtest/gtest.h>

#include "modbus_fakes.h"

namespace modbus {
namespace {

using test::Bytes;
using test::ServerHarness;

const Bytes kReadVersion = {0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0xFB, 0x03, 0x00, 0x00, 0x00, 0x01};
const Bytes kVersionAnswer = {0x00, 0x01, 0x00, 0x00, 0x00, 0x05, 0xFB, 0x03, 0x02, 0x01, 0x06};

TEST(ModbusServer, NinthClient_RefusedOthersServed) {
  ServerHarness h;
  std::vector<ConnectionId> ids;
  for (std::size_t i = 0; i < Server::kMaxClients; ++i) {
    const base::Result<ConnectionId> id = h.server.Open(test::kClientAddress, h.now);
    ASSERT_TRUE(id.ok()) << i;
    ids.push_back(*id);
  }
  const base::Result<ConnectionId> ninth = h.server.Open(test::kClientAddress, h.now);
  EXPECT_EQ(ninth.status().code(), base::StatusCode::kResourceExhausted);
  EXPECT_EQ(h.server.counters().refused, 1u);
  EXPECT_EQ(h.server.open_connections(), Server::kMaxClients);
  EXPECT_EQ(h.server.client_pool(),
            (base::PoolStats{Server::kMaxClients, Server::kMaxClients, Server::kMaxClients, 1}));
  for (ConnectionId id : ids) EXPECT_EQ(h.Exchange(id, kReadVersion), kVersionAnswer);
  // A slot freed is a slot for the next client.
  h.server.Close(ids[3]);
  const base::Result<ConnectionId> again = h.server.Open(test::kClientAddress, h.now);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(*again, ids[3]);
  EXPECT_EQ(h.Exchange(*again, kReadVersion), kVersionAnswer);
  for (ConnectionId id : ids) h.server.Close(id);
  h.server.Close(ids[0]);  // twice: no slot is given back twice
  EXPECT_EQ(h.server.client_pool(), (base::PoolStats{0, Server::kMaxClients, Server::kMaxClients, 1}));
  EXPECT_EQ(h.server.open_connections(), 0u);
}

TEST(ModbusServer, ClientsRegisterOfUnit251_CountsOpenConnections) {
  ServerHarness h;
  const ConnectionId a = h.Connect();
  h.Connect();
  h.Connect();
  EXPECT_EQ(h.Exchange(a, {0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0xFB, 0x03, 0x00, 0x30, 0x00, 0x01}),
            (Bytes{0x00, 0x01, 0x00, 0x00, 0x00, 0x05, 0xFB, 0x03, 0x02, 0x00, 0x03}));
}

TEST(ModbusServer, UnknownOrClosedIds_Harmless) {
  ServerHarness h;
  EXPECT_EQ(h.server.Receive(7, kReadVersion, h.now), 0u);
  EXPECT_EQ(h.server.Receive(200, kReadVersion, h.now), 0u);
  EXPECT_TRUE(h.server.PendingOutput(3).empty());
  EXPECT_FALSE(h.server.MustClose(3));
  h.server.Close(3);
  EXPECT_EQ(h.server.open_connections(), 0u);
}

TEST(ModbusServer, IdleConnection_ClosedAfterIdleTimeout) {
  ServerOptions options;
  options.idle_timeout = 10 * hal::kMicrosPerSecond;
  ServerHarness h(options);
  const ConnectionId id = h.Connect();
  EXPECT_EQ(h.server.NextDeadline(), h.now + options.idle_timeout);
  h.Advance(5 * hal::kMicrosPerSecond);
  EXPECT_EQ(h.Exchange(id, kReadVersion), kVersionAnswer);
  h.Advance(10 * hal::kMicrosPerSecond - 1);
  EXPECT_FALSE(h.server.MustClose(id));
  h.Advance(1);
  EXPECT_TRUE(h.server.MustClose(id));
  EXPECT_EQ(h.server.counters().idle_closes, 1u);
  // Nothing to wait for once it must close.
  EXPECT_EQ(h.server.NextDeadline(), hal::kNever);
}

TEST(ModbusServer, IdleTimeoutZero_NeverClosed) {
  ServerOptions options;
  options.idle_timeout = 0;
  ServerHarness h(options);
  const ConnectionId id = h.Connect();
  EXPECT_EQ(h.server.NextDeadline(), hal::kNever);
  h.Advance(3600 * hal::kMicrosPerSecond);
  EXPECT_FALSE(h.server.MustClose(id));
}

TEST(ModbusServer, DefaultIdleTimeout_TwoMinutes) {
  EXPECT_EQ(ServerOptions{}.idle_timeout, 120 * hal::kMicrosPerSecond);
}

TEST(ModbusServer, CommunicationNumberWalk_SkipsAToF) {
  EXPECT_EQ(NextCommunicationNumber(0x0009), 0x0010u);
  EXPECT_EQ(NextCommunicationNumber(0x0010), 0x0011u);
  EXPECT_EQ(NextCommunicationNumber(0x000B), 0x0010u);
  // Only the last digit is skipped (§8.9 (5) "0xxxxA to 0xxxxF"); 00A0 is asked (and reads 0x8000).
  EXPECT_EQ(NextCommunicationNumber(0x0099), 0x00A0u);
  EXPECT_EQ(NextCommunicationNumber(0xFA09), 0xFA10u);
  EXPECT_EQ(NextCommunicationNumber(0xFFF9), 0x10000u);
  EXPECT_EQ(LastCommunicationNumber(0x0009, 2), 0x0010u);
  EXPECT_EQ(LastCommunicationNumber(0x0000, 63), 0x0062u);
  EXPECT_EQ(LastCommunicationNumber(0xFFF8, 2), 0xFFF9u);
  EXPECT_GT(LastCommunicationNumber(0xFFF9, 2), 0xFFFFu);
}

}  // namespace
}  // namespace modbus
