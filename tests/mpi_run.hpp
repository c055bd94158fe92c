// mpi_run.hpp - run the built clrt under mpirun, as CI does (the [mpi-cli]
// tests of tests/dist/ and tests/app/).
#pragma once
#include <cstdlib>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "dist/communicator.hpp"

namespace clrt_test {

// Whether mpirun can launch this clrt as ranks: on PATH, and clrt built with MPI.
inline bool have_mpirun() {
  return std::system("command -v mpirun >/dev/null 2>&1") == 0;
}
inline bool can_run_mpi() {
  return clrt::dist::built_with_mpi() && have_mpirun();
}

// CI's mpirun: -q (no banners: the job's stderr is clrt's own lines),
// oversubscribed (3 ranks on 2 cores), allowed as root (CI's containers);
// a job that hangs is ended after 10 minutes.
inline std::string mpirun_prefix(int ranks) {
  return "timeout 600 mpirun -q --oversubscribe --allow-run-as-root -np " + std::to_string(ranks) + " ";
}

// `mpirun -np RANKS clrt ARGS...`.
inline RunResult run_mpi(int ranks, const std::vector<std::string>& args) {
  return run_command_line(mpirun_prefix(ranks) + clrt_command(args));
}

// The lines of stderr that clrt wrote ("clrt: ..."; mpirun may add its own).
inline std::vector<std::string> clrt_lines(const std::string& err) {
  std::vector<std::string> lines;
  size_t at = 0;
  for (size_t nl; (nl = err.find('\n', at)) != std::string::npos; at = nl + 1)
    if (err.compare(at, 6, "clrt: ") == 0) lines.push_back(err.substr(at, nl - at));
  return lines;
}

}  // namespace clrt_test
