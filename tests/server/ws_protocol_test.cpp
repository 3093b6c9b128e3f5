// The server's messages of /v1/ws: the packet message prefix the server
// writes in front of a payload without copying it, and error messages.
#include "ws_protocol.h"

#include <gtest/gtest.h>

#include <string>

namespace meshwave::server {
namespace {

TEST(WsProtocolTest, PacketPrefixPlusPayloadIsTheSerializedMessage) {
  for (uint32_t cursor : {0u, 1u, 127u, 128u, 70000u}) {
    for (uint32_t id : {0u, 5u, 300u}) {
      for (size_t size :
           {size_t{0}, size_t{1}, size_t{127}, size_t{128}, size_t{20000}}) {
        const std::string payload(size, 'x');
        proto::ServerMessage m;
        m.mutable_packet()->set_cursor(cursor);
        m.mutable_packet()->set_id(id);
        m.mutable_packet()->set_payload(payload);
        EXPECT_EQ(PacketMessagePrefix(cursor, id, size) + payload,
                  m.SerializeAsString())
            << cursor << " " << id << " " << size;
      }
    }
  }
}

TEST(WsProtocolTest, ErrorMessageParsesBack) {
  proto::ServerMessage m;
  ASSERT_TRUE(
      m.ParseFromString(ErrorMessage(proto::Error::NOT_FOUND, "no mesh")));
  ASSERT_TRUE(m.has_error());
  EXPECT_EQ(m.error().code(), proto::Error::NOT_FOUND);
  EXPECT_EQ(m.error().message(), "no mesh");
}

}  // namespace
}  // namespace meshwave::server
