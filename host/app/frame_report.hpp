// frame_report.hpp - how a frame's per-device shares are shown: text and JSON.
#pragma once
#include <cstdio>
#include <nlohmann/json.hpp>
#include <vector>

#include "render/band_scheduler.hpp"

namespace clrt {

// One line per device: bands, rows (share of the frame), kernel and busy
// time, longest launch.
void print_shares(const std::vector<DeviceShare>& shares, std::FILE* to = stdout);
nlohmann::json shares_json(const std::vector<DeviceShare>& shares);

}  // namespace clrt
