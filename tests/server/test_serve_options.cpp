// `avk serve` as a process: the token rules, the default database location, what a failed start
// leaves behind and what it says when it listens off this machine.
// A server that starts although it should not is stopped at the deadline and fails the test.

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "support/http_client.hpp"
#include "support/spawn_avk.hpp"
#include "support/temp_db.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Outcome {
  bool exited = false;  // false: still running at the deadline (then killed)
  int code = -1;
  std::string log;
};

std::string read_file(const std::string& path) {
  std::stringstream s;
  s << std::ifstream(path).rdbuf();
  return s.str();
}

// Waits for a started avk until it exits, or until `until_log` appears in its output (then
// SIGTERM), or the deadline (then SIGKILL).
Outcome wait_avk(pid_t pid, const std::string& log, const std::string& until_log = "",
                 std::chrono::seconds limit = std::chrono::seconds(30)) {
  Outcome o;
  if (pid <= 0) return o;
  const auto deadline = Clock::now() + limit;
  int status = 0;
  for (;;) {
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      o.exited = true;
      o.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      break;
    }
    if (!until_log.empty() && read_file(log).find(until_log) != std::string::npos) {
      ::kill(pid, SIGTERM);
      ::waitpid(pid, &status, 0);
      o.exited = false;
      break;
    }
    if (Clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  o.log = read_file(log);
  fs::remove(log);
  return o;
}

Outcome run_avk(const std::vector<std::string>& args, const std::string& log,
                const std::string& until_log = "",
                std::chrono::seconds limit = std::chrono::seconds(30),
                const std::vector<std::string>& env = {}) {
  return wait_avk(avk::testing::spawn_avk(args, log, env), log, until_log, limit);
}

// A loopback port held open, so that a server asked to use it fails to start.
class BusyPort {
 public:
  BusyPort() : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a);
    ::listen(fd_, 1);
    socklen_t len = sizeof a;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
  }
  ~BusyPort() { ::close(fd_); }
  std::string port() const { return std::to_string(port_); }

 private:
  int fd_;
  unsigned short port_ = 0;
};

// Regression: a token of 16 'a's was accepted, and then 0123456789abcdef0123456789abcdef.
TEST(ServeOptions, AUserTokenMustBeLongAndUnpredictable) {
  avk::testing::TempDb db("avk_serve_token");
  const std::string log = db.path() + ".log";
  for (const std::string& token :
       {std::string(16, 'a'), std::string(31, 'x') + "y", std::string(64, 'a'),
        std::string("abababababababababababababababababababab"), std::string(40, 'q') + " x",
        std::string("0123456789abcdef0123456789abcdef")}) {
    const auto o = run_avk({"serve", "--db", db.path(), "--port", "0", "--token", token}, log);
    EXPECT_TRUE(o.exited) << token << ": the server started";
    EXPECT_EQ(o.code, 2) << token << "\n" << o.log;
    EXPECT_NE(o.log.find("--token"), std::string::npos) << o.log;
  }
  fs::remove(db.path() + ".token");
}

TEST(ServeOptions, AnAllowedOriginMustBeAnOriginAndNothingMore) {
  avk::testing::TempDb db("avk_serve_origin");
  const std::string log = db.path() + ".log";
  for (const std::string& origin :
       {std::string("app.foxglove.dev"), std::string("https://app.foxglove.dev/studio"),
        std::string("ftp://x.example"), std::string("https://")}) {
    const auto o =
        run_avk({"serve", "--db", db.path(), "--port", "0", "--allow-origin", origin}, log);
    EXPECT_TRUE(o.exited) << origin << ": the server started";
    EXPECT_EQ(o.code, 2) << origin << "\n" << o.log;
    EXPECT_NE(o.log.find("--allow-origin"), std::string::npos) << o.log;
  }
  fs::remove(db.path() + ".token");
}

