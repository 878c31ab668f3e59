#pragma once
// A Beast response body read from a BodyFile (server/body_file.hpp) in large pieces: an export of
// tens of megabytes goes out from disk with a bounded buffer, never held in memory whole.

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <memory>
#include <system_error>
#include <utility>

#include "server/body_file.hpp"
#include "server/http/beast.hpp"

namespace avk::server {

struct DescriptorBody {
  using value_type = std::shared_ptr<BodyFile>;

  static std::uint64_t size(const value_type& file) { return file ? file->size() : 0; }

  class writer {
   public:
    using const_buffers_type = net::const_buffer;
    // Larger pieces mean fewer writes; the buffer lives as long as the response's serializer.
    static constexpr std::size_t kPieceBytes = std::size_t{256} << 10;

    template <bool isRequest, class Fields>
    writer(const http::header<isRequest, Fields>&, const value_type& file) : file_(file) {}

    void init(beast::error_code& ec) {
      ec = {};
      try {
        remaining_ = size(file_);
      } catch (const std::exception&) {
        ec = std::make_error_code(std::errc::io_error);
      }
    }

    boost::optional<std::pair<const_buffers_type, bool>> get(beast::error_code& ec) {
      ec = {};
      if (remaining_ == 0) return boost::none;
      if (!piece_) piece_ = std::make_unique<char[]>(kPieceBytes);
      const auto want = static_cast<std::size_t>(std::min<std::uint64_t>(remaining_, kPieceBytes));
      ssize_t n = -1;
      do {
        n = ::pread(file_->fd(), piece_.get(), want, static_cast<off_t>(offset_));
      } while (n < 0 && errno == EINTR);
      if (n <= 0) {
        // The file shrank or cannot be read: the response cannot be completed as announced.
        ec = std::make_error_code(std::errc::io_error);
        return boost::none;
      }
      offset_ += static_cast<std::uint64_t>(n);
      remaining_ -= static_cast<std::uint64_t>(n);
      return {{net::const_buffer(piece_.get(), static_cast<std::size_t>(n)), remaining_ > 0}};
    }

   private:
    const value_type& file_;
    std::uint64_t offset_ = 0;
    std::uint64_t remaining_ = 0;
    std::unique_ptr<char[]> piece_;
  };
};

}  // namespace avk::server
