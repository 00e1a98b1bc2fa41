// libFuzzer target for what a Foxglove WebSocket client sends the server (web/protocol, web/hub).
// Byte 0 picks the mode:
//   even: JSON ops. The rest, split at '\n', is a sequence of text messages of one client, each handed to the
//         Hub as the session does (subscribe, unsubscribe, get/setParameters, parameter subscriptions, ...);
//         bit 1 says whether the connection's URL carried the token.
//   odd:  WebSocket frames. The rest is the byte stream a client sends after the handshake (masked frames,
//         fragments, control frames, binary frames), read by Beast's frame parser with the server's limits over
//         an in-memory stream; each message is then dispatched as the session does (text to the Hub, binary
//         refused).
// Invariants beyond "no crash": parameters stay within their bounds and change only when the input held the
// token; the client's queues stay bounded (drained after each message, as the writer would).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include <boost/beast/_experimental/test/stream.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>

#include "tests/fuzz/web_fixture.hpp"

namespace {

namespace beast = boost::beast;
namespace websocket = beast::websocket;
using fsd::web::Peer;
using fsd::web::fuzz::WebFixture;

constexpr std::size_t kMaxFrameBytes = 4096;  // the server's web.max_frame_bytes, small to reach the limit

std::shared_ptr<Peer> connect(WebFixture& f, bool token_ok) {
  auto peer = std::make_shared<Peer>();
  peer->state = f.hub->make_client_state();
  peer->wake = [] {};
  peer->address = "127.0.0.1:9";
  peer->token_ok = token_ok;
  f.hub->add_peer(peer);
  return peer;
}

// The writer's side: take what the Hub queued. A control queue that overflowed is what the session disconnects.
void drain(Peer& peer) {
  while (peer.state->next()) {}
}

bool token_seen = false;  // a message of this input carried the token (the setParameters "token" field)

void on_message(WebFixture& f, Peer& peer, std::string_view text) {
  token_seen = token_seen || text.find(fsd::web::fuzz::kToken) != std::string_view::npos;
  f.hub->on_text(peer, text);
  f.hub->drain();
  drain(peer);
}

void fuzz_frames(WebFixture& f, Peer& peer, std::string_view bytes) {
  beast::net::io_context ioc;
  beast::test::stream server(ioc), client(ioc);
  server.connect(client);
  // The handshake as a browser makes it, then the fuzzed bytes as what the client sent after it.
  server.append(
      "GET / HTTP/1.1\r\nHost: car\r\nUpgrade: websocket\r\nConnection: upgrade\r\n"
      "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n"
      "Sec-WebSocket-Protocol: foxglove.websocket.v1\r\n\r\n");
  server.append({bytes.data(), bytes.size()});
  client.close();  // the end of the input is the end of the connection
  websocket::stream<beast::test::stream&> ws(server);
  ws.read_message_max(kMaxFrameBytes);
  beast::error_code ec;
  ws.accept(ec);
  if (ec) std::abort();  // the handshake is fixed: it must pass
  for (int i = 0; i < 64; ++i) {
    beast::flat_buffer buffer;
    ws.read(buffer, ec);
    if (ec) return;
    if (buffer.size() > kMaxFrameBytes) std::abort();
    if (!ws.got_text()) continue;  // the session refuses binary messages without looking at them
    const auto data = buffer.cdata();
    on_message(f, peer, {static_cast<const char*>(data.data()), data.size()});
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static WebFixture f;
  if (size < 1) return 0;
  const std::uint8_t mode = data[0];
  const std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
  const bool token_ok = (mode & 2) != 0;
  token_seen = false;
  const std::size_t before = f.changes;
  auto peer = connect(f, token_ok);
  if (mode & 1) {
    fuzz_frames(f, *peer, rest);
  } else {
    std::string_view messages = rest;
    while (!messages.empty()) {
      const auto nl = messages.find('\n');
      on_message(f, *peer, messages.substr(0, nl));
      messages = nl == std::string_view::npos ? std::string_view{} : messages.substr(nl + 1);
    }
  }
  if (peer->state->depth() > 64 + 64) std::abort();
  f.hub->remove_peer(peer.get());
  f.check(before, token_ok || token_seen);
  return 0;
}
