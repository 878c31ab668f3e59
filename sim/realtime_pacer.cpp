// The only place in sim/ that includes Asio: real-time pacing on a steady timer.
#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <optional>
#include <stdexcept>

#include "sim/scheduler.hpp"

namespace avk::sim {

struct RealtimePacer::Impl {
  boost::asio::io_context io;
  boost::asio::steady_timer timer{io};
  std::optional<std::chrono::steady_clock::time_point> wall_start;
  double sim_start_s = 0.0;
};

RealtimePacer::RealtimePacer(double factor) : impl_(std::make_unique<Impl>()), factor_(factor) {
  if (!(factor > 0.0)) throw std::invalid_argument("real-time factor must be positive");
}

RealtimePacer::~RealtimePacer() = default;

void RealtimePacer::wait_until(double sim_time_s) {
  const auto now = std::chrono::steady_clock::now();
  if (!impl_->wall_start) {
    impl_->wall_start = now;
    impl_->sim_start_s = sim_time_s;
    return;
  }
  const auto deadline =
      *impl_->wall_start +
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>((sim_time_s - impl_->sim_start_s) / factor_));
  if (deadline <= now) return;
  impl_->timer.expires_at(deadline);
  boost::system::error_code ec;
  impl_->timer.wait(ec);
}

}  // namespace avk::sim
