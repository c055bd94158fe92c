// frame_report.cpp - per-device shares of a frame, as text and JSON.
#include "app/frame_report.hpp"

#include "cl/launch_timing.hpp"

namespace clrt {

void print_shares(const std::vector<DeviceShare>& shares, std::FILE* to) {
  long long total = 0;
  for (const auto& s : shares) total += s.rows;
  for (size_t i = 0; i < shares.size(); ++i) {
    const auto& s = shares[i];
    std::fprintf(to,
                 "  device %zu %-48.48s %4d tiles, %6lld rows (%5.1f%%), kernel %9.2f ms, busy %9.2f ms, longest "
                 "launch %8.2f ms%s\n",
                 i, s.device.c_str(), s.tiles, s.rows, total ? 100.0 * s.rows / total : 0.0, s.kernel_ms, s.busy_ms,
                 s.max_launch_ms, time_source_note(s.host_timed_launches, s.tiles).c_str());
  }
}

void print_rank_shares(const std::vector<dist::RankShare>& shares, const char* unit, std::FILE* to) {
  long long total = 0;
  for (const auto& s : shares) total += s.rows;
  for (const auto& s : shares)
    std::fprintf(to, "  rank %d %-16.16s %-40.40s %4d %s, %6lld rows (%5.1f%%), kernel %9.2f ms, busy %9.2f ms\n",
                 s.rank, s.host.c_str(), s.devices.c_str(), s.units, unit, s.rows, total ? 100.0 * s.rows / total : 0.0,
                 s.kernel_ms, s.busy_ms);
}

nlohmann::json shares_json(const std::vector<DeviceShare>& shares) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& d : shares)
    a.push_back({{"device", d.device},
                 {"tiles", d.tiles},
                 {"rows", d.rows},
                 {"kernel_ms", d.kernel_ms},
                 {"kernel_time_source", time_source(d.host_timed_launches, d.tiles)},
                 {"busy_ms", d.busy_ms},
                 {"longest_launch_ms", d.max_launch_ms}});
  return a;
}

}  // namespace clrt
