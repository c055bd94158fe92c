// test_cli_conventions.cpp - what a user of command-line renderers expects:
// --version, the usage and one error line without a subcommand, a suggestion
// for a mistyped one, defaults and developer knobs in the help, `devices`
// numbering, `cache info` / `cache clear`, and a bash completion in step
// with the options.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "cli_run.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_cli_conventions {

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using clrt_test::run_clrt;
using clrt_test::RunResult;
using clrt_test::TempDir;
namespace fs = std::filesystem;

namespace {

// The version project() declares in CMakeLists.txt, read from the file.
std::string cmake_project_version() {
  const std::string text = clrt_test::slurp(clrt_test::source_path("CMakeLists.txt"));
  std::smatch m;
  REQUIRE(std::regex_search(text, m, std::regex(R"(project\(clrt[^)]*\bVERSION\s+([0-9][0-9.]*))")));
  return m[1];
}

void check_one_error(const RunResult& r, const std::string& needle) {
  INFO("stderr: " << r.err);
  CHECK(r.status == 2);
  CHECK(r.one_line_error());
  CHECK_THAT(r.err, StartsWith("clrt: error: "));
  CHECK_THAT(r.err, Contains(needle));
}

const std::vector<std::string> kCommands = {"devices",   "render",   "compare", "bench",   "sweep",   "scaling",
                                            "accuracy", "stability", "generate", "cache", "validate"};

// The long options `clrt COMMAND --help` lists (COMMAND: words, "cache warm").
std::set<std::string> help_options(const std::string& command) {
  std::vector<std::string> args;
  std::istringstream words(command);
  for (std::string w; words >> w;) args.push_back(w);
  args.push_back("--help");
  const RunResult r = run_clrt(args);
  REQUIRE(r.status == 0);
  std::set<std::string> out;
  std::istringstream in(r.out);
  std::string line;
  const std::regex option(R"(^  (?:(-[a-zA-Z]),)?(--[a-z0-9-]+))");
  std::smatch m;
  while (std::getline(in, line)) {
    if (!std::regex_search(line, m, option)) continue;
    if (m[1].matched && m[1] != "-h") out.insert(m[1]);  // -h: --help is offered
    out.insert(m[2]);
  }
  return out;
}

}  // namespace

TEST_CASE("clrt --version prints the version of CMakeLists.txt and how it was built", "[cli]") {
  const RunResult r = run_clrt({"--version"});
  INFO("stdout: " << r.out << "stderr: " << r.err);
  CHECK(r.status == 0);
  CHECK(r.err.empty());
  const std::string first = r.out.substr(0, r.out.find('\n'));
  CHECK(first == "clrt " + cmake_project_version());
  CHECK_THAT(r.out, Contains("built with "));
  CHECK_THAT(r.out, Contains(" build"));  // the build type (Release, Debug, ...)
  CHECK_THAT(run_clrt({"--help"}).out, Contains("--version"));
}

TEST_CASE("a bare clrt prints the usage and one error line", "[cli]") {
  const RunResult r = run_clrt({});
  check_one_error(r, "a subcommand is required (one of: devices, render, ");
  CHECK_THAT(r.out, Contains("Usage: clrt [OPTIONS] SUBCOMMAND"));
  for (const auto& c : kCommands) CHECK_THAT(r.out, Contains("  " + c + " "));
  const RunResult cache = run_clrt({"cache"});
  check_one_error(cache, "a cache subcommand is required (one of: info, warm, clear)");
  CHECK_THAT(cache.out, Contains("Usage: clrt cache [OPTIONS] SUBCOMMAND"));
}

