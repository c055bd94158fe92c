// test_mpi_cli.cpp - `clrt render` launched by mpirun with 3 ranks, as a user
// runs it: the image equals a single-process render pixel for pixel, and a
// failure anywhere (bad input on rank 0, a bad device on one rank, a rank
// killed) ends the job with one `clrt: error:` line and no output or temp
// file. Skipped (with a message) where mpirun is absent or clrt was built
// without MPI; there, the refusal of an mpirun launch is tested instead.
#include <signal.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "cli_run.hpp"
#include "dist/communicator.hpp"
#include "image/image_file.hpp"
#include "mpi_run.hpp"
#include "test_util.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_mpi_cli {

namespace fs = std::filesystem;
using clrt_test::have_mpirun;
using clrt_test::run_command_line;
using clrt_test::RunResult;
using clrt_test::shell_quote;
using clrt_test::TempDir;

namespace {

// The lines of `text` that start with `prefix`.
int lines_starting(const std::string& text, const std::string& prefix) {
  int n = 0;
  size_t at = 0;
  while (at < text.size()) {
    const size_t end = text.find('\n', at);
    if (text.compare(at, prefix.size(), prefix) == 0) ++n;
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return n;
}

// Pixels only (the files' metadata names the ranks).
void require_same_pixels(const std::string& a, const std::string& b) {
  const clrt::Image x = clrt::read_image(a, 4096, 1 << 24), y = clrt::read_image(b, 4096, 1 << 24);
  REQUIRE(x.width == y.width);
  REQUIRE(x.height == y.height);
  CHECK(clrt::to_u8(x) == clrt::to_u8(y));
  CHECK(x.rgb == y.rgb);
}

#define SKIP_WITHOUT_MPI()                                                         \
  if (!clrt_test::can_run_mpi()) {                                                 \
    WARN("skipped: " << (have_mpirun() ? "clrt built without MPI" : "no mpirun")); \
    return;                                                                        \
  }

}  // namespace

TEST_CASE("mpirun -np 3 clrt render: the same pixels as one process", "[mpi-cli][opencl]") {
  SKIP_WITHOUT_MPI();
  TempDir dir;
  const std::string scene = clrt_test::source_path("scenes/cgfs-demo.json");
  struct Case {
    std::string name;
    std::vector<std::string> options;
  };
  const Case cases[] = {
      {"demo.ppm", {"--width", "320", "--height", "200"}},
      {"demo.pfm", {"--width", "160", "--height", "123", "--spp", "2", "--mpi-tile-rows", "5"}},
      {"demo-sub.ppm", {"--width", "200", "--height", "90", "--subsample", "interpolate", "--mpi-tile-rows", "1"}},
  };
  for (const Case& c : cases) {
    std::vector<std::string> one{"render", scene, "-o", dir / ("one-" + c.name), "-q"};
    std::vector<std::string> many{"render", scene, "-o", dir / c.name, "-q"};
    one.insert(one.end(), c.options.begin(), c.options.end());
    many.insert(many.end(), c.options.begin(), c.options.end());
    const RunResult single = clrt_test::run_clrt(one);
    REQUIRE(single.status == 0);
    const RunResult job = run_command_line(clrt_test::mpirun_prefix(3) + clrt_test::clrt_command(many));
    INFO(job.err);
    REQUIRE(job.status == 0);
    // The report: the frame, then one line per rank.
    CHECK_THAT(job.out, Catch::Contains("on 3 MPI ranks"));
    CHECK(lines_starting(job.out, "  rank ") == 3);
    require_same_pixels(dir / ("one-" + c.name), dir / c.name);
  }
}

TEST_CASE("mpirun: bad input is one error line from rank 0, before any work", "[mpi-cli]") {
  SKIP_WITHOUT_MPI();
  TempDir dir;
  dir.write("bad.json", "{\"spheres\": [");
  const std::string out = dir / "out.ppm";
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"render", dir / "bad.json", "-o", out},
           {"render", clrt_test::source_path("scenes/cgfs-demo.json"), "-o", dir / "no-such-dir/out.ppm"},
           {"render", clrt_test::source_path("scenes/cgfs-demo.json"), "-o", out, "--width", "0"},
           {"render", clrt_test::source_path("scenes/cgfs-demo.json"), "-o", out, "--engine", "reference"},
           {"bench", clrt_test::source_path("scenes/cgfs-demo.json")},
       }) {
    const RunResult job = run_command_line(clrt_test::mpirun_prefix(3) + clrt_test::clrt_command(args));
    INFO(args[1] << " " << job.err);
    CHECK(job.status == 2);
    CHECK(job.one_line_error());
    CHECK(lines_starting(job.err, "clrt: error: ") == 1);
  }
  CHECK(dir.entries() == std::vector<std::string>{"bad.json"});
}

