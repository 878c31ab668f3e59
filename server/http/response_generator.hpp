#pragma once
// A response as the session writes it (a Beast BuffersGenerator, like http::message_generator):
// the header is copied into one buffer, so that header and body are offered to one gathered write.
// Beast's message_generator offers at most 12 buffers at a time and its header takes one a field
// plus four; with the security headers every answer carries, the header alone filled a write and
// the body went in a second one (two system calls and two segments for one answer).

#include <algorithm>
#include <array>
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <utility>

#include "server/http/beast.hpp"

namespace avk::server {

class ResponseGenerator {
 public:
  using const_buffers_type = std::span<const net::const_buffer>;

  // Implicit, as Beast's is: a function that returns a ResponseGenerator returns a response.
  template <class Body, class Fields>
  ResponseGenerator(http::response<Body, Fields>&& res)
      : impl_(std::make_unique<Impl<Body, Fields>>(std::move(res))) {}

  bool is_done() const { return impl_->is_done(); }
  const_buffers_type prepare(beast::error_code& ec) { return impl_->prepare(ec); }
  void consume(std::size_t n) { impl_->consume(n); }
  bool keep_alive() const { return impl_->keep_alive(); }

 private:
  // The header and up to this many buffers of the body in one offer (a body's writer hands out
  // one or two buffers at a time; chunked framing adds a few).
  static constexpr std::size_t kMaxBuffers = 16;

  struct ImplBase {
    virtual ~ImplBase() = default;
    virtual bool is_done() const = 0;
    virtual const_buffers_type prepare(beast::error_code& ec) = 0;
    virtual void consume(std::size_t n) = 0;
    virtual bool keep_alive() const = 0;
  };

  template <class Body, class Fields>
  struct Impl final : ImplBase {
    explicit Impl(http::response<Body, Fields>&& res) : res_(std::move(res)), sr_(res_) {
      sr_.split(true);
    }

    bool is_done() const override {
      return header_ready_ && header_sent_ == header_.size() && sr_.is_done();
    }

    const_buffers_type prepare(beast::error_code& ec) override {
      if (!header_ready_) {
        while (!sr_.is_header_done()) {
          std::size_t bytes = 0;
          sr_.next(ec, [&](beast::error_code&, const auto& buffers) {
            for (const auto b : beast::buffers_range_ref(buffers))
              header_.append(static_cast<const char*>(b.data()), b.size());
            bytes = beast::buffer_bytes(buffers);
          });
          if (ec) return {};
          sr_.consume(bytes);
        }
        header_ready_ = true;
      }
      std::size_t n = 0;
      if (header_sent_ < header_.size())
        buffers_[n++] = net::buffer(header_.data() + header_sent_, header_.size() - header_sent_);
      body_offered_ = 0;
      if (!sr_.is_done()) {
        sr_.next(ec, [&](beast::error_code&, const auto& buffers) {
          for (const auto b : beast::buffers_range_ref(buffers)) {
            if (n == buffers_.size()) break;
            buffers_[n++] = b;
            body_offered_ += b.size();
          }
        });
        if (ec) return {};
      }
      return {buffers_.data(), n};
    }

    void consume(std::size_t n) override {
      const std::size_t from_header = std::min(n, header_.size() - header_sent_);
      header_sent_ += from_header;
      const std::size_t from_body = std::min(n - from_header, body_offered_);
      body_offered_ -= from_body;
      if (from_body > 0) sr_.consume(from_body);
    }

    bool keep_alive() const override { return res_.keep_alive(); }

    http::response<Body, Fields> res_;
    http::response_serializer<Body, Fields> sr_;
    std::string header_;
    bool header_ready_ = false;
    std::size_t header_sent_ = 0;
    std::size_t body_offered_ = 0;
    std::array<net::const_buffer, kMaxBuffers> buffers_;
  };

  std::unique_ptr<ImplBase> impl_;
};

}  // namespace avk::server
