// test_output_rules.cpp - the small rules every report shares: CSV quoting
// (RFC 4180), the progress bar's text, and the log's routing to a sink.
#include <catch2/catch.hpp>
#include <sstream>
#include <utility>
#include <vector>

#include "util/csv.hpp"
#include "util/log.hpp"
#include "util/progress.hpp"

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

TEST_CASE("the progress bar redraws in place and ends with a newline", "[progress]") {
  std::ostringstream out;
  ProgressBar bar(out, 10);
  CHECK(bar.text(0, 4, "depth 0") == "\r[          ] 0/4 depth 0" + std::string(33, ' '));
  CHECK(bar.text(2, 4, "x") == "\r[#####     ] 2/4 x" + std::string(39, ' '));
  // The label is cut to 40 characters, so the line never wraps and grows.
  const std::string long_label(50, 'y');
  CHECK(bar.text(1, 4, long_label) == "\r[##        ] 1/4 " + std::string(40, 'y'));
  CHECK(bar.text(4, 4, "done") == "\r[##########] 4/4 done" + std::string(36, ' ') + "\n");
  CHECK(bar.text(0, 0, "done") == "\r[##########] 0/0 done" + std::string(36, ' ') + "\n");
  bar.show(1, 2, "a");
  bar.show(2, 2, "done");
  CHECK(out.str() == bar.text(1, 2, "a") + bar.text(2, 2, "done"));
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
