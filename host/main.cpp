// main.cpp - the clrt command line: one subcommand per cmd_<name>.cpp.
#include <CLI/CLI.hpp>
#include <iostream>

#include "cl.hpp"
#include "cli_common.hpp"
#include "error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"clrt - OpenCL Whitted ray tracer (Computer Graphics from Scratch, ch. 2-5) with a double reference"};
  app.require_subcommand(1);
  clrt::add_devices_command(app);
  clrt::add_render_command(app);
  clrt::add_compare_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "clrt: error: " << e.what() << "\n";
    return 2;
  } catch (const clrt::UserError& e) {
    std::cerr << "clrt: error: " << e.what() << "\n";
    return 2;
  } catch (const clrt::DeviceError& e) {
    std::cerr << "clrt: error: " << e.what() << "\n";
    return 2;
  } catch (const cl::Error& e) {
    std::cerr << "clrt: error: " << clrt::describe(e) << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "clrt: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
