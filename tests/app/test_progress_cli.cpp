// test_progress_cli.cpp - progress and --quiet as the user sees them: no
// progress when stderr is not a terminal, a bar with CLRT_PROGRESS=always
// (on stderr only), and -q/--quiet accepted by every command, silencing
// informational lines but never errors.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_progress_cli {

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using clrt_test::run_clrt;
using clrt_test::RunResult;
using clrt_test::TempDir;

namespace {

const std::vector<std::string> kCommands = {"devices",   "render",   "compare", "bench",   "sweep",   "scaling",
                                            "accuracy", "stability", "generate", "cache", "validate"};

std::string demo() {
  return clrt_test::source_path("scenes/cgfs-demo.json");
}

// A small run of each command that shows progress.
std::vector<std::vector<std::string>> progress_runs() {
  return {
      {"accuracy", demo(), "--width", "16", "--height", "16", "--repeat", "1", "--variants", "naive,robust"},
      {"sweep", demo(), "--depths", "0:1", "--width", "16", "--height", "16", "--repeat", "1"},
      {"bench", demo(), "--width", "16", "--height", "16", "--repeat", "1", "--no-omp", "--no-embree"},
      {"render", demo(), "--width", "16", "--height", "16", "-o", "-"},
  };
}

}  // namespace

TEST_CASE("every command takes -q/--quiet, before or after its name", "[cli][progress]") {
  for (const auto& c : kCommands) {
    INFO("clrt " << c);
    const RunResult help = run_clrt({c, "--help"});
    CHECK_THAT(help.out, Contains("-q,--quiet"));
  }
  CHECK_THAT(run_clrt({"--help"}).out, Contains("-q,--quiet"));
  TempDir dir;
  const RunResult gen = run_clrt({"-q", "generate", "--spheres", "3", "-o", dir / "s.json"});
  INFO(gen.err);
  CHECK(gen.status == 0);
  CHECK(gen.err.empty());
  const std::string env = "CLRT_CACHE_DIR=" + clrt_test::shell_quote(dir / "cache");
  CHECK(run_clrt({"cache", "info", "--quiet"}, env).status == 0);
  CHECK(run_clrt({"cache", "--quiet", "info"}, env).status == 0);
  CHECK(run_clrt({"--quiet", "devices"}).status == 0);
  // A mistyped command after --quiet still gets its suggestion.
  CHECK_THAT(run_clrt({"--quiet", "rendr"}).err, Contains("did you mean 'render'?"));
  // Errors are never silenced.
  const RunResult missing = run_clrt({"render", "--quiet", dir / "none.json", "-o", dir / clrt_test::image_name("x")});
  CHECK(missing.status == 2);
  CHECK(missing.one_line_error());
  CHECK_THAT(missing.err, StartsWith("clrt: error: "));
}

TEST_CASE("the --quiet flag silences informational lines", "[cli][progress][opencl]") {
  // With the image on stdout, render reports on stderr, and --verbose logs
  // the build options there: --quiet leaves only the image.
  const std::vector<std::string> args = {"render", demo(), "--width", "8", "--height", "8", "-o", "-", "--verbose"};
  const RunResult loud = run_clrt(args);
  INFO(loud.err);
  REQUIRE(loud.status == 0);
  CHECK_THAT(loud.err, Contains("clrt: build options"));
  CHECK_THAT(loud.err, Contains("kernel"));
  auto quiet_args = args;
  quiet_args.push_back("--quiet");
  const RunResult quiet = run_clrt(quiet_args);
  INFO(quiet.err);
  CHECK(quiet.status == 0);
  CHECK(quiet.err.empty());
  CHECK(clrt_test::starts_as_image(quiet.out));
}

TEST_CASE("progress is drawn only on a terminal (or when forced), on stderr only", "[cli][progress][opencl]") {
  for (const auto& args : progress_runs()) {
    INFO("clrt " << args[0]);
    // The tests' stderr is a file: nothing drawn.
    const RunResult plain = run_clrt(args);
    INFO(plain.err);
    REQUIRE(plain.status == 0);
    CHECK(plain.err.find('\r') == std::string::npos);
    CHECK(plain.err.find("] ") == std::string::npos);
    // Forced: a bar with its elapsed time, ended by a newline, and stdout as
    // it was.
    const RunResult forced = run_clrt(args, "CLRT_PROGRESS=always");
    INFO(forced.err);
    REQUIRE(forced.status == 0);
    CHECK(forced.err.rfind("\r[", 0) == 0);
    CHECK_THAT(forced.err, Contains(" 0:00 "));
    const size_t last_bar = forced.err.rfind('\r');
    CHECK(forced.err.find('\n', last_bar) != std::string::npos);
    if (args[0] != "render") {  // (a PNG holds \r\n bytes)
      CHECK(forced.out.find('\r') == std::string::npos);
      CHECK(forced.out.find("] ") == std::string::npos);
    }
    // --quiet wins over CLRT_PROGRESS=always.
    auto quiet = args;
    quiet.push_back("--quiet");
    const RunResult silent = run_clrt(quiet, "CLRT_PROGRESS=always");
    CHECK(silent.status == 0);
    CHECK(silent.err.find('\r') == std::string::npos);
  }
}

TEST_CASE("progress moves during a long frame on one device", "[cli][progress][opencl]") {
  // Before, a CPU frame was one launch: the bar showed 0/H rows until the
  // frame was done. Now it is cut into bands of about 250 ms once someone
  // watches. A 2000x2000 fp64 frame of the demo takes about 2 s on two
  // cores: the bar shows counts between 0 and all of its rows.
  TempDir dir;
  const RunResult r = run_clrt({"render", demo(), "--width", "2000", "--height", "2000", "--precision", "fp64", "-o",
                                dir / clrt_test::image_name("big")},
                               "CLRT_PROGRESS=always");
  INFO(r.err);
  if (r.status == 2 && r.err.find("cl_khr_fp64") != std::string::npos) {
    SUCCEED("the device has no fp64");
    return;
  }
  REQUIRE(r.status == 0);
  size_t between = 0;
  for (size_t at = r.err.find("] "); at != std::string::npos; at = r.err.find("] ", at + 1)) {
    const int done = std::atoi(r.err.c_str() + at + 2);
    between += done > 0 && done < 2000;
  }
  CHECK(between >= 1);
}

}  // namespace test_progress_cli
