// test_image_io.cpp - the imaging module (OpenImageIO behind dlopen): loaded
// only by the commands that read or write an image, found beside the binary,
// and a clear error when it is missing or is not a module of this build.
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "cli_run.hpp"
#include "image/image_file.hpp"
#include "image/image_io.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_image_io {

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using clrt_test::run_clrt;
using clrt_test::RunResult;
using clrt_test::TempDir;

namespace {

// Whether the dynamic loader's trace (LD_DEBUG=files, glibc) shows the
// process loading OpenImageIO or the module. Honest and needs nothing from
// clrt: the loader itself reports every file it maps.
bool loads_imaging(const RunResult& r) {
  return r.err.find("libOpenImageIO") != std::string::npos || r.err.find("clrt_imageio") != std::string::npos;
}

std::string demo_scene() {
  return std::string(CLRT_SOURCE_DIR) + "/scenes/cgfs-demo.json";
}

}  // namespace

TEST_CASE("commands that write no image do not load OpenImageIO", "[cli][imageio]") {
  const RunResult help = run_clrt({"--help"}, "LD_DEBUG=files");
  INFO("stderr: " << help.err.substr(0, 2000));
  CHECK(help.status == 0);
  CHECK(help.err.find("file=libstdc++") != std::string::npos);  // the trace works here
  CHECK_FALSE(loads_imaging(help));
  // (Whatever OpenCL drivers there are, or none: the trace is what counts.)
  const RunResult devices = run_clrt({"devices"}, "LD_DEBUG=files");
  CHECK_FALSE(loads_imaging(devices));
  // The same trace does see it where an image is written.
  TempDir dir;
  const RunResult render = run_clrt(
      {"render", demo_scene(), "--engine", "reference", "--width", "8", "--height", "8", "-o", dir / "out.png"},
      "LD_DEBUG=files");
  CHECK(render.status == 0);
  CHECK(loads_imaging(render));
}

TEST_CASE("a missing imaging module is one error line before the work", "[cli][imageio]") {
  TempDir dir;
  const RunResult r =
      run_clrt({"render", demo_scene(), "--engine", "reference", "--width", "8", "--height", "8", "-o", dir / "a.png"},
               "CLRT_IMAGEIO_MODULE=" + clrt_test::shell_quote(dir / "none.so"));
  INFO("stderr: " << r.err);
  CHECK(r.status == 2);
  CHECK(r.one_line_error());
  CHECK_THAT(r.err, StartsWith("clrt: error: the imaging module clrt_imageio.so"));
  CHECK_THAT(r.err, Contains("none.so"));
  CHECK(dir.entries().empty());
}

TEST_CASE("a file that is not the imaging module is one error line, not a crash", "[cli][imageio]") {
  TempDir dir;
  const std::string fake = dir.write("fake.so", "not a shared object");
  for (const std::string& module : {fake, std::string("/lib/x86_64-linux-gnu/libm.so.6")}) {
    const RunResult r = run_clrt(
        {"render", demo_scene(), "--engine", "reference", "--width", "8", "--height", "8", "-o", dir / "a.png"},
        "CLRT_IMAGEIO_MODULE=" + clrt_test::shell_quote(module));
    INFO("module " << module << ", stderr: " << r.err);
    CHECK(r.status == 2);
    CHECK(r.one_line_error());
    CHECK_THAT(r.err, StartsWith("clrt: error: "));
    CHECK_THAT(r.err, Contains(module));
  }
  CHECK(dir.entries() == std::vector<std::string>{"fake.so"});
}

TEST_CASE("the module is found beside the running binary", "[imageio]") {
  // The first place looked (without CLRT_IMAGEIO_MODULE) is this test
  // binary's directory, where the build puts the module.
  const auto places = clrt::imageio::module_candidates();
  REQUIRE_FALSE(places.empty());
  CHECK(places.front() == (std::filesystem::read_symlink("/proc/self/exe").parent_path() / "clrt_imageio.so").string());
  CHECK_NOTHROW(clrt::imageio::check_module_present());
  CHECK_NOTHROW(clrt::imageio::module());
  CHECK(clrt::imageio::module_loaded());
}

TEST_CASE("a library's module is looked for relative to the library, never beside the executable", "[imageio]") {
  // (The Python module: the executable is python3, whose folder is not clrt's.)
  const std::string exe_dir = std::filesystem::read_symlink("/proc/self/exe").parent_path().string();
  clrt::imageio::set_library_location("/opt/p/lib/python3.11/dist-packages/clrt", "../../../clrt");
  CHECK(clrt::imageio::module_candidates() == std::vector<std::string>{"/opt/p/lib/clrt/clrt_imageio.so"});
  // Inside the build folder (this binary's): the build folder's module only.
  clrt::imageio::set_library_location(exe_dir + "/python/clrt", "../../../clrt");
  CHECK(clrt::imageio::module_candidates() == std::vector<std::string>{exe_dir + "/clrt_imageio.so"});
  clrt::imageio::set_library_location("", "");  // (back to the executable's places)
  CHECK(clrt::imageio::module_candidates().front() == exe_dir + "/clrt_imageio.so");
}

TEST_CASE("every format checked without OpenImageIO is one it writes", "[imageio]") {
  clrt::imageio::Module& io = clrt::imageio::module();
  for (const auto& ext : clrt::written_without_asking()) {
    INFO("." << ext);
    CHECK(io.can_write("x." + ext));
  }
  CHECK_FALSE(io.can_write("x.notaformat"));
}

}  // namespace test_image_io
