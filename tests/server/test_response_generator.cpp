// How a response is handed to the socket: header and body in one gathered write whenever the body
// is at hand, however many header fields it has (every answer carries the security headers), and
// the exact bytes Beast's serializer makes, over as many writes as the socket takes.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "server/http/response_generator.hpp"
#include "server/http/responses.hpp"

namespace {

namespace beast = boost::beast;
namespace http = beast::http;
using avk::server::ResponseGenerator;

// The serializer's bytes for the message, the reference the generator must reproduce.
template <class Body>
std::string serialized(const http::response<Body>& res) {
  std::ostringstream out;
  out << res;
  return out.str();
}

// A static file's answer: the common headers and its validators, more fields than a dozen buffers.
http::response<http::string_body> file_answer(std::size_t body_bytes) {
  http::response<http::string_body> res{http::status::ok, 11};
  avk::server::set_common_headers(res);
  res.set(http::field::etag, "\"85cf-17e5c0b8a1f0c2d4\"");
  res.set(http::field::last_modified, "Thu, 03 Dec 2026 19:30:00 GMT");
  res.set(http::field::cache_control, "no-cache");
  res.set(http::field::content_type, "text/html; charset=utf-8");
  res.keep_alive(true);
  res.body() = std::string(body_bytes, 'x');
  res.prepare_payload();
  return res;
}

// Writes the generator's bytes as a socket would, taking at most `take` bytes of each offer.
std::string drain(ResponseGenerator& gen, std::size_t take, int& offers) {
  std::string out;
  offers = 0;
  while (!gen.is_done()) {
    beast::error_code ec;
    const auto buffers = gen.prepare(ec);
    EXPECT_FALSE(ec) << ec.message();
    if (ec || offers > 100000) break;
    ++offers;
    const std::string offered = beast::buffers_to_string(buffers);
    const std::size_t n = std::min(take, offered.size());
    out += offered.substr(0, n);
    gen.consume(n);
  }
  return out;
}

TEST(ResponseGenerator, OffersHeaderAndBodyToOneWrite) {
  auto res = file_answer(34255);
  const std::string expected = serialized(res);
  ResponseGenerator gen(std::move(res));
  ASSERT_TRUE(gen.keep_alive());
  beast::error_code ec;
  const auto buffers = gen.prepare(ec);
  ASSERT_FALSE(ec);
  EXPECT_EQ(beast::buffers_to_string(buffers), expected);
  gen.consume(beast::buffer_bytes(buffers));
  EXPECT_TRUE(gen.is_done());
}

TEST(ResponseGenerator, AWriteTakingPiecesSendsTheSameBytes) {
  auto res = file_answer(5000);
  const std::string expected = serialized(res);
  ResponseGenerator gen(std::move(res));
  int offers = 0;
  EXPECT_EQ(drain(gen, 7, offers), expected);
  EXPECT_GT(offers, 1);
}

TEST(ResponseGenerator, AHeaderWithoutBody) {
  http::response<http::empty_body> res{http::status::not_modified, 11};
  avk::server::set_common_headers(res);
  res.set(http::field::etag, "\"1-2\"");
  res.keep_alive(false);
  const std::string expected = serialized(res);
  ResponseGenerator gen(std::move(res));
  EXPECT_FALSE(gen.keep_alive());
  int offers = 0;
  EXPECT_EQ(drain(gen, 1 << 20, offers), expected);
  EXPECT_EQ(offers, 1);
}

TEST(ResponseGenerator, AChunkedBodyInPieces) {
  http::response<http::string_body> res{http::status::ok, 11};
  avk::server::set_common_headers(res);
  res.body() = std::string(3000, 'y');
  res.chunked(true);
  const std::string expected = serialized(res);
  ResponseGenerator gen(std::move(res));
  int offers = 0;
  EXPECT_EQ(drain(gen, 100, offers), expected);
}

}  // namespace
