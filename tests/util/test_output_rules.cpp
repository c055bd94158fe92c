// test_output_rules.cpp - the small rules every report shares: CSV quoting
// (RFC 4180), the progress bar's text, and the log's routing to a sink.
#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

#include "util/csv.hpp"
#include "util/log.hpp"
#include "util/progress.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_output_rules {

using namespace clrt;

TEST_CASE("CSV fields are quoted only when they must be, quotes doubled", "[csv]") {
  CHECK(csv_field("") == "");
  CHECK(csv_field("pthread-Intel(R) Xeon(R) CPU") == "pthread-Intel(R) Xeon(R) CPU");
  CHECK(csv_field("scenes/cgfs-demo.json") == "scenes/cgfs-demo.json");
  CHECK(csv_field("a,b") == "\"a,b\"");
  CHECK(csv_field("say \"hi\"") == "\"say \"\"hi\"\"\"");
  CHECK(csv_field("two\nlines") == "\"two\nlines\"");
  CHECK(csv_field("cr\rhere") == "\"cr\rhere\"");
  CHECK(csv_field("\"") == "\"\"\"\"");
}

TEST_CASE("progress text: elapsed time, and an ETA from the fraction done", "[progress][util]") {
  CHECK(format_duration(0) == "0:00");
  CHECK(format_duration(-3) == "0:00");
  CHECK(format_duration(7.9) == "0:07");
  CHECK(format_duration(62) == "1:02");
  CHECK(format_duration(3723) == "1:02:03");
  // No ETA before the first step is done, nor at the end.
  CHECK(progress_text(0, 4, "depth 0", 0.2, 10) == "[          ] 0/4 0:00 depth 0");
  // 2 of 4 in 3 s: 3 s to go.
  CHECK(progress_text(2, 4, "x", 3.0, 10) == "[#####     ] 2/4 0:03 (ETA 0:03) x");
  // 1 of 4 in 20 s: 60 s to go.
  CHECK(progress_text(1, 4, "y", 20.0, 10) == "[##        ] 1/4 0:20 (ETA 1:00) y");
  CHECK(progress_text(4, 4, "done", 65.0, 10) == "[##########] 4/4 1:05 done");
  CHECK(progress_text(0, 0, "done", 0, 10) == "[##########] 0/0 0:00 done");
  // The label is cut to 28 characters, so the line fits 80 columns.
  const std::string line = progress_text(123, 456, std::string(50, 'y'), 3599, 20);
  CHECK(line == "[#####               ] 123/456 59:59 (ETA 2:42:23) " + std::string(28, 'y'));
  CHECK(line.size() < 80);
}

TEST_CASE("the progress bar redraws in place, pads over a longer line and ends with a newline", "[progress][util]") {
  std::ostringstream out;
  {
    ProgressBar bar(out, 10, /*delay_s=*/0, /*interval_s=*/0);
    bar.show(0, 2, "a longer label");
    bar.show(1, 2, "b");
    bar.show(2, 2, "done");
  }
  const std::string s = out.str();
  CHECK(s.rfind("\r[          ] 0/2 0:00 a longer label", 0) == 0);
  CHECK(s.find("\r[#####     ] 1/2 0:00 (ETA 0:00) b") != std::string::npos);
  CHECK(s.find("\r[##########] 2/2 0:00 done") != std::string::npos);
  CHECK(s.back() == '\n');
  CHECK(std::count(s.begin(), s.end(), '\n') == 1);
  // "done" is shorter than the line before: padded with blanks over it.
  CHECK(s.size() - s.rfind('\r') - 2 == std::string("[          ] 0/2 0:00 a longer label").size());

  // Throttled: at most one redraw per interval, the first and last always.
  std::ostringstream slow;
  {
    ProgressBar bar(slow, 10, 0, /*interval_s=*/60);
    for (int i = 0; i <= 5; ++i) bar.show(i, 5, "step");
  }
  const std::string t = slow.str();
  CHECK(std::count(t.begin(), t.end(), '\r') == 2);
  CHECK(t.find("] 5/5 ") != std::string::npos);

  // Not yet due (a fast command): nothing at all, not even the newline.
  std::ostringstream fast;
  {
    ProgressBar bar(fast, 10, /*delay_s=*/60);
    bar.show(0, 2, "a");
    bar.show(2, 2, "done");
  }
  CHECK(fast.str().empty());

  // Left unfinished (an exception): the line is ended for what follows.
  std::ostringstream cut;
  {
    ProgressBar bar(cut, 10, 0);
    bar.show(1, 3, "a");
  }
  CHECK(cut.str().back() == '\n');
}

