#pragma once
// A throwaway PostgreSQL cluster for tests: initdb into a folder of its own, a server listening
// on a Unix socket in that folder and on a free loopback port, trust authentication for a
// superuser "avk", and everything removed afterwards. PostgreSQL refuses to run as root, so under
// root the server runs as Debian's "postgres" system user.
//
// CTest starts one shared cluster for the whole run (the pg_cluster fixture, tests/CMakeLists.txt)
// and names its folder in AVK_TEST_PG_DIR; a test binary run by hand starts its own. Tests that
// kill the server start a private PgCluster.

#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "store/postgresql.hpp"

namespace avk::testing {

// The folder of PostgreSQL's server programs (initdb, pg_ctl, postgres).
inline std::string pg_bindir() {
  for (const char* v : {"17", "16", "15", "14", "13"}) {
    const std::string dir = std::string("/usr/lib/postgresql/") + v + "/bin";
    if (std::filesystem::exists(dir + "/initdb")) return dir;
  }
  throw std::runtime_error(
      "PostgreSQL server programs not found under /usr/lib/postgresql/*/bin: run scripts/setup");
}

inline int free_loopback_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t n = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &n);
  ::close(fd);
  return ntohs(a.sin_port);
}

class PgCluster {
 public:
  // Creates and starts a cluster in `dir` (made fresh); throws naming the step that failed.
  explicit PgCluster(std::filesystem::path dir) : dir_(std::move(dir)) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    port_ = free_loopback_port();
    if (::geteuid() == 0) run("chown postgres " + quoted(dir_.string()), "chown");
    run(as_server_user(pg_bindir() + "/initdb -D " + quoted(data()) +
                       " -U avk --auth=trust --no-sync -E UTF8 --locale=C.UTF-8") +
            " > " + quoted(log("initdb")) + " 2>&1",
        "initdb");
    start();
  }
  // A streaming-replication standby of `primary` in `dir`: its base backup (pg_basebackup -R,
  // which also writes the standby's connection to the primary), started on a port of its own.
  struct StandbyOf {
    const PgCluster& primary;
  };
  PgCluster(std::filesystem::path dir, StandbyOf s) : dir_(std::move(dir)) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    port_ = free_loopback_port();
    if (::geteuid() == 0) run("chown postgres " + quoted(dir_.string()), "chown");
    run(as_server_user(pg_bindir() + "/pg_basebackup -h " + quoted(s.primary.dir().string()) +
                       " -p " + std::to_string(s.primary.port()) + " -U avk -D " + quoted(data()) +
                       " -R -X stream -c fast") +
            " > " + quoted(log("basebackup")) + " 2>&1",
        "pg_basebackup");
    start();
  }
  // Adopts the cluster a PgCluster left running in `dir` (the CTest fixture's).
  struct Adopt {};
  PgCluster(std::filesystem::path dir, Adopt) : dir_(std::move(dir)), owned_(false) {
    std::ifstream in(dir_ / "port");
    if (!(in >> port_)) throw std::runtime_error("no running test cluster in " + dir_.string());
  }
  ~PgCluster() {
    if (!owned_) return;
    stop();
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  PgCluster(const PgCluster&) = delete;
  PgCluster& operator=(const PgCluster&) = delete;

  // The cluster outlives this object (the CTest fixture's start step).
  void keep_running() { owned_ = false; }
  int port() const { return port_; }
  const std::filesystem::path& dir() const { return dir_; }
  // A libpq connection string for a database of this cluster, over the Unix socket.
  std::string conninfo(const std::string& dbname = "postgres") const {
    return "host=" + dir_.string() + " port=" + std::to_string(port_) +
           " user=avk dbname=" + dbname + " connect_timeout=10";
  }
  // The same database as a URI over the loopback port.
  std::string url(const std::string& dbname) const {
    return "postgresql://avk@127.0.0.1:" + std::to_string(port_) + "/" + dbname;
  }

  void start() {
    // A start right after kill9() may find the old server's last processes still leaving:
    // tried again a few times, and the logs are in the error when it never starts.
    for (int attempt = 1;; ++attempt) {
      try {
        start_once();
        return;
      } catch (const std::runtime_error& e) {
        if (attempt == 3)
          throw std::runtime_error(std::string(e.what()) + "\n" + tail(log("pg_ctl")) + "\n" +
                                   tail(log("server")));
        std::this_thread::sleep_for(std::chrono::seconds(1));
      }
    }
  }
  void start_once() {
    // fsync off: a test cluster does not need to survive a power cut, and a process crash (the
    // kill -9 the outage tests use) loses nothing committed without it.
    run(as_server_user(
            pg_bindir() + "/pg_ctl -D " + quoted(data()) + " -l " + quoted(log("server")) +
            " -w -t 60 start -o " +
            quoted("-c port=" + std::to_string(port_) +
                   " -c listen_addresses=127.0.0.1 -c unix_socket_directories=" + dir_.string() +
                   " -c fsync=off -c max_connections=300" +
                   " -c shared_buffers=16MB -c wal_level=replica" + " -c max_wal_senders=4")) +
            " > " + quoted(log("pg_ctl")) + " 2>&1",
        "pg_ctl start (see " + log("server") + ")");
    std::ofstream(dir_ / "port") << port_;
  }
  void stop() {
    std::system(
        (as_server_user(pg_bindir() + "/pg_ctl -D " + quoted(data()) + " -m immediate -w stop") +
         " > /dev/null 2>&1")
            .c_str());
  }
  // A standby becomes a primary that takes writes; returns once it does.
  void promote() {
    run(as_server_user(pg_bindir() + "/pg_ctl -D " + quoted(data()) + " -w -t 60 promote") + " > " +
            quoted(log("promote")) + " 2>&1",
        "pg_ctl promote");
  }
  // SIGKILL to the server and every process it started, as a crash would; returns once all are
  // gone, so that start() can recover the data folder.
  void kill9() {
    std::ifstream in(data() + "/postmaster.pid");
    pid_t pid = 0;
    if (!(in >> pid) || pid <= 0) throw std::runtime_error("no postmaster.pid in " + data());
    // Stopped first, so that it forks no backend (a client reconnecting) while its children are
    // listed: a backend missed here would keep the old shared memory, and no new server starts.
    ::kill(pid, SIGSTOP);
    std::vector<pid_t> all{pid};
    for (const auto& e : std::filesystem::directory_iterator("/proc")) {
      std::ifstream stat(e.path() / "stat");
      std::string comm, state;
      pid_t self = 0, parent = 0;
      if (stat >> self >> comm >> state >> parent && parent == pid) all.push_back(self);
    }
    for (const pid_t p : all)
      ::kill(p, SIGKILL);
    for (const pid_t p : all)
      while (::kill(p, 0) == 0 && std::filesystem::exists("/proc/" + std::to_string(p) + "/stat")) {
        std::ifstream stat("/proc/" + std::to_string(p) + "/stat");
        std::string self, comm, state;
        stat >> self >> comm >> state;
        if (state == "Z") break;  // a zombie of pg_ctl's shell holds nothing
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
  }

  // A fresh, empty database; its connection string.
  std::string create_database() {
    static std::atomic<int> counter{0};
    const std::string name =
        "avk_t_" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
    store::PgConnection admin(conninfo());
    admin.exec("CREATE DATABASE " + name);
    return name;
  }
  void drop_database(const std::string& name) {
    try {
      store::PgConnection admin(conninfo());
      admin.exec("DROP DATABASE IF EXISTS " + name + " WITH (FORCE)");
    } catch (const std::exception&) {
      // The cluster may already be gone (a test that killed it); it is thrown away anyway.
    }
  }

  std::string data() const { return (dir_ / "data").string(); }
  std::string log(const std::string& name) const { return (dir_ / (name + ".log")).string(); }

  static std::string quoted(const std::string& s) { return "'" + s + "'"; }
  // The last 2000 characters of a file.
  static std::string tail(const std::string& path) {
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return text.size() > 2000 ? text.substr(text.size() - 2000) : text;
  }
  static std::string as_server_user(const std::string& command) {
    if (::geteuid() != 0) return command;
    return "runuser -u postgres -- " + command;
  }
  static void run(const std::string& command, const std::string& step) {
    if (std::system(command.c_str()) != 0)
      throw std::runtime_error("test PostgreSQL cluster: " + step + " failed");
  }

 private:
  std::filesystem::path dir_;
  int port_ = 0;
  bool owned_ = true;
};

// The number a query answers on a database; -1 while it cannot be reached.
inline std::int64_t pg_number(const std::string& conninfo, const std::string& sql) {
  try {
    store::PgConnection c(conninfo);
    auto s = c.prepare(sql);
    return s.step() ? s.column_int64(0) : -1;
  } catch (const store::StoreError&) {
    return -1;
  }
}

// The cluster this test process uses: CTest's shared one (AVK_TEST_PG_DIR), or one of its own
// started on first use and removed at exit.
inline PgCluster& shared_pg_cluster() {
  static std::unique_ptr<PgCluster> cluster = [] {
    if (const char* dir = std::getenv("AVK_TEST_PG_DIR");
        dir && std::filesystem::exists(std::filesystem::path(dir) / "port"))
      return std::make_unique<PgCluster>(dir, PgCluster::Adopt{});
    return std::make_unique<PgCluster>(std::filesystem::temp_directory_path() /
                                       ("avk_pg_" + std::to_string(::getpid())));
  }();
  return *cluster;
}

// A fresh database of the shared cluster for one test, dropped afterwards.
class PgTestDb {
 public:
  PgTestDb() : name_(shared_pg_cluster().create_database()) {}
  ~PgTestDb() { shared_pg_cluster().drop_database(name_); }
  PgTestDb(const PgTestDb&) = delete;
  PgTestDb& operator=(const PgTestDb&) = delete;
  std::string conninfo() const { return shared_pg_cluster().conninfo(name_); }
  std::string url() const { return shared_pg_cluster().url(name_); }
  const std::string& name() const { return name_; }

 private:
  std::string name_;
};

}  // namespace avk::testing
