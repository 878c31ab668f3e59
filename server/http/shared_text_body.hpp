#pragma once
// A Beast response body that sends text held elsewhere (a cached static file) without copying it:
// the response keeps the text alive while it is written, and the header and the whole body go
// out in one gathered write.

#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "server/http/beast.hpp"

namespace avk::server {

struct SharedTextBody {
  using value_type = std::shared_ptr<const std::string>;

  static std::uint64_t size(const value_type& body) { return body ? body->size() : 0; }

  class writer {
   public:
    using const_buffers_type = net::const_buffer;

    template <bool isRequest, class Fields>
    writer(const http::header<isRequest, Fields>&, const value_type& body) : body_(body) {}

    void init(beast::error_code& ec) { ec = {}; }

    boost::optional<std::pair<const_buffers_type, bool>> get(beast::error_code& ec) {
      ec = {};
      if (sent_ || !body_ || body_->empty()) return boost::none;
      sent_ = true;
      return {{net::const_buffer(body_->data(), body_->size()), false}};
    }

   private:
    const value_type& body_;
    bool sent_ = false;
  };
};

}  // namespace avk::server
