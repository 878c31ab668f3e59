#include "exhaustion_client.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

namespace avk::bench {

using namespace std::chrono_literals;

int connect_loopback(unsigned short port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return -1;
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  const int one = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  return fd;
}

bool send_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const auto n = ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
    if (n <= 0) return false;
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

bool still_open(int fd, std::string* seen) {
  char b[4096];
  for (;;) {
    const auto n = ::recv(fd, b, sizeof b, MSG_DONTWAIT);
    if (n > 0) {
      if (seen && seen->size() < 256) seen->append(b, static_cast<std::size_t>(n));
      continue;
    }
    if (n == 0) return false;
    return errno == EAGAIN || errno == EWOULDBLOCK;
  }
}

bool read_until_closed(int fd, Clock::time_point deadline, std::string& got, std::size_t keep) {
  char b[65536];
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) return false;
    const auto n = ::recv(fd, b, sizeof b, 0);
    if (n <= 0) return true;
    if (got.size() < keep) got.append(b, std::min(static_cast<std::size_t>(n), keep - got.size()));
  }
}

// One GET /api/v1/health on a fresh connection; the time to the complete answer, or < 0.
double health_once(unsigned short port) {
  const auto t0 = Clock::now();
  const int fd = connect_loopback(port);
  if (fd < 0) return -1;
  const std::string req =
      "GET /api/v1/health HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
  if (!send_all(fd, req)) {
    ::close(fd);
    return -3;
  }
  std::string got;
  const bool closed = read_until_closed(fd, t0 + 5s, got, 4096);
  ::close(fd);
  if (!closed) return -4;
  if (!got.starts_with("HTTP/1.1 200")) return got.empty() ? -5 : -6;
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

int connect_from(const std::string& from, unsigned short port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return -1;
  sockaddr_in source{};
  source.sin_family = AF_INET;
  ::inet_pton(AF_INET, from.c_str(), &source.sin_addr);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&source), sizeof source) != 0 ||
      ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

int exchange(const std::string& from, unsigned short port, const std::string& request,
             std::chrono::seconds limit) {
  const int fd = connect_from(from, port);
  if (fd < 0) return 0;
  std::string head;
  if (send_all(fd, request)) read_until_closed(fd, Clock::now() + limit, head, 16);
  ::close(fd);
  return head.starts_with("HTTP/1.1 ") && head.size() >= 12 ? std::stoi(head.substr(9, 3)) : 0;
}

std::string get_request(const std::string& target) {
  return "GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
  return v[std::min(i, v.size() - 1)];
}

}  // namespace avk::bench
