// test_kernel_source.cpp - kernel text: the embedded files, #include
// expansion and --kernel-dir. Host only: no OpenCL device is needed (the
// [opencl] tests build what this expands).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cl/kernel_source.hpp"
#include "cli_run.hpp"
#include "test_util.hpp"
#include "util/error.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_kernel_source {

using namespace clrt;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Lines that are `#include "..."` directives (what the expansion replaces).
size_t quoted_includes(const std::string& text) {
  std::istringstream in(text);
  size_t n = 0;
  for (std::string line; std::getline(in, line);) n += line.rfind("#include \"", 0) == 0;
  return n;
}

const std::string kParts[] = {"clrt_layout.h",   "clrt_kernel_args.h", "clrt_config.h", "clrt_lanes.h",
                              "clrt_math.h",     "clrt_scene.h",       "clrt_sphere.h", "clrt_flat.h",
                              "clrt_query.h",    "clrt_query_all.h",   "clrt_bvh.h",    "clrt_shade.h",
                              "clrt_ray_tree.h", "clrt_camera.h",      "clrt_block.h",  "clrt_subsample.h",
                              "clrt_samples.h",  "clrt_film.h",        "clrt_layers.h", "clrt_device_status.h"};

}  // namespace

TEST_CASE("every embedded kernel file expands, with no include left", "[kernel_source]") {
  REQUIRE_FALSE(embedded_kernel_files().empty());
  for (const auto& file : embedded_kernel_files()) {
    INFO(file.name);
    const std::string text = load_kernel_source(file.name);
    CHECK_THAT(text, StartsWith("#line 1 \"" + std::string(file.name) + "\"\n"));
    CHECK(quoted_includes(text) == 0);
    // A file without includes comes through unchanged after its #line.
    if (quoted_includes(file.text) == 0) CHECK(text == "#line 1 \"" + std::string(file.name) + "\"\n" + file.text);
  }
}

TEST_CASE("the embedded files are the source tree's kernels/", "[kernel_source]") {
  size_t on_disk = 0;
  for (const auto& e : std::filesystem::directory_iterator(clrt_test::source_path("kernels"))) {
    const std::string ext = e.path().extension().string();
    if (ext != ".cl" && ext != ".h") continue;
    ++on_disk;
    const std::string name = e.path().filename().string();
    INFO(name);
    bool found = false;
    for (const auto& file : embedded_kernel_files())
      if (name == file.name) found = file.text == clrt_test::slurp(e.path().string());
    CHECK(found);
  }
  CHECK(on_disk == embedded_kernel_files().size());
}

TEST_CASE("trace.cl is its parts, each once", "[kernel_source]") {
  const std::string text = load_kernel_source("trace.cl");
  for (const std::string& part : kParts) {
    INFO(part);
    CHECK(count(text, "#line 1 \"" + part + "\"\n") == 1);
  }
  for (const char* kernel : {"render", "camera_hits"})
    CHECK(count(text, std::string("__kernel void ") + kernel + "(") == 1);
  // The layout probe sees the same shared header.
  CHECK(count(load_kernel_source("layout_probe.cl"), "#line 1 \"clrt_layout.h\"\n") == 1);
}

TEST_CASE("nested includes expand in place, once each, between #line directives", "[kernel_source]") {
  clrt_test::TempDir dir;
  dir.write("main.cl", "a\n#include \"b.h\"\nc\n  #  include \"d.h\"  // again\n#include <stdio.h>\ne\n");
  dir.write("b.h", "#include \"d.h\"\nb\n");
  dir.write("d.h", "d\n");
  CHECK(load_kernel_source("main.cl", dir.path().string()) ==
        "#line 1 \"main.cl\"\n"
        "a\n"
        "#line 1 \"b.h\"\n"
        "#line 1 \"d.h\"\n"
        "d\n"
        "#line 2 \"b.h\"\n"
        "b\n"
        "#line 3 \"main.cl\"\n"
        "c\n"
        "#line 5 \"main.cl\"\n"  // d.h was expanded already
        "#include <stdio.h>\n"   // left to the compiler (clrt_layout.h's host branch has one)
        "e\n");
}

TEST_CASE("a missing kernel file is a clear error", "[kernel_source]") {
  clrt_test::TempDir dir;
  const std::string d = dir.path().string();
  SECTION("the main file, embedded or in --kernel-dir") {
    CHECK_THROWS_WITH(load_kernel_source("no_such.cl"), "kernel file \"no_such.cl\" is not embedded in this binary");
    CHECK_THROWS_WITH(load_kernel_source("trace.cl", d), d + "/trace.cl: cannot open kernel file (--kernel-dir)");
  }
  SECTION("an include names the file that includes it") {
    dir.write("main.cl", "x\n\n#include \"gone.h\"\n");
    CHECK_THROWS_WITH(load_kernel_source("main.cl", d),
                      d + "/gone.h: cannot open kernel file (--kernel-dir), included from main.cl line 3");
    dir.write("inner.h", "#include \"gone.h\"\n");
    dir.write("outer.cl", "#include \"inner.h\"\n");
    CHECK_THROWS_WITH(load_kernel_source("outer.cl", d),
                      Contains("gone.h") && Contains("included from inner.h line 1"));
    CHECK_THROWS_AS(load_kernel_source("outer.cl", d), UserError);
  }
  SECTION("an unreadable include line") {
    dir.write("main.cl", "#include \"unterminated\n");
    CHECK_THROWS_WITH(load_kernel_source("main.cl", d), StartsWith("main.cl line 1: cannot read this #include"));
    dir.write("main.cl", "#include NAME\n");
    CHECK_THROWS_AS(load_kernel_source("main.cl", d), UserError);
  }
}

TEST_CASE("a kernel directory copied from kernels/ expands like the embedded files, edits show", "[kernel_source]") {
  clrt_test::TempDir dir;
  const std::string copy = dir / "kernels";
  std::filesystem::copy(clrt_test::source_path("kernels"), copy, std::filesystem::copy_options::recursive);
  for (const auto& file : embedded_kernel_files()) {
    INFO(file.name);
    CHECK(load_kernel_source(file.name, copy) == load_kernel_source(file.name));
  }
  // An edit to a nested part reaches the expanded trace.cl (and so the
  // program cache key, which hashes the expanded text).
  std::ofstream(copy + "/clrt_math.h", std::ios::app) << "\n/* edited */\n";
  const std::string edited = load_kernel_source("trace.cl", copy);
  CHECK(edited != load_kernel_source("trace.cl"));
  CHECK(count(edited, "/* edited */") == 1);
}

}  // namespace test_kernel_source
