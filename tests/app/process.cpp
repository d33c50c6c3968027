#include "process.hpp"

#include "test_support.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace gs::test {

ProcessResult runGhostspace(const std::vector<std::string>& args,
                            const std::vector<std::string>& env) {
  static std::atomic<int> counter{0};
  const auto dir = std::filesystem::temp_directory_path();
  const std::string stem =
      "gs_proc_" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  // Each run has a private XDG_RUNTIME_DIR, so windows of tests running side by side never
  // hand their inputs to each other (app/single_instance.hpp); `env` may name a shared one.
  const auto runtimeDir = dir / (stem + ".xdg");
  std::filesystem::create_directories(runtimeDir);
  const std::string runtimeEnv = "XDG_RUNTIME_DIR=" + runtimeDir.string();
  const auto outPath = dir / (stem + ".out");
  const auto errPath = dir / (stem + ".err");

  std::vector<std::string> argvStore{GS_EXECUTABLE};
  argvStore.insert(argvStore.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argvStore) argv.push_back(a.data());
  argv.push_back(nullptr);

  ProcessResult r;
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int o = ::open(outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = ::open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(o, 1);
    ::dup2(e, 2);
    ::putenv(const_cast<char*>(runtimeEnv.c_str()));
    for (const auto& kv : env) ::putenv(const_cast<char*>(kv.c_str()));
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  std::error_code ignored;
  std::filesystem::remove_all(runtimeDir, ignored);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readBytes(outPath);
  r.err = readBytes(errPath);
  std::filesystem::remove(outPath);
  std::filesystem::remove(errPath);
  return r;
}

}  // namespace gs::test
