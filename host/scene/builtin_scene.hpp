// builtin_scene.hpp - the book's demo scene compiled into the binary, for
// self-tests that must work wherever clrt runs (`clrt devices --check`).
#pragma once
#include "scene/scene.hpp"

namespace clrt {
Scene builtin_demo_scene();
}
