// process_bench.cpp - clrt_process_bench: whole processes, compared.
//
//   clrt_process_bench [-n ROUNDS] [--warmup K] -c 'CMD ARGS...' [-c 'CMD ARGS...' ...]
//
// Runs each command line once per round, alternating (round r starts with
// command r mod k, so that no command always runs first), after K unmeasured
// warm-up rounds. Each run is a posix_spawn and a wait4: wall time from just
// before the spawn to the child's exit, the child's user+system CPU time and
// its peak resident set (ru_maxrss). Prints, per command, mean ± sd, min, max
// and N of each, and per command after the first the ratio to the first,
// taken within each round. A command line is split at spaces (no quoting);
// leading NAME=VALUE words are set in its environment. Its standard output is
// discarded; a run that fails (status != 0) stops the bench and shows its
// standard error. A benchmark tool, not part of clrt.
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

namespace {

struct Command {
  std::string text;
  std::vector<std::string> env, argv;
};

struct Run {
  double wall_ms, cpu_ms, rss_mb;
};

struct Summary {
  double mean = 0, sd = 0, min = 0, max = 0;
  size_t n = 0;
};

Summary summarize(const std::vector<double>& v) {
  Summary s;
  s.n = v.size();
  if (v.empty()) return s;
  for (double x : v) s.mean += x;
  s.mean /= double(v.size());
  for (double x : v) s.sd += (x - s.mean) * (x - s.mean);
  s.sd = v.size() > 1 ? std::sqrt(s.sd / double(v.size() - 1)) : 0;
  s.min = *std::min_element(v.begin(), v.end());
  s.max = *std::max_element(v.begin(), v.end());
  return s;
}

void print(const char* what, const Summary& s, const char* unit, int digits) {
  std::printf("  %-10s %.*f ± %.*f %s  (min %.*f, max %.*f, N=%zu)\n", what, digits, s.mean, digits, s.sd, unit, digits,
              s.min, digits, s.max, s.n);
}

Command parse_command(const std::string& text) {
  Command c;
  c.text = text;
  std::istringstream in(text);
  std::string word;
  while (in >> word) {
    const auto eq = word.find('=');
    if (c.argv.empty() && eq != std::string::npos && eq > 0 && word.find('/') > eq)
      c.env.push_back(word);
    else
      c.argv.push_back(word);
  }
  if (c.argv.empty()) throw std::runtime_error("empty command: '" + text + "'");
  return c;
}

// The environment of `c`: ours, with its NAME=VALUE words replacing ours.
std::vector<std::string> environment(const Command& c) {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) {
    const std::string var = *e;
    const std::string name = var.substr(0, var.find('='));
    bool replaced = false;
    for (const auto& own : c.env) replaced |= own.compare(0, name.size() + 1, name + "=") == 0;
    if (!replaced) env.push_back(var);
  }
  env.insert(env.end(), c.env.begin(), c.env.end());
  return env;
}

std::vector<char*> pointers(std::vector<std::string>& words) {
  std::vector<char*> p;
  for (auto& w : words) p.push_back(&w[0]);
  p.push_back(nullptr);
  return p;
}

Run run_once(const Command& c, const std::string& err_path) {
  std::vector<std::string> argv_words = c.argv, env_words = environment(c);
  std::vector<char*> argv = pointers(argv_words), envp = pointers(env_words);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  const auto t0 = std::chrono::steady_clock::now();
  pid_t pid;
  const int rc = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start '" + c.text + "': " + std::strerror(rc));
  int status = 0;
  struct rusage ru {};
  while (wait4(pid, &status, 0, &ru) < 0)
    if (errno != EINTR) throw std::runtime_error(std::string("wait4: ") + std::strerror(errno));
  const auto t1 = std::chrono::steady_clock::now();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::ifstream err(err_path);
    std::stringstream text;
    text << err.rdbuf();
    throw std::runtime_error("'" + c.text + "' failed (" +
                             (WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                                : "signal " + std::to_string(WTERMSIG(status))) +
                             "); its standard error:\n" + text.str());
  }
  const double cpu =
      (ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) * 1e3 + (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) / 1e3;
  return {std::chrono::duration<double, std::milli>(t1 - t0).count(), cpu, ru.ru_maxrss / 1024.0};
}

int usage(const char* self) {
  std::fprintf(stderr, "usage: %s [-n ROUNDS] [--warmup K] -c 'CMD ARGS...' [-c 'CMD ARGS...' ...]\n", self);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  int rounds = 10, warmup = 1;
  std::vector<Command> commands;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (i + 1 >= argc) return usage(argv[0]);
      if (a == "-n")
        rounds = std::stoi(argv[++i]);
      else if (a == "--warmup")
        warmup = std::stoi(argv[++i]);
      else if (a == "-c")
        commands.push_back(parse_command(argv[++i]));
      else
        return usage(argv[0]);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "clrt_process_bench: error: %s\n", e.what());
    return 2;
  }
  if (commands.empty() || rounds < 1 || warmup < 0) return usage(argv[0]);

  char err_template[] = "/tmp/clrt_process_bench_XXXXXX";
  const int fd = mkstemp(err_template);
  if (fd < 0) {
    std::perror("clrt_process_bench: mkstemp");
    return 2;
  }
  close(fd);
  const std::string err_path = err_template;
  const size_t k = commands.size();
  std::vector<std::vector<Run>> runs(k);
  try {
    for (int r = 0; r < warmup + rounds; ++r)
      for (size_t j = 0; j < k; ++j) {
        const size_t c = (size_t(r) + j) % k;
        const Run run = run_once(commands[c], err_path);
        if (r >= warmup) runs[c].push_back(run);
      }
  } catch (const std::exception& e) {
    unlink(err_path.c_str());
    std::fprintf(stderr, "clrt_process_bench: error: %s\n", e.what());
    return 1;
  }
  unlink(err_path.c_str());

  std::printf("%d rounds after %d warm-up round(s), the commands alternating\n", rounds, warmup);
  for (size_t c = 0; c < k; ++c) {
    std::vector<double> wall, cpu, rss;
    for (const Run& run : runs[c]) wall.push_back(run.wall_ms), cpu.push_back(run.cpu_ms), rss.push_back(run.rss_mb);
    std::printf("[%zu] %s\n", c + 1, commands[c].text.c_str());
    print("wall", summarize(wall), "ms", 1);
    print("cpu", summarize(cpu), "ms", 1);
    print("peak RSS", summarize(rss), "MB", 1);
    if (c > 0) {
      std::vector<double> ratio;
      for (int r = 0; r < rounds; ++r) ratio.push_back(runs[c][size_t(r)].wall_ms / runs[0][size_t(r)].wall_ms);
      print("wall/[1]", summarize(ratio), "", 2);
    }
  }
  return 0;
}