TEST_CASE("a mistyped subcommand: one error line with a suggestion", "[cli]") {
  TempDir dir;
  const std::string out = dir / clrt_test::image_name("out");
  const RunResult r = run_clrt({"rendr", clrt_test::source_path("scenes/cgfs-demo.json"), "-o", out});
  check_one_error(r, "unknown command 'rendr'; did you mean 'render'?");
  CHECK(r.out.empty());
  CHECK_FALSE(fs::exists(out));
  check_one_error(run_clrt({"devcies"}), "unknown command 'devcies'; did you mean 'devices'?");
  check_one_error(run_clrt({"cache", "clr"}), "unknown cache command 'clr'; did you mean 'clear'?");
  // Nothing near: the list instead.
  check_one_error(run_clrt({"frobnicate"}), "unknown command 'frobnicate' (expected one of: devices, render, ");
  // Options: before a subcommand only clrt's own; after one, the subcommand's.
  check_one_error(run_clrt({"--bogus", "render"}), "unknown option '--bogus'");
  check_one_error(run_clrt({"render", clrt_test::source_path("scenes/cgfs-demo.json"), "-o", out, "--bogus"}),
                  "--bogus");
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("the help shows defaults and puts developer knobs in their own group", "[cli]") {
  const RunResult r = run_clrt({"render", "--help"});
  REQUIRE(r.status == 0);
  const std::string& help = r.out;
  CHECK_THAT(help, Contains("--width INT=600"));
  CHECK_THAT(help, Contains("--precision TEXT=robust"));
  CHECK_THAT(help, Contains("--engine TEXT=opencl"));
  CHECK_THAT(help, Contains("--accel TEXT=auto"));
  // No prose repeating a default CLI11 shows.
  CHECK_THAT(help, !Contains("(default"));
  CHECK_THAT(help, !Contains("default 600"));
  // Sentinels ("unset") show no number.
  CHECK_THAT(help, !Contains("--depth INT:INT in [0 - 64]=-1"));
  CHECK_THAT(help, !Contains("--max-launch-ms FLOAT=-1"));
  const size_t group = help.find("Developer options:");
  REQUIRE(group != std::string::npos);
  for (const char* knob : {"--local", "--lanes", "--band-rows", "--cl-options", "--kernel-dir", "--no-ftz",
                           "--max-launch-ms", "--no-specialize"}) {
    INFO(knob);
    CHECK(help.find(std::string("  ") + knob + " ") > group);
  }
  for (const char* user : {"--width", "--device", "--precision", "--output", "--verbose", "--no-cache"}) {
    INFO(user);
    CHECK(help.find(std::string(user) + " ") < group);
  }
  const std::string bench = run_clrt({"bench", "--help"}).out;
  CHECK(bench.find("--no-overlap") > bench.find("Developer options:"));
  CHECK(std::regex_search(bench, std::regex(R"(--repeat INT:INT in \[1 - 1000\]=[0-9]+\s)")));
  for (const auto& c : kCommands) {
    INFO(c);
    CHECK_THAT(run_clrt({c, "--help"}).out, !Contains("(default"));
  }
}

TEST_CASE("devices: platform:device numbers, driver, memory and the default", "[cli][opencl]") {
  const RunResult r = run_clrt({"devices"});
  INFO("stdout: " << r.out << "stderr: " << r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, StartsWith("index P:D "));
  CHECK_THAT(r.out, Contains("driver"));
  CHECK_THAT(r.out, Contains("memory"));
  // The default device's row: its index marked, then its P:D.
  CHECK(std::regex_search(r.out, std::regex(R"((^|\n)[0-9]+\* +[0-9]+:[0-9]+ )")));
  CHECK(std::regex_search(r.out, std::regex(R"( [0-9.]+ (GiB|MiB) )")));
  // What `devices` lists, --device takes: 0:0 is the first platform's first device.
  TempDir dir;
  const RunResult render = run_clrt({"render", clrt_test::source_path("scenes/cgfs-demo.json"), "--device", "0:0",
                                     "--width", "8", "--height", "8", "-o", dir / clrt_test::image_name("out")});
  INFO("render stderr: " << render.err);
  CHECK(render.status == 0);
  check_one_error(run_clrt({"render", clrt_test::source_path("scenes/cgfs-demo.json"), "--device", "9:9", "-o",
                            dir / clrt_test::image_name("x")}),
                  "unknown device \"9:9\"");
}

TEST_CASE("cache info and cache clear", "[cli][cache]") {
  TempDir dir;
  const std::string cache = (dir.path() / "cache").string();
  fs::create_directory(cache);
  const std::string env = "CLRT_CACHE_DIR=" + clrt_test::shell_quote(cache);
  std::ofstream(cache + "/0123456789abcdef.bin") << std::string(1000, 'x');
  std::ofstream(cache + "/fedcba9876543210.bin") << std::string(500, 'y');
  std::ofstream(cache + "/notes.txt") << "not an entry";

  RunResult info = run_clrt({"cache", "info"}, env);
  INFO("stdout: " << info.out << "stderr: " << info.err);
  CHECK(info.status == 0);
  CHECK_THAT(info.out, Contains("path     " + cache + "\n"));
  CHECK_THAT(info.out, Contains("entries  2\n"));
  CHECK_THAT(info.out, Contains("size     1500 bytes\n"));
  CHECK_THAT(info.out, Contains("limit    256.0 MiB (268435456 bytes), the default"));
  CHECK_THAT(info.out, Contains("other    1 file"));

  info = run_clrt({"cache", "info"}, env + " CLRT_CACHE_MAX_SIZE=64M");
  CHECK_THAT(info.out, Contains("limit    64.0 MiB (67108864 bytes), from CLRT_CACHE_MAX_SIZE"));
  check_one_error(run_clrt({"cache", "info"}, env + " CLRT_CACHE_MAX_SIZE=lots"), "CLRT_CACHE_MAX_SIZE");

  const RunResult clear = run_clrt({"cache", "clear"}, env);
  INFO("clear: " << clear.out << clear.err);
  CHECK(clear.status == 0);
  CHECK_THAT(clear.out, Contains("removed 2 entries (1500 bytes)"));
  CHECK(fs::exists(cache + "/notes.txt"));
  CHECK_FALSE(fs::exists(cache + "/0123456789abcdef.bin"));
  CHECK_THAT(run_clrt({"cache", "info"}, env).out, Contains("entries  0\n"));

  const RunResult missing = run_clrt({"cache", "info"}, "CLRT_CACHE_DIR=" + clrt_test::shell_quote(dir / "none"));
  CHECK(missing.status == 0);
  CHECK_THAT(missing.out, Contains("(does not exist yet)"));
  CHECK(run_clrt({"cache", "clear"}, "CLRT_CACHE_DIR=" + clrt_test::shell_quote(dir / "none")).status == 0);
}

TEST_CASE("cache warm stores the programs a render then loads", "[cli][cache][opencl]") {
  // A node's cache starts cold (the first frame builds: seconds on PoCL);
  // `cache warm` builds and stores what a render with the same options
  // would use, so that render loads it (its --verbose line says so).
  TempDir dir;
  const std::string storing = std::string(clrt_test::kStoringDriverEnv) + " ";
  const std::string env = storing + "CLRT_CACHE_DIR=" + clrt_test::shell_quote(dir / "cache");
  const std::string scene = dir / "one.json";  // (cold builds: clrt_test::kOneSphereScene says why)
  std::ofstream(scene) << clrt_test::kOneSphereScene;
  const std::vector<std::string> size{"--width", "64", "--height", "48", "--aspect", "image"};
  const auto with = [&](std::vector<std::string> args) {
    args.insert(args.end(), size.begin(), size.end());
    return args;
  };
  // Cold, a render builds (so that the check below can fail).
  RunResult cold = run_clrt(with({"render", scene, "-o", dir / clrt_test::image_name("cold"), "--verbose"}),
                            storing + "CLRT_CACHE_DIR=" + clrt_test::shell_quote(dir / "other"));
  INFO(cold.err);
  CHECK_THAT(cold.err, Contains("program built, stored in cache"));
  const RunResult warm = run_clrt(with({"cache", "warm", scene}), env);
  INFO(warm.out << warm.err);
  REQUIRE(warm.status == 0);
  CHECK_THAT(warm.out, Contains(scene + ": "));
  CHECK_THAT(warm.out, Contains("built and stored in the cache"));
  const RunResult render = run_clrt(with({"render", scene, "-o", dir / clrt_test::image_name("x"), "--verbose"}), env);
  INFO(render.err);
  CHECK(render.status == 0);
  CHECK_THAT(render.err, Contains("program loaded from cache"));
  CHECK_THAT(render.err, !Contains("program built"));
  CHECK_THAT(run_clrt(with({"cache", "warm", scene}), env).out, Contains("in the cache already"));
  // Float outputs take another program: --format warms it.
  if (!clrt::kLeanBuild) {
    REQUIRE(run_clrt(with({"cache", "warm", scene, "--format", "pfm"}), env).status == 0);
    const RunResult pfm = run_clrt(with({"render", scene, "-o", dir / "x.pfm", "--verbose"}), env);
    CHECK_THAT(pfm.err, Contains("program loaded from cache"));
  }
  check_one_error(run_clrt(with({"cache", "warm", scene, "--no-cache"}), env), "--no-cache");
  check_one_error(run_clrt(with({"cache", "warm", dir / "none.json"}), env), "none.json");
}

TEST_CASE("the bash completion knows every subcommand and option", "[cli]") {
  const std::string script = clrt_test::source_path("packaging/clrt.bash-completion");
  REQUIRE(fs::exists(script));
  TempDir dir;
  // Completes `clrt WORDS...` in bash and returns the candidates, one a line.
  auto complete = [&](const std::string& words) {
    const std::string cmd = "bash -c " +
                            clrt_test::shell_quote("source " + clrt_test::shell_quote(script) + "; COMP_WORDS=(clrt " +
                                                   words + "); COMP_CWORD=$((${#COMP_WORDS[@]}-1)); _clrt; " +
                                                   "printf '%s\\n' \"${COMPREPLY[@]}\"") +
                            " >" + clrt_test::shell_quote(dir / "out") + " 2>&1";
    REQUIRE(std::system(cmd.c_str()) == 0);
    std::set<std::string> out;
    std::istringstream in(clrt_test::slurp(dir / "out"));
    for (std::string line; std::getline(in, line);)
      if (!line.empty()) out.insert(line);
    return out;
  };
  const auto commands = complete("''");
  for (const auto& c : kCommands) CHECK(commands.count(c) == 1);
  CHECK(complete("ren") == std::set<std::string>{"render"});
  CHECK(complete("cache ''") == std::set<std::string>{"info", "clear", "warm"});
  CHECK(complete("cache warm -") == help_options("cache warm"));
  CHECK(complete("render --precision r") == std::set<std::string>{"robust"});
  for (const auto& c : kCommands) {
    if (c == "cache") continue;
    INFO("clrt " << c);
    CHECK(complete(c + " -") == help_options(c));
  }
}

}  // namespace test_cli_conventions
