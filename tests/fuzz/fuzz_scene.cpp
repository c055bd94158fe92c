// fuzz_scene.cpp - libFuzzer target for the scene parser: any input must
// either parse or raise a one-line UserError naming the input; a scene that
// parses must survive scene_to_json -> parse_scene unchanged.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "scene/scene_json.hpp"
#include "util/error.hpp"

namespace {

[[noreturn]] void die(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz_scene: %s: %s\n", what, detail.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  clrt::Scene scene;
  try {
    scene = clrt::parse_scene(text, "fuzz.json");
  } catch (const clrt::UserError& e) {
    const std::string msg = e.what();
    if (msg.rfind("fuzz.json: ", 0) != 0) die("error does not name the file", msg);
    if (msg.find('\n') != std::string::npos) die("error is not one line", msg);
    return 0;
  }
  // Any other exception escapes and libFuzzer reports it as a crash.
  const std::string once = clrt::scene_to_json(scene);
  clrt::Scene again;
  try {
    again = clrt::parse_scene(once, "roundtrip.json");
  } catch (const clrt::UserError& e) {
    die("serialized scene does not parse", e.what());
  }
  if (clrt::scene_to_json(again) != once) die("round trip changed the scene", once);
  return 0;
}
