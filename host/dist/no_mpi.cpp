// no_mpi.cpp - dist/communicator.hpp in a build without MPI (CLRT_MPI=OFF):
// always a world of one process.
#include "dist/communicator.hpp"
#include "dist/single_process.hpp"

namespace clrt::dist {

Communicator& world() {
  static SingleProcess one;
  return one;
}

Session::Session(int&, char**&) {}
Session::~Session() = default;

bool built_with_mpi() {
  return false;
}

std::string mpi_version() {
  return "built without MPI";
}

}  // namespace clrt::dist
