// environment.cpp - what the environment says about an mpirun launch
// (shared by the MPI and the single-process builds).
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

}  // namespace clrt::dist
