// plot_none.cpp - charts in a lean build (CLRT_LEAN=ON, no PLplot;
// CMakeLists.txt builds this file instead of plot.cpp): every --plot is
// refused before the measurement (UserError, exit 2). The palette and the
// markers (plot_style.cpp) are the same in both builds.
#include "image/plot.hpp"
#include "util/build_features.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"

namespace clrt {

namespace {

[[noreturn]] void no_plots(const std::string& path) {
  throw UserError("plot " + path + ": " + kLeanBuildNote + ": no plots (PLplot); use the full build");
}

}  // namespace

const std::vector<std::string>& plot_extensions() {
  static const std::vector<std::string> none;
  return none;
}

void check_plot_output(const std::string& path) {
  (void)check_output(path, "plot");  // a bad path first, as in the full build
  no_plots(path);
}

void write_plot(const std::string& path, const std::string&, const std::string&, const std::string&,
                const std::vector<Series>&, const PlotOptions&) {
  no_plots(path);
}

void write_plot(const std::string& path, const std::vector<PlotPanel>&) {
  no_plots(path);
}

}  // namespace clrt