TEST_CASE("mpirun: a bad device on one rank ends the job, naming the rank", "[mpi-cli][opencl]") {
  SKIP_WITHOUT_MPI();
  TempDir dir;
  const std::string scene = clrt_test::source_path("scenes/cgfs-demo.json"), out = dir / clrt_test::image_name("out");
  // MPMD: ranks 0 and 1 as usual, rank 2 with a device that does not exist.
  const std::vector<std::string> args{"render", scene,      "-o",  out,        "--width",
                                      "200",    "--height", "100", "--aspect", "image"};
  std::vector<std::string> bad = args;
  bad.insert(bad.end(), {"--device", "99"});
  const RunResult job = run_command_line("timeout 600 mpirun -q --oversubscribe --allow-run-as-root -np 2 " +
                                         clrt_test::clrt_command(args) + " : -np 1 " + clrt_test::clrt_command(bad));
  INFO(job.err);
  CHECK(job.status == 2);
  CHECK(job.one_line_error());
  CHECK_THAT(job.err, Catch::StartsWith("clrt: error: rank 2 ("));
  CHECK(dir.entries().empty());
}

TEST_CASE("mpirun: a rank killed mid-frame ends the job with no output or temp file", "[mpi-cli][opencl]") {
  SKIP_WITHOUT_MPI();
  TempDir dir;
  const std::string out = dir / clrt_test::image_name("killed");
  // A frame of several seconds (spp 16 over 3 ranks on 2 cores).
  const std::string line = clrt_test::mpirun_prefix(3) +
                           clrt_test::clrt_command({"render", clrt_test::source_path("scenes/cgfs-demo.json"), "-o",
                                                    out, "--width", "1280", "--height", "720", "--spp", "16"});
  RunResult job;
  std::thread runner([&] { job = run_command_line(line); });
  // Find rank 1 (its environment says so) among the processes writing `out`, once it renders: it has loaded an
  // OpenCL driver (which clrt asks for only after MPI's start, when every rank knows who reports a signal; killed
  // before, under load, the other ranks were still starting and each printed its own line), and ~0.5 s more.
  bool killed = false;
  int rendering_since = -1;
  for (int attempt = 0; attempt < 400 && !killed; ++attempt) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    for (const auto& proc : fs::directory_iterator("/proc")) {
      const std::string pid = proc.path().filename();
      if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
      const std::string cmdline = clrt_test::slurp(proc.path() / "cmdline");
      if (cmdline.find(out) == std::string::npos || cmdline.find("mpirun") != std::string::npos) continue;
      const std::string env = clrt_test::slurp(proc.path() / "environ");
      if (env.find(std::string("OMPI_COMM_WORLD_RANK=1") + '\0') == std::string::npos) continue;
      const std::string maps = clrt_test::slurp(proc.path() / "maps");
      if (rendering_since < 0 &&
          (maps.find("libpocl") != std::string::npos || maps.find("Rusticl") != std::string::npos))
        rendering_since = attempt;
      if (rendering_since < 0 || attempt < rendering_since + 10) break;
      killed = ::kill(std::stoi(pid), SIGKILL) == 0;
      break;
    }
  }
  runner.join();
  INFO(job.err);
  REQUIRE(killed);
  CHECK(job.status != 0);
  CHECK(lines_starting(job.err, "clrt: error: ") == 1);
  CHECK_THAT(job.err, Catch::Contains("mpirun ends every rank"));
  CHECK(dir.entries().empty());  // neither the image nor its temp file
}

