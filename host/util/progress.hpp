// progress.hpp - progress on a terminal: a one-line bar with elapsed time and
// an ETA, redrawn in place on stderr (never stdout), and a note for one long
// step ("building kernel for DEVICE... 2.1 s"). The layers that measure only
// call a ProgressFn they were given (or open a SlowStep); this file draws, and
// only when progress_enabled(): stderr is a terminal (or CLRT_PROGRESS=always)
// and --quiet was not given.
#pragma once
#include <chrono>
#include <functional>
#include <memory>
#include <ostream>
#include <string>

namespace clrt {

// Called with the steps done so far and the total; `what` names the step
// about to run ("done" once done == total).
using ProgressFn = std::function<void(int done, int total, const std::string& what)>;
// Asked between steps whether to stop (true: stop; util/error.hpp's
// Cancelled says so to the caller). Safe to call from several threads.
using CancelFn = std::function<bool()>;

// --quiet: no progress and no informational lines (errors and warnings stay).
void set_quiet(bool quiet);
bool quiet();

// Whether anything is drawn: not --quiet, and $CLRT_PROGRESS is "always", or
// it is not "never" and stderr is a terminal.
bool progress_enabled();

// "0:07", "1:02", "1:02:03" (whole seconds, rounded down).
std::string format_duration(double seconds);

// The bar's text without the carriage return: "[#####     ] 2/4 0:03 (ETA 0:03)
// what", the ETA from the fraction done (none before the first step, none at
// the end); `what` cut to 28 characters so the line fits 80 columns.
std::string progress_text(int done, int total, const std::string& what, double elapsed_s, int width = 20);

class ProgressBar {
 public:
  // `to`: where the bar is drawn. The clock starts at the first show().
  // `delay_s`: nothing is drawn before this much time has passed (fast
  // commands stay silent); `interval_s`: at most
  // one redraw per interval (the first and the last always).
  explicit ProgressBar(std::ostream& to, int width = 20, double delay_s = 0, double interval_s = 0.1);
  // Ends a line left unfinished (an exception) with a newline.
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // Redraws the bar in place ("\r" + text, padded over a longer previous
  // line); done == total draws the last line and ends it with a newline.
  // Safe from several threads.
  void show(int done, int total, const std::string& what);

  struct Line;  // (progress.cpp)

 private:
  std::shared_ptr<Line> line_;
  int width_;
  double delay_s_, interval_s_;
  std::chrono::steady_clock::time_point start_, last_;
  bool started_ = false, drawn_ = false;
};

// A bar on stderr when progress_enabled() (drawn from 0.5 s on; at once with
// CLRT_PROGRESS=always), else an empty function: what app/ hands to the
// measuring layers.
ProgressFn stderr_progress();

// Erases the progress line on stderr, if one is drawn, so a message can
// follow; the bar redraws at its next step. app/'s log sink calls it.
void clear_progress_line();

// One long step without steps of its own (a cold kernel build): when
// progress_enabled() and it lasts more than `delay_s`, a line on stderr
// "WHAT... 2.1 s" counting up, ended by "WHAT: 3.4 s" on destruction. Steps
// open at once (devices building in parallel) share the line.
class SlowStep {
 public:
  explicit SlowStep(std::string what, double delay_s = 1.0);
  ~SlowStep();
  SlowStep(const SlowStep&) = delete;
  SlowStep& operator=(const SlowStep&) = delete;

  struct State;  // (progress.cpp)

 private:
  std::shared_ptr<State> state_;
};

}  // namespace clrt
