// Starts or removes the test run's shared PostgreSQL cluster (support/pg_cluster.hpp):
// pg_cluster_ctl start|stop DIR. CTest runs it as the pg_cluster fixture.
#include <iostream>
#include <string>

#include "support/pg_cluster.hpp"

int main(int argc, char** argv) {
  if (argc != 3 || (std::string(argv[1]) != "start" && std::string(argv[1]) != "stop")) {
    std::cerr << "usage: pg_cluster_ctl start|stop DIR\n";
    return 2;
  }
  try {
    if (std::string(argv[1]) == "start") {
      // Whatever an interrupted run left in the folder is stopped first.
      if (std::filesystem::exists(std::filesystem::path(argv[2]) / "port"))
        avk::testing::PgCluster(argv[2], avk::testing::PgCluster::Adopt{}).stop();
      avk::testing::PgCluster cluster(argv[2]);
      cluster.keep_running();
      std::cout << "test cluster at " << cluster.conninfo() << "\n";
    } else if (std::filesystem::exists(std::filesystem::path(argv[2]) / "port")) {
      avk::testing::PgCluster cluster(argv[2], avk::testing::PgCluster::Adopt{});
      cluster.stop();
      std::filesystem::remove_all(argv[2]);
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "pg_cluster_ctl: " << e.what() << "\n";
    return 1;
  }
}
