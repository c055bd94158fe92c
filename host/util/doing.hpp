// doing.hpp - what the process is doing, for the one line that reports
// running out of memory. A std::bad_alloc says nothing of what did not fit;
// the steps that can take much memory (loading a scene, reading a mesh,
// building a hierarchy, allocating the frame's buffers) name themselves in
// a Doing for their scope, and main() names the innermost one that an
// exception left: "clrt: error: out of memory while reading the mesh file
// m.obj".
#pragma once
#include <exception>
#include <string>

namespace clrt {

class Doing {
 public:
  explicit Doing(std::string what);
  ~Doing();
  Doing(const Doing&) = delete;
  Doing& operator=(const Doing&) = delete;

 private:
  std::string what_;
  Doing* outer_;
  int exceptions_;
};

// The innermost step an exception has left on this thread since the last
// step began ("" when none): what main() names for a std::bad_alloc.
std::string failed_step();

}  // namespace clrt
