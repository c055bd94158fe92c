// frame_report.hpp - how a frame's per-device shares are shown: text and JSON.
#pragma once
#include <cstdio>
#include <nlohmann/json.hpp>
#include <vector>

#include "dist/frame_farm.hpp"
#include "render/band_scheduler.hpp"

namespace clrt {

// One line per device: bands, rows (share of the frame), kernel and busy
// time, longest launch.
void print_shares(const std::vector<DeviceShare>& shares, std::FILE* to = stdout);
nlohmann::json shares_json(const std::vector<DeviceShare>& shares);
// One line per rank of an MPI job: its host and devices, what it rendered
// (`unit`: "tiles", "frames", ...) and its share of the rows, busy time.
void print_rank_shares(const std::vector<dist::RankShare>& shares, const char* unit, std::FILE* to = stdout);

}  // namespace clrt
