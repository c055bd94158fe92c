// main.cpp - the clrt command line: one subcommand per cmd_<name>.cpp.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/options.hpp"
#include "cl/cl.hpp"
#include "dist/communicator.hpp"
#include "dist/job.hpp"
#include "util/doing.hpp"
#include "util/edit_distance.hpp"
#include "util/error.hpp"
#include "util/log.hpp"
#include "util/output_file.hpp"
#include "util/progress.hpp"

// The version and build facts, from CMakeLists.txt (project(VERSION) and the
// configuration), the one place they are written.
#ifndef CLRT_VERSION
#define CLRT_VERSION "unknown"
#endif
#ifndef CLRT_BUILD_INFO
#define CLRT_BUILD_INFO "unknown"
#endif

namespace {

// Every error is one line on stderr, whatever a library put in its message.
// In an MPI job, rank 0 prints the job's errors: every rank parses the same
// command line (a `symmetric` error: the others stay silent), and a rank's
// failure in its share of the work travels to rank 0. Another rank prints
// only an error of its own outside that (`symmetric` false), with its rank.
void report(std::string msg, const char* what = "error", bool symmetric = true) {
  const clrt::dist::Communicator& world = clrt::dist::world();
  if (world.rank() != 0 && symmetric) return;
  for (auto& c : msg)
    if (c == '\n' || c == '\r') c = ' ';
  if (world.rank() != 0) msg = clrt::dist::rank_label(world.rank(), world.host()) + ": " + msg;
  clrt::clear_progress_line();
  std::cerr << "clrt: " << what << ": " << msg << "\n";
}

// The exit status of a rank other than 0 after an error rank 0 reports: 0,
// so that the job's status is rank 0's and mpirun does not end rank 0 (with
// SIGTERM, as it does when a rank exits with another status) before rank 0
// has printed the error and removed its temp files.
int status_of_symmetric(int status) {
  return clrt::dist::world().rank() != 0 || clrt::dist::environment_rank() != 0 ? clrt::kExitOk : status;
}

// The subcommands that spread their work over the ranks of an MPI job (and
// `cache warm`, which every rank runs for its own node); the others refuse to
// run with more than one rank (each rank would do all of it). `next`: the
// word after the command that is not an option.
bool runs_across_ranks(const std::string& command, const std::string& next) {
  return command == "render" || command == "sweep" || command == "accuracy" || (command == "cache" && next == "warm");
}

// An MPI job's checks before the command line is read: a clrt built without
// MPI refuses an mpirun launch (each process would render the whole job and
// write the same files); a subcommand that does not distribute refuses more
// than one rank.
void check_launch(int argc, char** argv) {
  namespace dist = clrt::dist;
  if (dist::launched_by_mpi() && !dist::built_with_mpi())
    throw clrt::UserError("launched by mpirun, but this clrt was built without MPI (configure with -DCLRT_MPI=ON)");
  if (!dist::world().distributed()) return;
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.empty() || word[0] == '-') continue;
    std::string next;
    for (int j = i + 1; j < argc && next.empty(); ++j)
      if (argv[j][0] != '-') next = argv[j];
    if (!runs_across_ranks(word, next))
      throw clrt::UserError("'" + word + "' does not run across MPI ranks (" + std::to_string(dist::world().size()) +
                            " here): run it without mpirun; render, sweep, accuracy and cache warm do");
    return;
  }
}

std::string command_list(const CLI::App& app) {
  std::string names;
  for (const CLI::App* sub : app.get_subcommands({})) names += (names.empty() ? "" : ", ") + sub->get_name();
  return names;
}

// A word where a subcommand belongs that names none: one error, with the
// nearest name when it looks like a typo ("rendr" -> "render"). Walks the
// commands that have subcommands (clrt, clrt cache); stops at the first
// option or at a command that takes its own arguments. Without the
// subcommand (`clrt`, `clrt cache`): that command's usage on stdout, then
// the error.
void check_command_names(CLI::App& app, int argc, char** argv) {
  CLI::App* level = &app;
  std::string parent, path;  // "clrt", "cache" at `clrt cache`
  for (int i = 1;; ++i) {
    const auto subs = level->get_subcommands({});
    if (subs.empty()) return;
    if (i == argc) {
      // help(PARENT) shows a subcommand's usage as "PARENT NAME".
      std::cout << (level == &app ? app.help() : level->help(parent)) << std::flush;
      throw clrt::UserError("a " + (path.empty() ? std::string() : path + " ") +
                            "subcommand is required (one of: " + command_list(*level) + ")");
    }
    const std::string word = argv[i];
    if (level == &app && (word == "--quiet" || word == "-q")) continue;  // clrt --quiet COMMAND
    if (!word.empty() && word[0] == '-' && word != "--" && level == &app &&
        !app.get_option_no_throw(word.substr(0, word.find('='))))
      throw clrt::UserError("unknown option '" + word + "' (before the subcommand: --help or --version)");
    if (word.empty() || word[0] == '-') return;
    std::vector<std::string> names;
    CLI::App* next = nullptr;
    for (CLI::App* sub : subs) {
      names.push_back(sub->get_name());
      if (sub->check_name(word)) next = sub;
    }
    if (!next) {
      const std::string near = clrt::closest_match(word, names);
      const std::string what = "unknown " + (path.empty() ? std::string() : path + " ") + "command '" + word + "'";
      if (!near.empty()) throw clrt::UserError(what + "; did you mean '" + near + "'?");
      throw clrt::UserError(what + " (expected one of: " + command_list(*level) + ")");
    }
    parent = level == &app ? "clrt" : parent + " " + level->get_name();
    path += (path.empty() ? "" : " ") + next->get_name();
    level = next;
  }
}

