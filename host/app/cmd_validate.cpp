// cmd_validate.cpp - `clrt validate SCENE...`: every problem of each scene
// file, one `clrt: error: FILE: ...` line each (the texts the reader stops
// at); `clrt validate --schema`: the JSON Schema of scene files.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>

#include "app/options.hpp"
#include "scene/scene_json.hpp"
#include "scene/scene_schema.hpp"
#include "util/error.hpp"
#include "util/progress.hpp"

namespace clrt {

void add_validate_command(CLI::App& app) {
  struct Opts {
    std::vector<std::string> scenes, overrides;
    bool schema = false;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = app.add_subcommand(
      "validate", "Check scene files and print every problem, one line each (exit status 2 if any); nothing is rendered");
  cmd->add_option("scenes", o->scenes, "Scene files (JSON)");
  add_override_option(cmd, o->overrides);
  cmd->add_flag("--schema", o->schema, "Print the JSON Schema (draft 2020-12) of scene files instead");
  cmd->callback([o] {
    if (o->schema && !o->scenes.empty()) throw UserError("--schema prints the schema: give no SCENE with it");
    if (o->schema) {
      std::fputs(scene_schema_text().c_str(), stdout);
      return;
    }
    if (o->scenes.empty()) throw UserError("a SCENE is required (or --schema)");
    const SceneOverrides overrides = parse_overrides(o->overrides);
    size_t problems = 0;
    for (const std::string& path : o->scenes) {
      const size_t found = validate_scene(path, [](std::string message) {
        for (auto& c : message)  // one line each, whatever a library put in it
          if (c == '\n' || c == '\r') c = ' ';
        clear_progress_line();
        std::fprintf(stderr, "clrt: error: %s\n", message.c_str());
      }, {}, overrides);
      if (found == 0) std::printf("%s: valid\n", path.c_str());
      problems += found;
    }
    if (problems > 0) throw ProblemsReported(std::to_string(problems) + " problem(s)");
  });
}

}  // namespace clrt
