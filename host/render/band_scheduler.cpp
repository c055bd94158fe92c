// band_scheduler.cpp - dynamic, adaptive band scheduling over devices.
#include "render/band_scheduler.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>

#include "cl/launch_timing.hpp"
#include "util/error.hpp"
#include "util/parallel.hpp"
#include "util/timer.hpp"

namespace clrt {

double launch_limit_ms(const TilePolicy& policy, const std::string& device_type) {
  if (policy.max_launch_ms >= 0) return policy.max_launch_ms;
  return is_cpu_type(device_type) ? 0.0 : 500.0;
}

bool BandQueue::take(int want, bool guided, int& y0, int& rows) {
  std::lock_guard<std::mutex> lock(mutex_);
  int left = end_ - next_;
  if (left <= 0) return false;
  int n = std::min(want, left);
  if (guided && workers_ > 1) n = std::min(n, std::max(1, (left + 2 * workers_ - 1) / (2 * workers_)));
  y0 = next_;
  rows = n;
  next_ += n;
  return true;
}

namespace {

// Rows done over every worker, for the progress callback.
struct RowProgress {
  const ProgressFn& fn;
  std::atomic<int> rows{0};
  RowProgress(const ProgressFn& f, int height) : fn(f) {
    if (fn) fn(0, height, "rows");
  }
  void add(int n, int height) {
    const int done = rows += n;
    if (fn) fn(done, height, "rows");
  }
};

// Throws Cancelled once `cancel` asked for a stop (after the bands in flight).
void run_worker(DeviceRenderer& r, BandQueue& queue, Image& img, const TilePolicy& policy, int n_workers,
                DeviceShare& share, RowProgress& progress, int range_rows, const CancelFn& cancel) {
  const int W = img.width, H = range_rows;
  const double limit = launch_limit_ms(policy, r.device().type);
  // Largest band the device can hold (float RGB output is the largest buffer).
  const long long alloc_rows = std::max<long long>(1, (long long)(r.device().max_alloc / (3 * sizeof(float))) / W);
  const int max_rows = int(std::min<long long>(H, alloc_rows));
  // Someone watches the progress: bands of about kProgressBandMs, so that
  // the bar moves during a long frame on a device without a launch limit
  // (before, a CPU frame was one launch: "0/600 rows" until it ended).
  // The few extra launches cost nothing against a frame that long; short
  // frames grow to one or two bands at once (4x per band).
  // A caller that may stop the frame (cancel) gets the same bands: a stop
  // waits for the bands in flight, so they must be short.
  constexpr double kProgressBandMs = 250;
  const bool watched = static_cast<bool>(progress.fn) || static_cast<bool>(cancel);
  // The time per band aimed at: 80% of the launch limit, or (no limit) 100
  // ms with several devices, kProgressBandMs when watched; 0: none.
  const double target = limit > 0 ? 0.8 * limit : n_workers > 1 ? 100.0 : watched ? kProgressBandMs : 0.0;
  int rows;
  if (policy.band_rows > 0)
    rows = policy.band_rows;
  else if (target > 0 && limit == 0 && r.ms_per_row() > 0)  // (never where a watchdog may kill a launch)
    rows = int(std::max(1.0, std::min(std::floor(target / r.ms_per_row()), double(max_rows))));  // the last frame's rate
  else if (target > 0)
    rows = std::min(16, max_rows);  // calibration band: measure before growing
  else
    rows = max_rows;  // one device, no limit: as few launches as memory allows
  rows = std::max(1, std::min(rows, max_rows));

  // Up to r.tiles_in_flight() bands at once: on devices whose results are
  // read over a bus, band k's results travel and are converted while band
  // k+1's kernel runs. Band sizes adapt to the last finished band.
  struct Band {
    int rows;
  };
  std::vector<Band> in_flight;  // oldest first
  const auto finish_oldest = [&] {
    const int n = in_flight.front().rows;
    in_flight.erase(in_flight.begin());
    const LaunchTime launch = r.finish_tile(img);
    const double ms = launch.ms;
    share.host_timed_launches += !launch.from_events;
    share.kernel_ms += ms;
    share.max_launch_ms = std::max(share.max_launch_ms, ms);
    share.tiles += 1;
    share.rows += n;
    progress.add(n, H);
    if (policy.band_rows > 0) return;
    // Adapt to the target, growing at most 4x per step.
    const double per_row = std::max(ms, 1e-3) / n;
    if (target > 0) {
      double want = std::floor(target / per_row);
      rows = int(std::max(1.0, std::min({want, 4.0 * n, double(max_rows)})));
    }
  };
  const auto t0 = Clock::now();
  int y0 = 0, n = 0;
  bool stopped = false;
  while (!(stopped = cancel && cancel()) && queue.take(rows, policy.band_rows == 0, y0, n)) {
    r.submit_tile(0, y0, W, n, img);
    in_flight.push_back({n});
    while (int(in_flight.size()) >= r.tiles_in_flight()) finish_oldest();
  }
  while (!in_flight.empty()) finish_oldest();
  share.busy_ms = ms_since(t0);
  if (share.rows > 0) r.set_ms_per_row(std::max(share.kernel_ms, 1e-3) / double(share.rows));  // (the next frame's)
  if (stopped) throw Cancelled("render cancelled");
}

}  // namespace

std::vector<DeviceShare> render_bands(const std::vector<DeviceRenderer*>& workers, Image& img, const TilePolicy& policy,
                                      const ProgressFn& progress, int y_begin, int y_end, const CancelFn& cancel) {
  if (y_end < 0) y_end = img.height;
  if (y_begin < 0 || y_begin > y_end || y_end > img.height) throw std::logic_error("render_bands: rows out of range");
  const int range_rows = y_end - y_begin;
  RowProgress rows(progress, range_rows);
  std::vector<DeviceShare> shares(workers.size());
  for (size_t i = 0; i < workers.size(); ++i) shares[i].device = workers[i]->device().name;
  BandQueue queue(y_begin, y_end, int(workers.size()));
  if (workers.size() == 1) {
    run_worker(*workers[0], queue, img, policy, 1, shares[0], rows, range_rows, cancel);
    return shares;
  }
  // One host thread per device: each owns its context, queue and program, and
  // writes disjoint rows of `img`.
  run_on_threads(workers.size(), [&](size_t i) {
    run_worker(*workers[i], queue, img, policy, int(workers.size()), shares[i], rows, range_rows, cancel);
  });
  return shares;
}

}  // namespace clrt
