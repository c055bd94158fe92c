// pocl_workers.cpp - see pocl_workers.hpp.
#include "cl/pocl_workers.hpp"

#include <cstdlib>
#include <mutex>

#ifdef __linux__
#include <sched.h>
#include <unistd.h>
#endif

namespace clrt {

bool should_pin_pocl_workers(const char* affinity, const char* max_threads, const std::vector<int>& allowed,
                             long online) {
  if (affinity != nullptr || max_threads != nullptr) return false;  // the user's choice
  if (online < 2 || long(allowed.size()) != online) return false;
  for (size_t i = 0; i < allowed.size(); ++i)
    if (allowed[i] != int(i)) return false;
  return true;
}

std::vector<int> process_cpus() {
  std::vector<int> cpus;
#ifdef __linux__
  cpu_set_t mask;
  CPU_ZERO(&mask);
  if (sched_getaffinity(0, sizeof mask, &mask) != 0) return cpus;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
    if (CPU_ISSET(cpu, &mask)) cpus.push_back(cpu);
#endif
  return cpus;
}

void pin_pocl_workers_by_default() {
#ifdef __linux__
  static std::once_flag once;
  std::call_once(once, [] {
    if (should_pin_pocl_workers(std::getenv("POCL_AFFINITY"), std::getenv("POCL_MAX_PTHREAD_COUNT"), process_cpus(),
                                sysconf(_SC_NPROCESSORS_ONLN)))
      setenv("POCL_AFFINITY", "1", 0);
  });
#endif
}

}  // namespace clrt