// -q/--quiet on clrt and on every (sub)command, so it goes anywhere on the line.
void add_quiet_flag(CLI::App* cmd) {
  cmd->add_flag_callback(
      "-q,--quiet", [] { clrt::set_quiet(true); },
      "No progress and no informational lines on stderr (errors and warnings stay)");
  for (CLI::App* sub : cmd->get_subcommands({})) add_quiet_flag(sub);
}

}  // namespace

int main(int argc, char** argv) {
  // A rank whose mpirun is gone stops at once (dist/communicator.hpp).
  clrt::dist::watch_launcher();
  // Named "clrt" whatever the path it runs from (usage lines, the man page).
  CLI::App app{"clrt - OpenCL Whitted ray tracer (Computer Graphics from Scratch, ch. 2-5) with a double reference",
               "clrt"};
  app.set_version_flag("--version", std::string("clrt ") + CLRT_VERSION + "\n" + CLRT_BUILD_INFO,
                       "Print the version and how this binary was built, then exit");
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
  clrt::add_cache_command(app);
  clrt::add_validate_command(app);
  add_quiet_flag(&app);
  clrt::add_number_checks(&app);
  // Messages of the layers below: none of --verbose's with --quiet, and the
  // progress line erased before any other.
  clrt::set_log_sink([](clrt::LogLevel level, const std::string& message) {
    if (level == clrt::LogLevel::Info && clrt::quiet()) return;
    clrt::clear_progress_line();
    clrt::write_log_to_stderr(level, message);
  });
  clrt::install_signal_cleanup();
  // MPI, when launched by mpirun (dist/communicator.hpp); finalized when
  // main returns.
  std::unique_ptr<clrt::dist::Session> mpi;
  try {
    mpi = std::make_unique<clrt::dist::Session>(argc, argv);
  } catch (const std::exception& e) {
    if (clrt::dist::environment_rank() == 0) std::cerr << "clrt: error: " << e.what() << "\n";
    return clrt::kExitBadInput;
  }
  if (clrt::dist::world().distributed())
    clrt::set_signal_report(clrt::dist::world().rank() == 0,
                            " (mpirun ends every rank when one fails or the job is cancelled)");
  try {
    if (clrt::dist::launched_by_mpi() && !clrt::dist::built_with_mpi() && clrt::dist::environment_rank() != 0)
      return clrt::kExitOk;  // rank 0 says why (check_launch) and fails the job
    check_launch(argc, argv);
    check_command_names(app, argc, argv);
    app.parse(argc, argv);
    // Results printed to stdout (tables, JSON) must have reached it: a full
    // disk or closed pipe is an error, not a silent truncation.
    if (std::fflush(stdout) != 0 || std::ferror(stdout))
      throw clrt::UserError(std::string("cannot write standard output: ") + std::strerror(errno));
  } catch (const CLI::CallForHelp& e) {
    return clrt::dist::world().rank() == 0 ? app.exit(e) : clrt::kExitOk;  // (one copy of the help)
  } catch (const CLI::CallForAllHelp& e) {
    return clrt::dist::world().rank() == 0 ? app.exit(e) : clrt::kExitOk;
  } catch (const CLI::CallForVersion& e) {
    return clrt::dist::world().rank() == 0 ? app.exit(e) : clrt::kExitOk;
  } catch (const clrt::dist::JobAborted&) {
    return clrt::kExitOk;  // stopped by rank 0, which prints the error and fails the job
  } catch (const CLI::ParseError& e) {
    report(e.what());
    return status_of_symmetric(clrt::kExitBadInput);
  } catch (const clrt::ProblemsReported&) {
    return status_of_symmetric(clrt::kExitBadInput);  // (printed by the command, one line a problem)
  } catch (const clrt::CheckFailure& e) {
    report(e.what(), "check failed");
    return status_of_symmetric(clrt::kExitCheckFailed);
  } catch (const clrt::UserError& e) {
    report(e.what());
    return status_of_symmetric(clrt::kExitBadInput);
  } catch (const clrt::DeviceError& e) {
    report(e.what(), "error", /*symmetric=*/false);
    return clrt::kExitBadInput;
  } catch (const cl::Error& e) {
    report(clrt::describe(e), "error", false);
    return clrt::kExitBadInput;
  } catch (const std::bad_alloc&) {
    // Bad input too: a scene or size that needs more memory than there is.
    const std::string step = clrt::failed_step();
    report("out of memory" + (step.empty() ? std::string() : " while " + step), "error", false);
    return clrt::kExitBadInput;
  } catch (const std::exception& e) {
    report(e.what(), "internal error", false);
    return clrt::kExitInternalError;
  }
  return clrt::kExitOk;
}
