// frame_pattern.hpp - output names of a run of frames: `frame_####.png` is
// frame_0000.png, frame_0001.png, ... (the frame's index, zero-padded to the
// run's length, with more digits where the index needs them: frame_##.png
// gives frame_99.png, frame_100.png).
#pragma once
#include <string>
#include <vector>

namespace clrt {

// The run of '#' in OUT's file name (after its last '/'; a '#' in a
// directory name is an ordinary character).
struct FramePattern {
  std::string prefix, suffix;  // OUT around the run
  int digits = 0;              // the run's length; 0 = OUT has no run
  bool has_run() const { return digits > 0; }
};

// UserError naming `out` when its file name holds more than one run of '#'.
FramePattern parse_frame_pattern(const std::string& out);
// Frame `index`'s name (`out` itself without a run).
std::string frame_path(const FramePattern& p, int index);

// The names of `frames` frames (>= 1) written to `out`: with a run of '#',
// frame_path() of 0, 1, ...; without one, `out` itself for one frame, and a
// UserError naming `out` for several.
std::vector<std::string> frame_paths(const std::string& out, int frames);

}  // namespace clrt