// The connection caps and the request workers take whole numbers in range, named when not.
TEST(ServeOptions, CapsAndRequestWorkersMustBeInRange) {
  avk::testing::TempDb db("avk_serve_caps");
  const std::string log = db.path() + ".log";
  const std::vector<std::pair<std::vector<std::string>, std::string>> wrong = {
      {{"--max-streams-per-address", "0"}, "--max-streams-per-address"},
      {{"--request-workers", "0"}, "--request-workers"},
      {{"--request-workers", "300"}, "--request-workers"},
      {{"--request-queue", "1.5"}, "--request-queue"},
      {{"--expensive-requests-per-address", "-1"}, "--expensive-requests-per-address"},
      {{"--request-workers", "2", "--expensive-requests", "3"}, "--expensive-requests"},
  };
  for (const auto& [options, named] : wrong) {
    std::vector<std::string> args = {"serve", "--db", db.path(), "--port", "0"};
    args.insert(args.end(), options.begin(), options.end());
    const auto o = run_avk(args, log);
    EXPECT_TRUE(o.exited) << named << ": the server started";
    EXPECT_EQ(o.code, 2) << named << "\n" << o.log;
    EXPECT_NE(o.log.find(named), std::string::npos) << o.log;
  }
  fs::remove(db.path() + ".token");
}

// The map background is checked before anything is opened or written: a path that is not a tile
// folder or an MBTiles file stops the start, naming the option and the path.
TEST(ServeOptions, TilesMustBeAFolderOfTilesOrAnMbtilesFile) {
  avk::testing::TempDb db("avk_serve_tiles");
  const std::string log = db.path() + ".log";
  const fs::path dir = db.path() + ".dir";
  fs::create_directories(dir / "empty");
  std::ofstream(dir / "notes.mbtiles") << "not a database\n";
  for (const fs::path& tiles : {dir / "missing", dir / "empty", dir / "notes.mbtiles"}) {
    const auto o =
        run_avk({"serve", "--db", db.path(), "--port", "0", "--tiles", tiles.string()}, log);
    EXPECT_TRUE(o.exited) << tiles << ": the server started";
    EXPECT_EQ(o.code, 2) << tiles << "\n" << o.log;
    EXPECT_NE(o.log.find("--tiles"), std::string::npos) << o.log;
    EXPECT_NE(o.log.find(tiles.string()), std::string::npos) << o.log;
    EXPECT_FALSE(fs::exists(db.path() + ".token")) << "a refused start left its token file";
  }
  // A folder with a tile is taken, and the start says so.
  fs::create_directories(dir / "tiles/3/2");
  std::ofstream(dir / "tiles/3/2/5.png", std::ios::binary) << "\x89PNG\r\n\x1a\n";
  const auto o =
      run_avk({"serve", "--db", db.path(), "--port", "0", "--tiles", (dir / "tiles").string()}, log,
              "map tiles:");
  EXPECT_FALSE(o.exited) << o.log;
  EXPECT_NE(o.log.find("map tiles: folder"), std::string::npos) << o.log;
  EXPECT_NE(o.log.find("zoom 3-3"), std::string::npos) << o.log;
  fs::remove_all(dir);
  fs::remove(db.path() + ".token");
}

// Regression: an existing token file readable by others (0644) was used silently.
TEST(ServeOptions, ATokenFileOthersCanReadIsRefused) {
  avk::testing::TempDb db("avk_serve_mode");
  const std::string token_file = db.path() + ".token";
  const std::string log = db.path() + ".log";
  std::ofstream(token_file) << "0123456789abcdef0123456789abcdef\n";
  ASSERT_EQ(::chmod(token_file.c_str(), 0644), 0);
  const auto o = run_avk({"serve", "--db", db.path(), "--port", "0"}, log);
  EXPECT_TRUE(o.exited) << "the server started with a world-readable token";
  EXPECT_NE(o.code, 0);
  EXPECT_NE(o.log.find("0644"), std::string::npos) << o.log;
  EXPECT_NE(o.log.find(token_file), std::string::npos) << o.log;
  // The file is left as it was: the operator decides.
  EXPECT_TRUE(fs::exists(token_file));
  fs::remove(token_file);
}

