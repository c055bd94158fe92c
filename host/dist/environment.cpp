// environment.cpp - what the environment says about an mpirun launch, and
// the watch on the launcher (shared by the MPI and the single-process
// builds).
#include <sys/prctl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <string>

#include "dist/communicator.hpp"

namespace clrt::dist {

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

int environment_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    if (const char* v = std::getenv(name)) return std::atoi(v);
  return 0;
}

namespace {

std::atomic<double> g_silence_bound_s{kDefaultSilenceBoundS};

}  // namespace

void set_silence_bound_s(double seconds) {
  g_silence_bound_s = seconds;
}

double silence_bound_s() {
  return g_silence_bound_s.load();
}

namespace {

// The parent at start (mpirun, or Open MPI's daemon on another node) and,
// where the environment names it, the launching daemon's own pid; 0: none.
std::atomic<pid_t> g_parent{0}, g_launcher{0};

// Open MPI names each node's session directory after the pid of the daemon
// that launched the ranks there (mpirun itself on its own node):
// .../ompi.HOST.UID/pid.PID (OMPI_MCA_orte_jobfam_session_dir,
// PMIX_SERVER_TMPDIR). 0 where neither says so.
pid_t launcher_from_environment() {
  for (const char* name : {"OMPI_MCA_orte_jobfam_session_dir", "PMIX_SERVER_TMPDIR"}) {
    const char* v = std::getenv(name);
    if (!v) continue;
    const std::string dir = v;
    const size_t at = dir.rfind("/pid.");
    if (at == std::string::npos) continue;
    const std::string digits = dir.substr(at + 5);
    if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    return pid_t(std::atol(digits.c_str()));
  }
  return 0;
}

}  // namespace

void watch_launcher() {
  if (!launched_by_mpi()) return;
  // The kernel sends SIGTERM when the parent ends (mpirun killed, or cancelled
  // twice: it then exits without ending its ranks): the signal handler
  // removes any temp file and exits, so an orphaned rank never finishes a
  // frame nobody waits for, and rank 0 never writes after the job ended.
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  // PDEATHSIG is not armed for a parent that died before the call above:
  // the parent and launcher recorded here let launcher_gone() tell.
  g_parent = ::getppid();
  g_launcher = launcher_from_environment();
  if (launcher_gone()) std::raise(SIGTERM);
}

bool launcher_gone() {
  const pid_t parent = g_parent.load();
  if (parent == 0) return false;  // not watched: not an mpirun launch
  if (::getppid() != parent) return true;
  // (a wrapper between mpirun and clrt is the parent; the launcher is then
  // checked on its own)
  const pid_t launcher = g_launcher.load();
  return launcher > 0 && ::kill(launcher, 0) != 0 && errno == ESRCH;
}

void stop_if_orphaned() {
  if (launcher_gone()) std::raise(SIGTERM);
}

}  // namespace clrt::dist
