// cmd_generate.cpp - `clrt generate -o SCENE.json`: a random-sphere scene of
// any size (scene/random_scene.hpp), for benchmarks and tests.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>

#include "app/options.hpp"
#include "scene/random_scene.hpp"
#include "scene/scene_json.hpp"
#include "util/error.hpp"
#include "util/output_file.hpp"

namespace clrt {

void add_generate_command(CLI::App& app) {
  auto settings = std::make_shared<RandomSceneSettings>();
  auto out = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("generate", "Write a scene of N random spheres above the book's floor (JSON)");
  cmd->add_option("--spheres", settings->count, "Number of random spheres")
      ->check(CLI::Range(size_t(0), kMaxGeneratedSpheres))
      ->capture_default_str();
  cmd->add_option("--seed", settings->seed, "Seed of the generator: the same seed, the same scene")
      ->capture_default_str();
  cmd->add_option("--fill", settings->fill, "Fraction of the volume the spheres fill: the density at every count")
      ->check(CLI::Range(1e-6, 1.0))
      ->capture_default_str();
  cmd->add_option("-o,--output", *out, "Scene file to write ('-' = standard output)")->required();
  cmd->callback([settings, out] {
    check_writable(*out, "scene");  // fail before the work
    write_text_atomic(*out, scene_to_json(random_scene(*settings), JsonStyle::Compact) + "\n", "scene");
  });
}

}  // namespace clrt
