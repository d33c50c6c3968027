// gs_fault_server: the tests' fault server (fault_server.hpp) as a program of its own, for
// the soak test (tests/soak/soak.sh, docs/soak.md). Serves the files of a folder on
// 127.0.0.1 with the faults asked for, until SIGINT or SIGTERM. Not installed.
//
//   gs_fault_server --root DIR [--port N] [--fault KIND]... [--cut BYTES] [--rate B/S]
//                   [--stall-seconds S] [--verbose]
//
// Connection i gets the i-th --fault (cycled); see --help for the kinds.
#include "http/fault_server.hpp"

#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  using gs::test::FaultServer;
  FaultServer::Config config;
  std::vector<std::string> faults;
  CLI::App cli{
      "Serves the files of a folder over HTTP on 127.0.0.1 with injected faults (the soak "
      "test's fault server; tests/http/fault_server.hpp). Runs until SIGINT or SIGTERM.",
      "gs_fault_server"};
  cli.add_option("--root", config.root, "Folder whose files are served")->required();
  cli.add_option("--port", config.port, "TCP port (0: one the kernel picks, printed)")
      ->check(CLI::Range(0, 65535));
  cli.add_option("--fault", faults,
                 "Behaviour of the next connection, in turn and cycled: serve, reset (RST after "
                 "--cut body bytes), reset-once, truncate (FIN after --cut bytes), stall (--cut "
                 "bytes, then silence for --stall-seconds), wrong-range (206 whose "
                 "Content-Range is --cut bytes off), ignore-ranges, short (Content-Length too "
                 "large), not-found, server-error, redirect, redirect-file")
      ->type_name("KIND");
  cli.add_option("--cut", config.cutAfter, "Body bytes sent before a fault (default 0)");
  cli.add_option("--rate", config.bytesPerSecond,
                 "Bytes per second at most of every response: a slow drip (0: unlimited)")
      ->check(CLI::NonNegativeNumber);
  cli.add_option("--stall-seconds", config.stallSeconds,
                 "How long a stall lasts before the connection is closed (default: until the "
                 "client closes or the server stops)");
  cli.add_flag("--verbose", config.verbose, "One line per request on stderr");
  CLI11_PARSE(cli, argc, argv);
  if (config.stallSeconds < 0.0) config.stallSeconds = 1e9;  // ends when the client closes
  for (const std::string& name : faults) {
    FaultServer::Behaviour b;
    if (!FaultServer::behaviourFromName(name, b)) {
      std::fprintf(stderr, "gs_fault_server: unknown --fault '%s'\n", name.c_str());
      return 2;
    }
    config.plan.push_back(b);
  }

  // SIGINT and SIGTERM are blocked before the server's thread starts (it inherits the
  // mask) and awaited here.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  FaultServer server(config);
  if (!server.ok()) {
    std::fprintf(stderr, "gs_fault_server: cannot listen on 127.0.0.1:%d\n", config.port);
    return 1;
  }
  std::printf("%s\n", server.url("/").c_str());
  std::fflush(stdout);
  int received = 0;
  sigwait(&signals, &received);
  return 0;
}