TEST_CASE("a clrt built without MPI refuses an mpirun launch", "[mpi-cli]") {
  if (clrt::dist::built_with_mpi() || !have_mpirun()) {
    WARN("skipped: " << (have_mpirun() ? "clrt built with MPI (the tests above run)" : "no mpirun"));
    return;
  }
  TempDir dir;
  const RunResult job = run_command_line(
      clrt_test::mpirun_prefix(2) +
      clrt_test::clrt_command({"render", clrt_test::source_path("scenes/cgfs-demo.json"), "-o", dir / "x.ppm"}));
  CHECK(job.status == 2);
  CHECK(job.one_line_error());
  CHECK_THAT(job.err, Catch::Contains("built without MPI"));
  CHECK(dir.entries().empty());
}

TEST_CASE("mpirun: a rank whose link stalls mid-message ends the job within the bound, naming it",
          "[mpi-cli][opencl]") {
  SKIP_WITHOUT_MPI();
  TempDir dir;
  const std::string out = dir / clrt_test::image_name("stalled");
  // Over TCP (through shared memory rank 0 would read the rest of a message
  // itself): rank 2 stops taking part in MPI in the middle of its first rows
  // message (the hidden test hook), a 67-row tile of 640-pixel rows, 171 KB,
  // past TCP's 64 KiB eager limit: its bytes stop flowing. Ranks 0 and 1 get
  // the rest of the frame's tiles meanwhile; rank 0 then ends the job after
  // the bound (3 s here), naming rank 2. Before, rank 0 sat in a blocking
  // receive of those rows: no rank got another tile, and the job never
  // ended (`timeout` ends it here after 120 s, before CTest's limit, so that
  // a hang shows its output; a machine with load 10 on 2 cores once saw
  // mpirun wait on after its three ranks had exited).
  const std::string line =
      "timeout 120 mpirun -q --oversubscribe --allow-run-as-root --mca btl tcp,self -np 3 " +
      clrt_test::clrt_command({"render", clrt_test::source_path("scenes/cgfs-demo.json"), "-o", out, "--width", "640",
                               "--height", "480", "--aspect", "image", "--mpi-test-stall", "2", "--mpi-timeout", "3"});
  RunResult job = run_command_line(line);
  // Open MPI 4.1's mpirun itself sometimes crashes while it tears the job
  // down after MPI_Abort (SIGSEGV in PMIx_server_finalize, under orte_finalize,
  // after clrt's error line: seen once in CI at load ~4 on 2 cores, never in
  // 15 quiet runs). That is the launcher's fault, not the job's: run again.
  if (job.status != 2 && job.err.find("PMIx_server_finalize") != std::string::npos) {
    WARN("mpirun crashed in its own teardown (Open MPI's PMIx_server_finalize); running the job again");
    job = run_command_line(line);
  }
  INFO(job.err);
  CHECK(job.status == 2);
  const std::vector<std::string> lines = clrt_test::clrt_lines(job.err);
  REQUIRE(lines.size() == 1);
  CHECK_THAT(lines[0], Catch::StartsWith("clrt: error: rank 2 ("));
  CHECK_THAT(lines[0], Catch::Contains("no message for 3 s (--mpi-timeout)"));
  // The other ranks were served: most of the frame arrived (all but rank 2's
  // two tiles, at most a third of it).
  const size_t at = lines[0].find("; ");
  REQUIRE(at != std::string::npos);
  const int rows = std::stoi(lines[0].substr(at + 2));
  CHECK(rows >= 480 * 2 / 3);
  CHECK(rows < 480);
  CHECK(dir.entries().empty());
}