// Regression: `serve --db X` created $HOME/.local/share/avk-station anyway, and a start
// that failed (here: the port is taken) left a new X.token behind.
TEST(ServeOptions, AFailedStartWithDbLeavesNothingNewBehind) {
  avk::testing::TempDb db("avk_serve_fail");
  const std::string log = db.path() + ".log";
  const fs::path home = db.path() + ".home";
  fs::create_directories(home);
  const std::string old_home = std::getenv("HOME") ? std::getenv("HOME") : "";
  const char* old_xdg = std::getenv("XDG_DATA_HOME");
  const std::string saved_xdg = old_xdg ? old_xdg : "";
  ::setenv("HOME", home.c_str(), 1);
  ::unsetenv("XDG_DATA_HOME");
  BusyPort busy;
  const auto o = run_avk({"serve", "--db", db.path(), "--port", busy.port()}, log);
  ::setenv("HOME", old_home.c_str(), 1);
  if (old_xdg) ::setenv("XDG_DATA_HOME", saved_xdg.c_str(), 1);
  EXPECT_TRUE(o.exited);
  EXPECT_NE(o.code, 0);
  EXPECT_NE(o.log.find(busy.port()), std::string::npos) << o.log;
  EXPECT_FALSE(fs::exists(home / ".local"))
      << "the default location was made although --db was given";
  EXPECT_FALSE(fs::exists(db.path() + ".token")) << "a failed start left its token file";
  fs::remove_all(home);
}

// Regression: --bind 0.0.0.0 printed no warning, only a 127.0.0.1 URL.
TEST(ServeOptions, ListeningOffThisMachineIsSaidAloud) {
  avk::testing::TempDb db("avk_serve_bind");
  const std::string log = db.path() + ".log";
  const auto o =
      run_avk({"serve", "--db", db.path(), "--port", "0", "--bind", "0.0.0.0"}, log, "WARNING");
  EXPECT_FALSE(o.exited) << o.log;  // it started, and was stopped once it had warned
  EXPECT_NE(o.log.find("reachable from other machines"), std::string::npos) << o.log;
  EXPECT_NE(o.log.find("http://127.0.0.1:"), std::string::npos) << o.log;
  fs::remove(db.path() + ".token");
}

// Through http://<a DNS name>:8080/ every request was 421 (the Host rule), and the Docker image
// could only be given names by rewriting its command line: `avk serve` also takes them from
// AVK_ALLOW_HOSTS (comma separated), beside --allow-host.
TEST(ServeOptions, AllowedHostNamesComeFromTheEnvironmentToo) {
  avk::testing::TempDb db("avk_serve_hosts");
  const std::string log = db.path() + ".log";
  const auto p = avk::testing::spawn_serve({"--db", db.path(), "--port", "0"}, log,
                                           {"AVK_ALLOW_HOSTS=station.example, Avk.Lan ,"});
  ASSERT_GT(p.port, 0) << read_file(log);
  const auto health = [&](const std::string& host) {
    return avk::testing::http_call(p.port, "GET", "/api/v1/health", "", {{"Host", host}});
  };
  for (const std::string host : {"station.example:8080", "station.example", "STATION.example",
                                 "avk.lan:8080", "127.0.0.1:8080"})
    EXPECT_EQ(health(host).status, 200) << host;
  const auto refused = health("other.example:8080");
  EXPECT_EQ(refused.status, 421);
  EXPECT_NE(refused.body.find("AVK_ALLOW_HOSTS"), std::string::npos) << refused.body;
  ::kill(p.pid, SIGTERM);
  int status = 0;
  ::waitpid(p.pid, &status, 0);
  fs::remove(log);
  fs::remove(db.path() + ".token");
}

TEST(ServeOptions, AnAllowedHostFromTheEnvironmentMustBeAHostName) {
  avk::testing::TempDb db("avk_serve_hosts_bad");
  const std::string log = db.path() + ".log";
  const auto o = run_avk({"serve", "--db", db.path(), "--port", "0"}, log, "",
                         std::chrono::seconds(30), {"AVK_ALLOW_HOSTS=station.example,http://x"});
  EXPECT_TRUE(o.exited) << "the server started";
  EXPECT_EQ(o.code, 2) << o.log;
  EXPECT_NE(o.log.find("AVK_ALLOW_HOSTS"), std::string::npos) << o.log;
  EXPECT_NE(o.log.find("'http://x'"), std::string::npos) << o.log;
  EXPECT_FALSE(fs::exists(db.path() + ".token"));
}

