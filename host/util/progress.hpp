// progress.hpp - a one-line text progress bar for a terminal: redrawn in
// place with a carriage return, finished with a newline when done == total.
#pragma once
#include <ostream>
#include <string>

namespace clrt {

class ProgressBar {
 public:
  // `to`: where the bar is drawn, chosen by the caller (app/: a terminal).
  explicit ProgressBar(std::ostream& to, int width = 30) : to_(to), width_(width) {}

  // Redraws the bar for `done` of `total` steps, `what` being the current one.
  void show(int done, int total, const std::string& what);

  // What show() writes: "\r[####      ] 2/6 what...", the label padded or cut
  // to 40 characters (so a shorter label overwrites a longer one), and a
  // newline once done == total.
  std::string text(int done, int total, const std::string& what) const;

 private:
  std::ostream& to_;
  int width_;
};

}  // namespace clrt
