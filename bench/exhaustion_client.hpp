#pragma once
// The client side of bench_exhaustion: raw loopback sockets (a hostile client controls every byte
// and every pause), one /health probe, one request on a fresh connection, and percentiles of what
// was measured.

#include <chrono>
#include <string>
#include <string_view>
#include <vector>

namespace avk::bench {

using Clock = std::chrono::steady_clock;

// A connected TCP socket to 127.0.0.1:port with Nagle off, or -1.
int connect_loopback(unsigned short port);
// A TCP socket to 127.0.0.1:port bound to the local address `from` (127.0.0.x), or -1.
int connect_from(const std::string& from, unsigned short port);

bool send_all(int fd, std::string_view bytes);

// Reads what is there without waiting; false once the peer closed (EOF or reset).
bool still_open(int fd, std::string* seen = nullptr);

// Reads until the peer closes (true) or the deadline passes (false), keeping at most `keep` bytes
// of the start in `got`.
bool read_until_closed(int fd, Clock::time_point deadline, std::string& got, std::size_t keep);

// One GET /api/v1/health on a fresh connection; the time to the complete answer, or < 0:
// -2 connect, -3 send, -4 timeout, -5 closed unanswered, -6 not 200.
double health_once(unsigned short port);

// One request on a fresh connection from `from`; the answer's status (0: none within the limit),
// its body discarded as it comes.
int exchange(const std::string& from, unsigned short port, const std::string& request,
             std::chrono::seconds limit);

std::string get_request(const std::string& target);

// The q-quantile of v (nearest rank), 0 when v is empty.
double percentile(std::vector<double> v, double q);

}  // namespace avk::bench
