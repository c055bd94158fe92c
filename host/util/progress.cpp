// progress.cpp - drawing the progress bar and the slow-step line.
#include "util/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <mutex>
#include <thread>
#include <vector>

namespace clrt {

// The line a bar or a step draws on: what is on it now (its length), so a
// shorter text is padded over a longer one and the line can be erased.
struct ProgressBar::Line {
  std::ostream* to;
  size_t len = 0;
  std::mutex mutex;

  explicit Line(std::ostream& o) : to(&o) {}
  void draw(const std::string& text) {  // with `mutex` held
    *to << '\r' << text;
    if (len > text.size()) *to << std::string(len - text.size(), ' ');
    len = std::max(len, text.size());
    to->flush();
  }
  void end(const std::string& text) {
    draw(text);
    *to << '\n';
    to->flush();
    len = 0;
  }
  void clear() {
    if (!len) return;
    *to << '\r' << std::string(len, ' ') << '\r';
    to->flush();
    len = 0;
  }
};

namespace {

using Clock = std::chrono::steady_clock;
constexpr size_t kLabelWidth = 28;
std::atomic<bool> g_quiet{false};

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// The one line on stderr that bars and steps share.
std::shared_ptr<ProgressBar::Line> stderr_line() {
  static auto line = std::make_shared<ProgressBar::Line>(std::cerr);
  return line;
}

// The steps open now, with the line's mutex held.
std::vector<SlowStep::State*>& open_steps() {
  static std::vector<SlowStep::State*> steps;
  return steps;
}

}  // namespace

void set_quiet(bool q) {
  g_quiet = q;
}

bool quiet() {
  return g_quiet;
}

bool progress_enabled() {
  if (g_quiet) return false;
  const char* mode = std::getenv("CLRT_PROGRESS");
  if (mode && std::strcmp(mode, "always") == 0) return true;
  if (mode && std::strcmp(mode, "never") == 0) return false;
  return isatty(STDERR_FILENO) == 1;
}

std::string format_duration(double seconds) {
  const long long s = seconds > 0 ? static_cast<long long>(seconds) : 0;
  char buf[48];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%lld:%02lld", s / 60, s % 60);
  return buf;
}

std::string progress_text(int done, int total, const std::string& what, double elapsed_s, int width) {
  const int filled = total > 0 ? std::clamp(done, 0, total) * width / total : width;
  std::string out = "[" + std::string(filled, '#') + std::string(width - filled, ' ') + "] " + std::to_string(done) +
                    "/" + std::to_string(total) + " " + format_duration(elapsed_s);
  if (done > 0 && done < total) out += " (ETA " + format_duration(elapsed_s * (total - done) / done) + ")";
  return out + " " + what.substr(0, kLabelWidth);
}

ProgressBar::ProgressBar(std::ostream& to, int width, double delay_s, double interval_s)
    : line_(&to == &std::cerr ? stderr_line() : std::make_shared<Line>(to)),
      width_(width),
      delay_s_(delay_s),
      interval_s_(interval_s),
      start_(),
      last_() {}

ProgressBar::~ProgressBar() {
  std::lock_guard<std::mutex> lock(line_->mutex);
  if (drawn_ && line_->len) {
    *line_->to << '\n';
    line_->to->flush();
    line_->len = 0;
  }
}

void ProgressBar::show(int done, int total, const std::string& what) {
  std::lock_guard<std::mutex> lock(line_->mutex);
  if (!started_) start_ = Clock::now(), started_ = true;
  const double elapsed = seconds_since(start_);
  const bool last = done >= total;
  if (last) {
    if (drawn_ || elapsed >= delay_s_) line_->end(progress_text(done, total, what, elapsed, width_));
    drawn_ = false;
    return;
  }
  if (elapsed < delay_s_) return;
  if (drawn_ && line_->len && seconds_since(last_) < interval_s_) return;
  line_->draw(progress_text(done, total, what, elapsed, width_));
  drawn_ = true;
  last_ = Clock::now();
}

ProgressFn stderr_progress() {
  if (!progress_enabled()) return {};
  // CLRT_PROGRESS=always (tests, recordings): from the first step on.
  const char* mode = std::getenv("CLRT_PROGRESS");
  const bool always = mode && std::strcmp(mode, "always") == 0;
  auto bar = std::make_shared<ProgressBar>(std::cerr, 20, /*delay_s=*/always ? 0.0 : 0.5);
  return [bar](int done, int total, const std::string& what) { bar->show(done, total, what); };
}

void clear_progress_line() {
  auto line = stderr_line();
  std::lock_guard<std::mutex> lock(line->mutex);
  line->clear();
}

struct SlowStep::State {
  std::string what;
  Clock::time_point start = Clock::now();
  bool shown = false;  // (the line's mutex)
  bool stop = false;   // (`mutex`)
  std::mutex mutex;
  std::condition_variable wake;
  std::thread ticker;

  std::string text(const char* sep) const {
    char t[32];
    std::snprintf(t, sizeof t, "%.1f s", seconds_since(start));
    return what + sep + t;
  }
};

namespace {

// Every shown step on the line, with its mutex held.
void draw_steps(ProgressBar::Line& line) {
  std::string text;
  for (const SlowStep::State* s : open_steps())
    if (s->shown) text += (text.empty() ? "" : "; ") + s->text("... ");
  if (!text.empty()) line.draw(text);
}

}  // namespace

SlowStep::SlowStep(std::string what, double delay_s) {
  if (!progress_enabled()) return;
  state_ = std::make_shared<State>();
  state_->what = std::move(what);
  {
    auto line = stderr_line();
    std::lock_guard<std::mutex> lock(line->mutex);
    open_steps().push_back(state_.get());
  }
  State* s = state_.get();
  s->ticker = std::thread([s, delay_s] {
    std::unique_lock<std::mutex> lock(s->mutex);
    if (s->wake.wait_for(lock, std::chrono::duration<double>(delay_s), [s] { return s->stop; })) return;
    do {
      lock.unlock();
      {
        auto line = stderr_line();
        std::lock_guard<std::mutex> draw(line->mutex);
        s->shown = true;
        draw_steps(*line);
      }
      lock.lock();
    } while (!s->wake.wait_for(lock, std::chrono::milliseconds(200), [s] { return s->stop; }));
  });
}

SlowStep::~SlowStep() {
  if (!state_) return;
  {
    std::lock_guard<std::mutex> lock(state_->mutex);
    state_->stop = true;
  }
  state_->wake.notify_all();
  state_->ticker.join();
  auto line = stderr_line();
  std::lock_guard<std::mutex> lock(line->mutex);
  auto& steps = open_steps();
  steps.erase(std::remove(steps.begin(), steps.end(), state_.get()), steps.end());
  if (state_->shown) {
    line->end(state_->text(": "));
    draw_steps(*line);  // the others, still counting
  }
}

}  // namespace clrt
