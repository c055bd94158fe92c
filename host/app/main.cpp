// main.cpp - the clrt command line: one subcommand per cmd_<name>.cpp.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

#include "app/options.hpp"
#include "cl/cl.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"

namespace {

// Every error is one line on stderr, whatever a library put in its message.
void report(std::string msg, const char* what = "error") {
  for (auto& c : msg)
    if (c == '\n' || c == '\r') c = ' ';
  std::cerr << "clrt: " << what << ": " << msg << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"clrt - OpenCL Whitted ray tracer (Computer Graphics from Scratch, ch. 2-5) with a double reference"};
  app.require_subcommand(1);
  clrt::add_devices_command(app);
  clrt::add_render_command(app);
  clrt::add_compare_command(app);
  clrt::add_bench_command(app);
  clrt::add_sweep_command(app);
  clrt::add_scaling_command(app);
  clrt::add_accuracy_command(app);
  clrt::add_stability_command(app);
  clrt::add_generate_command(app);
  clrt::install_signal_cleanup();
  try {
    app.parse(argc, argv);
    // Results printed to stdout (tables, JSON) must have reached it: a full
    // disk or closed pipe is an error, not a silent truncation.
    if (std::fflush(stdout) != 0 || std::ferror(stdout))
      throw clrt::UserError(std::string("cannot write standard output: ") + std::strerror(errno));
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    report(e.what());
    return clrt::kExitBadInput;
  } catch (const clrt::CheckFailure& e) {
    report(e.what(), "check failed");
    return clrt::kExitCheckFailed;
  } catch (const clrt::UserError& e) {
    report(e.what());
    return clrt::kExitBadInput;
  } catch (const clrt::DeviceError& e) {
    report(e.what());
    return clrt::kExitBadInput;
  } catch (const cl::Error& e) {
    report(clrt::describe(e));
    return clrt::kExitBadInput;
  } catch (const std::exception& e) {
    report(e.what(), "internal error");
    return clrt::kExitInternalError;
  }
  return clrt::kExitOk;
}