namespace {
// std::cerr into a string, CLRT_PROGRESS set, for one scope.
struct CaptureStderr {
  std::ostringstream text;
  std::streambuf* old;
  explicit CaptureStderr(const char* mode) : old(std::cerr.rdbuf(text.rdbuf())) { ::setenv("CLRT_PROGRESS", mode, 1); }
  ~CaptureStderr() {
    std::cerr.rdbuf(old);
    ::unsetenv("CLRT_PROGRESS");
    set_quiet(false);
  }
};
}  // namespace

TEST_CASE("progress is drawn on a terminal or with CLRT_PROGRESS=always, never with --quiet", "[progress][util]") {
  {
    CaptureStderr err("never");
    CHECK_FALSE(progress_enabled());
    CHECK_FALSE(stderr_progress());
    SlowStep step("building kernel for X", 0);
  }
  {
    CaptureStderr err("always");
    CHECK(progress_enabled());
    ProgressFn p = stderr_progress();
    REQUIRE(p);
    p(0, 2, "first");
    clear_progress_line();  // a message can follow on a clean line
    std::cerr << "clrt: warning: w\n";
    p(2, 2, "done");
    const std::string s = err.text.str();
    CHECK(s.rfind("\r[          ", 0) == 0);
    CHECK(s.find("first" + std::string(1, '\r')) != std::string::npos);  // erased, then the warning
    CHECK(s.find("\rclrt: warning: w\n") != std::string::npos);
    CHECK(s.find("] 2/2 0:00 done\n") != std::string::npos);
  }
  {
    CaptureStderr err("always");
    set_quiet(true);
    CHECK_FALSE(progress_enabled());
    CHECK_FALSE(stderr_progress());
    SlowStep step("building kernel for X", 0);
    CHECK(err.text.str().empty());
  }
}

TEST_CASE("a slow step counts its seconds on one line and ends it", "[progress][util]") {
  CaptureStderr err("always");
  {
    SlowStep step("building kernel for X", /*delay_s=*/0);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  }
  const std::string s = err.text.str();
  INFO(s);
  CHECK(s.rfind("\rbuilding kernel for X... 0.", 0) == 0);
  CHECK(s.find("\rbuilding kernel for X: 0.") != std::string::npos);
  const std::string last = s.substr(s.rfind('\r'));  // padded over the longer line before
  CHECK(last.rfind("\rbuilding kernel for X: 0.", 0) == 0);
  CHECK(last.find(" s ") != std::string::npos);
  CHECK(last.back() == '\n');
  CHECK(std::count(s.begin(), s.end(), '\n') == 1);
  {
    SlowStep quick("building kernel for Y", /*delay_s=*/60);  // done before its delay: silent
  }
  CHECK(err.text.str() == s);
}

TEST_CASE("log messages go to the sink app/ sets, and back to stderr's default", "[log]") {
  std::vector<std::pair<LogLevel, std::string>> seen;
  set_log_sink([&seen](LogLevel level, const std::string& message) { seen.emplace_back(level, message); });
  log_message(LogLevel::Warning, "cannot write the program cache entry /x");
  log_message(LogLevel::Info, "build options (dev): -cl-std=CL1.2");
  set_log_sink(nullptr);  // the default again: nothing more reaches `seen`
  REQUIRE(seen.size() == 2);
  CHECK(seen[0].first == LogLevel::Warning);
  CHECK(seen[0].second == "cannot write the program cache entry /x");
  CHECK(seen[1].first == LogLevel::Info);
}

}  // namespace test_output_rules
