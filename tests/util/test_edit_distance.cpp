// test_edit_distance.cpp - the distance behind "did you mean ...?".
#include <catch2/catch.hpp>

#include "util/edit_distance.hpp"

// (clrt_tests is a unity build: each file's code is in a namespace of its own.)
namespace test_edit_distance {

using clrt::closest_match;
using clrt::edit_distance;

TEST_CASE("edit distance: insertions, deletions, substitutions, adjacent swaps", "[util]") {
  CHECK(edit_distance("", "") == 0);
  CHECK(edit_distance("render", "render") == 0);
  CHECK(edit_distance("", "abc") == 3);
  CHECK(edit_distance("abc", "") == 3);
  CHECK(edit_distance("rendr", "render") == 1);    // a deletion
  CHECK(edit_distance("renderr", "render") == 1);  // an insertion
  CHECK(edit_distance("rander", "render") == 1);   // a substitution
  CHECK(edit_distance("redner", "render") == 1);   // two neighbours swapped
  CHECK(edit_distance("kitten", "sitting") == 3);
  CHECK(edit_distance("ca", "abc") == 3);  // optimal string alignment: no edit of a swapped pair
  CHECK(edit_distance("Render", "render") == 1);
  // Symmetric.
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {"bench", "bnch"}, {"devices", "device"}, {"compare", "comprae"}, {"x", "sweep"}};
  for (const auto& [a, b] : pairs) CHECK(edit_distance(a, b) == edit_distance(b, a));
}

TEST_CASE("closest match: only near misses are suggested", "[util]") {
  const std::vector<std::string> commands = {"devices", "render",   "compare",   "bench",    "sweep",
                                             "scaling", "accuracy", "stability", "generate", "cache"};
  CHECK(closest_match("rendr", commands) == "render");
  CHECK(closest_match("devcies", commands) == "devices");
  CHECK(closest_match("cahce", commands) == "cache");
  CHECK(closest_match("benhc", commands) == "bench");
  CHECK(closest_match("stabilty", commands) == "stability");
  CHECK(closest_match("xyz", commands).empty());
  CHECK(closest_match("frobnicate", commands).empty());
  CHECK(closest_match("", commands).empty());
  CHECK(closest_match("a", {"b"}).empty());  // one edit is the whole word
  CHECK(closest_match("ab", {"abc"}) == "abc");
  CHECK(closest_match("clr", {"info", "clear"}) == "clear");
  CHECK(closest_match("nfo", {"info", "clear"}) == "info");
  CHECK(closest_match("rndr", commands) == "render");  // two edits
  CHECK(closest_match("rndrx", commands).empty());     // three
  CHECK(closest_match("rendr", {}).empty());
}

}  // namespace test_edit_distance