// A Docker bind mount owned by root (-v /host/dir:/var/lib/avk): the image's user could not write
// there and the start said only "cannot create the token file". It now names the folder (or the
// database file), its owner, the uid avk runs as and what to do. Root writes anywhere, so a test
// running as root runs avk as nobody (65534), as the image runs it as its own user.
TEST(ServeOptions, ADatabaseLocationThisUserCannotWriteIsNamedWithItsOwner) {
  avk::testing::TempDb db("avk_serve_ro");
  const fs::path dir = db.path() + ".dir";
  fs::create_directories(dir / "ro");
  fs::create_directories(dir / "rw");
  ASSERT_EQ(::chmod(dir.c_str(), 0755), 0);
  ASSERT_EQ(::chmod((dir / "ro").c_str(), 0555), 0);
  ASSERT_EQ(::chmod((dir / "rw").c_str(), 0777), 0);
  std::ofstream(dir / "rw" / "station.db") << "";
  ASSERT_EQ(::chmod((dir / "rw" / "station.db").c_str(), 0444), 0);
  const bool root = ::geteuid() == 0;
  const uid_t uid = root ? 65534 : ::geteuid();
  const gid_t gid = root ? 65534 : ::getegid();
  const auto start_as = [&](const fs::path& db_path, const std::string& log) {
    const std::vector<std::string> args = {"serve", "--db", db_path.string(), "--port", "0"};
    return wait_avk(
        root ? avk::testing::spawn_avk_as(uid, gid, args, log) : avk::testing::spawn_avk(args, log),
        log);
  };
  for (const fs::path& where : {dir / "ro", dir / "rw" / "station.db"}) {
    const fs::path db_path = where.filename() == "station.db" ? where : where / "station.db";
    const auto o = start_as(db_path, db.path() + ".log");
    if (o.log.find(avk::testing::kCannotChangeUser) != std::string::npos)
      GTEST_SKIP() << "running as root without the right to run avk as uid " << uid
                   << ", where write permissions would bite";
    struct stat st {};
    ASSERT_EQ(::stat(where.c_str(), &st), 0);
    EXPECT_TRUE(o.exited) << where << ": the server started";
    EXPECT_EQ(o.code, 1) << o.log;
    EXPECT_NE(o.log.find(where.string()), std::string::npos) << o.log;
    EXPECT_NE(o.log.find("owned by uid " + std::to_string(st.st_uid)), std::string::npos) << o.log;
    EXPECT_NE(o.log.find("avk runs as uid " + std::to_string(uid)), std::string::npos) << o.log;
    EXPECT_NE(o.log.find("chown " + std::to_string(uid)), std::string::npos) << o.log;
    EXPECT_EQ(o.log.find("cannot create the token file"), std::string::npos) << o.log;
    EXPECT_FALSE(fs::exists(db_path.string() + ".token")) << where;
  }
  ::chmod((dir / "ro").c_str(), 0755);
  fs::remove_all(dir);
}

// A database path whose folder is a regular file: said as such, whoever runs the test.
TEST(ServeOptions, ADatabaseFolderThatIsAFileIsNamed) {
  avk::testing::TempDb db("avk_serve_notdir");
  const std::string log = db.path() + ".log";
  const fs::path file = db.path() + ".file";
  std::ofstream(file) << "not a folder\n";
  const auto o = run_avk({"serve", "--db", (file / "station.db").string(), "--port", "0"}, log);
  EXPECT_TRUE(o.exited) << "the server started";
  EXPECT_EQ(o.code, 1) << o.log;
  EXPECT_NE(o.log.find(file.string() + " is not a folder"), std::string::npos) << o.log;
  fs::remove(file);
}

}  // namespace
