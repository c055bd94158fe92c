// progress.cpp - drawing the progress bar.
#include "util/progress.hpp"

namespace clrt {
namespace {

constexpr size_t kLabelWidth = 40;

}  // namespace

std::string ProgressBar::text(int done, int total, const std::string& what) const {
  const int filled = total ? done * width_ / total : width_;
  std::string label = what.substr(0, kLabelWidth);
  label.resize(kLabelWidth, ' ');
  std::string out = "\r[" + std::string(filled, '#') + std::string(width_ - filled, ' ') + "] " + std::to_string(done) +
                    "/" + std::to_string(total) + " " + label;
  if (done == total) out += "\n";
  return out;
}

void ProgressBar::show(int done, int total, const std::string& what) {
  to_ << text(done, total, what);
  to_.flush();
}

}  // namespace clrt