TEST_CASE("mpirun killed mid-frame: no rank outlives it, nothing is written", "[mpi-cli][opencl]") {
  SKIP_WITHOUT_MPI();
  TempDir dir;
  const std::string out = dir / clrt_test::image_name("orphan");
  // A frame of several seconds (spp 16 over 3 ranks on 2 cores). mpirun
  // killed with SIGKILL ends none of its ranks itself (a second SIGTERM, as
  // `timeout` and schedulers send, does the same): each rank must stop on
  // its own (PR_SET_PDEATHSIG) and rank 0 must not write the frame.
  const std::string line = "mpirun -q --oversubscribe --allow-run-as-root -np 3 " +
                           clrt_test::clrt_command({"render", clrt_test::source_path("scenes/cgfs-demo.json"), "-o",
                                                    out, "--width", "1280", "--height", "720", "--spp", "16"});
  RunResult job;
  std::thread runner([&] { job = run_command_line(line); });
  // The processes of this job: mpirun (its first word) and the ranks (their
  // environment names their rank).
  const auto job_processes = [&](bool want_mpirun) {
    std::vector<int> pids;
    for (const auto& proc : fs::directory_iterator("/proc")) {
      const std::string pid = proc.path().filename();
      if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
      const std::string cmdline = clrt_test::slurp(proc.path() / "cmdline");
      if (cmdline.find(out) == std::string::npos) continue;
      const std::string first = cmdline.substr(0, cmdline.find('\0'));
      const bool is_mpirun = fs::path(first).filename() == "mpirun";
      const bool is_rank =
          clrt_test::slurp(proc.path() / "environ").find("OMPI_COMM_WORLD_RANK=") != std::string::npos;
      if (want_mpirun ? is_mpirun : is_rank && !is_mpirun) pids.push_back(std::stoi(pid));
    }
    return pids;
  };
  // Kill mpirun once its three ranks have run for ~1.5 s (they render).
  bool killed = false;
  for (int attempt = 0; attempt < 400 && !killed; ++attempt) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (job_processes(false).size() < 3) continue;
    for (int wait = 0; wait < 30; ++wait) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    for (int pid : job_processes(true)) killed = ::kill(pid, SIGKILL) == 0 || killed;
  }
  runner.join();
  REQUIRE(killed);
  // Every rank gone within a few seconds (PDEATHSIG: at once; before, the
  // ranks rendered on, and rank 0 could write the frame after mpirun had
  // returned).
  std::vector<int> left = job_processes(false);
  for (int wait = 0; wait < 100 && !left.empty(); ++wait) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    left = job_processes(false);
  }
  CHECK(left.empty());
  for (int pid : left) ::kill(pid, SIGKILL);
  CHECK(dir.entries().empty());  // neither the image nor its temp file
}

TEST_CASE("mpirun clrt cache warm: every rank warms its node's cache, rank 0 reports", "[mpi-cli][cache][opencl]") {
  SKIP_WITHOUT_MPI();
  TempDir dir;
  // (Both ranks run here, so they share one cache: the second finds the
  // entry the first stored, or stores the same one; either is a warm cache.)
  const std::string env =
      std::string(clrt_test::kStoringDriverEnv) + " CLRT_CACHE_DIR=" + shell_quote(dir / "cache") + " ";
  const std::string scene = clrt_test::source_path("scenes/cgfs-demo.json");
  const RunResult job = run_command_line(
      env + clrt_test::mpirun_prefix(2) +
      clrt_test::clrt_command({"cache", "warm", scene, "--width", "64", "--height", "48", "--aspect", "image"}));
  INFO(job.out << job.err);
  CHECK(job.status == 0);
  CHECK(lines_starting(job.out, "rank 0 (") == 1);
  CHECK(lines_starting(job.out, "rank 1 (") == 1);
  const RunResult render = clrt_test::run_clrt({"render", scene, "-o", dir / clrt_test::image_name("x"), "--width",
                                                "64", "--height", "48", "--aspect", "image", "--verbose"},
                                               env.substr(0, env.size() - 1));
  INFO(render.err);
  CHECK_THAT(render.err, Catch::Contains("program loaded from cache"));
}

}  // namespace test_mpi_cli
