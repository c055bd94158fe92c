// tracers_none.cpp - the comparison tracers in a lean build (CLRT_LEAN=ON:
// no OpenMP tracer, no Embree; CMakeLists.txt builds this file into
// clrt_core instead of the libraries clrt_omp and clrt_embree). `clrt bench`
// does not call them there (eval/bench.cpp says why they were not run); a
// call is refused all the same.
#include "embree_tracer.hpp"
#include "omp_tracer.hpp"
#include "util/build_features.hpp"
#include "util/error.hpp"

namespace clrt_bench {

namespace {

[[noreturn]] void no_tracers() {
  throw clrt::UserError(std::string(clrt::kLeanBuildNote) + ": no Embree/OpenMP comparison tracers");
}

}  // namespace

int omp_render(const clrt::Scene&, int, int, int, std::vector<float>&) {
  no_tracers();
}
int omp_render(const clrt::Scene&, int, int, int, std::vector<uint8_t>&) {
  no_tracers();
}
void omp_warm_threads() {
  no_tracers();
}
int embree_render(const clrt::Scene&, int, int, int, std::vector<float>&, EmbreeBuildInfo*, EmbreeSpheres) {
  no_tracers();
}
int embree_render(const clrt::Scene&, int, int, int, std::vector<uint8_t>&, EmbreeBuildInfo*, EmbreeSpheres) {
  no_tracers();
}

}  // namespace clrt_bench
