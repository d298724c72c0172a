// Start-up time of the `sutura` executable as a whole process (issue 28): wall time from spawn
// to exit of `sutura --version` and of a replay that neither draws nor reads a mesh file (a
// generated tube), median and spread of N alternating runs, for one or two executables (A/B in
// one run: the machine is shared and noisy).
//   bench_startup [--runs N] SUTURA [OTHER_SUTURA]
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

extern char** environ;

namespace {

// Wall seconds of one run of `args` (stdout and stderr to /dev/null); exits on a failed run.
double run_once(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  if (posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) != 0) {
    std::fprintf(stderr, "bench_startup: cannot start %s\n", argv[0]);
    std::exit(2);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  const auto end = std::chrono::steady_clock::now();
  posix_spawn_file_actions_destroy(&actions);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::fprintf(stderr, "bench_startup: %s %s failed\n", argv[0], args.size() > 1 ? args[1].c_str() : "");
    std::exit(2);
  }
  return std::chrono::duration<double>(end - start).count();
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * double(v.size() - 1) + 0.5)];
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 31;
  std::vector<std::string> exes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) runs = std::max(1, std::atoi(argv[++i]));
    else exes.push_back(a);
  }
  if (exes.empty() || exes.size() > 2) {
    std::fprintf(stderr, "usage: bench_startup [--runs N] SUTURA [OTHER_SUTURA]\n");
    return 2;
  }
  std::string pattern = (std::filesystem::temp_directory_path() / "sutura_bench_startup_XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) {
    std::fprintf(stderr, "bench_startup: cannot make a temporary directory\n");
    return 2;
  }
  const std::filesystem::path dir = pattern;
  const std::string session = (dir / "tube.jsonl").string();
  std::ofstream(session) << "{\"format\": \"sutura-session\", \"version\": 3}\n"
                            "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, "
                            "\"length\": 20, \"segments_around\": 16, \"segments_along\": 10}\n";
  const std::string out = (dir / "out").string();
  struct Case {
    const char* name;
    std::vector<std::string> args;
  };
  const std::vector<Case> cases = {{"--version", {"--version"}},
                                   {"replay (generate only)", {"replay", session, "--out", out, "--quiet"}}};
  std::printf("%-24s %-40s %10s %10s %10s\n", "case", "executable", "median ms", "p10 ms", "p90 ms");
  for (const Case& c : cases) {
    std::vector<std::vector<double>> times(exes.size());
    for (int r = 0; r < runs; ++r)
      for (std::size_t e = 0; e < exes.size(); ++e) {  // alternating: drift hits both alike
        std::vector<std::string> args{exes[e]};
        args.insert(args.end(), c.args.begin(), c.args.end());
        times[e].push_back(run_once(args));
      }
    for (std::size_t e = 0; e < exes.size(); ++e)
      std::printf("%-24s %-40s %10.1f %10.1f %10.1f\n", c.name, exes[e].c_str(),
                  1e3 * quantile(times[e], 0.5), 1e3 * quantile(times[e], 0.1),
                  1e3 * quantile(times[e], 0.9));
    if (exes.size() == 2)
      std::printf("%-24s %-40s %10.2f\n", c.name, "ratio (first / second), medians",
                  quantile(times[0], 0.5) / quantile(times[1], 0.5));
  }
  std::filesystem::remove_all(dir);
  return 0;
}
