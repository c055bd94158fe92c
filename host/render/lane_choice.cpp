// lane_choice.cpp - the candidates, bands and memory of the lanes probe.
#include "render/lane_choice.hpp"

#include <algorithm>
#include <cstring>
#include <map>
#include <mutex>

#include "util/content_hash.hpp"

namespace clrt {

std::vector<int> lane_candidates(const KernelConfig& cfg, const DeviceInfo& dev, bool bvh) {
  if (cfg.lanes != 0) return {cfg.lanes};
  const int lanes = default_lanes(cfg, dev);
  if (lanes == 1 || !bvh || !cfg.probe_lanes) return {lanes};
  if (lanes == 16) return {16, 8, 1};
  return {lanes, 1};
}

std::vector<RowBand> probe_bands(int height) {
  std::vector<RowBand> bands;
  if (height <= 0) return bands;
  const int share = height / (kProbeBands * kProbeShare);
  const int rows = std::max(1, (share + kProbeBlockRows - 1) / kProbeBlockRows) * kProbeBlockRows;
  for (int i = 0; i < kProbeBands; ++i) {
    // centred on the middle of the i-th quarter of the image, on a block row
    const int middle = int((2 * int64_t(i) + 1) * height / (2 * kProbeBands));
    const int y0 = std::max(0, std::min(middle - rows / 2, height - rows)) / kProbeBlockRows * kProbeBlockRows;
    const int clipped = std::min(rows, height - y0);
    if (!bands.empty() && y0 < bands.back().y0 + bands.back().rows) continue;  // a short image: no row twice
    bands.push_back({y0, clipped});
  }
  return bands;
}

namespace {

std::mutex memory_mutex;
std::map<std::string, int>& memory() {
  static std::map<std::string, int> choices;
  return choices;
}

}  // namespace

std::string lane_choice_key(const DeviceInfo& dev, const std::string& options, const SceneData& data,
                            const std::vector<clrt_wide_node>* nodes) {
  ContentHash hash;
  hash.add(&data.params, sizeof data.params);
  hash.add(data.spheres);
  hash.add(data.lights);
  hash.add(data.materials);
  hash.add(data.planes);
  hash.add(&data.triangles_digest, sizeof data.triangles_digest);
  if (nodes) hash.add(*nodes);
  return dev.name + "\n" + dev.platform_name + "\n" + options + "\n" + std::to_string(hash.value);
}

int recall_lanes(const std::string& key) {
  const std::lock_guard<std::mutex> lock(memory_mutex);
  const auto found = memory().find(key);
  return found == memory().end() ? 0 : found->second;
}

void remember_lanes(const std::string& key, int lanes) {
  const std::lock_guard<std::mutex> lock(memory_mutex);
  memory()[key] = lanes;
}

}  // namespace clrt
