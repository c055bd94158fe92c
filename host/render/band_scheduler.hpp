// band_scheduler.hpp - splits a frame into horizontal bands (tiles of full
// width) handed out dynamically to one or more devices: each device takes its
// next band when it finishes the previous one, so faster devices take more.
// Band heights adapt per device so no kernel launch exceeds a time limit (GPU
// watchdogs) and no band exceeds the device's largest allocation.
#pragma once
#include <mutex>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "render/device_renderer.hpp"
#include "util/progress.hpp"

namespace clrt {

struct TilePolicy {
  // Upper bound for one kernel launch in ms; 0 = none. The default (-1)
  // means: 500 ms on GPUs/accelerators (watchdogs kill long launches), none
  // on CPUs.
  double max_launch_ms = -1;
  // Fixed band height in rows; 0 = adaptive.
  int band_rows = 0;
};

// What one device did in a frame.
struct DeviceShare {
  std::string device;
  int tiles = 0;                // bands rendered
  long long rows = 0;           // image rows rendered
  double kernel_ms = 0;         // sum of kernel times (profiling events, or host time where implausible)
  int host_timed_launches = 0;  // launches timed by the host clock (launch_timing.hpp)
  double busy_ms = 0;           // wall time spent launching, waiting and copying
  double max_launch_ms = 0;
};

// The rows of a frame, taken band by band by several threads.
class BandQueue {
 public:
  // Rows [begin, end) of a frame.
  BandQueue(int begin, int end, int workers) : end_(end), workers_(workers), next_(begin) {}

  // Takes up to `want` rows; when `guided` and there are several workers, at
  // most half of an even share of what is left (guided scheduling), so the
  // frame ends with small bands and no device waits long for the slowest.
  // Returns false when the frame is done.
  bool take(int want, bool guided, int& y0, int& rows);

 private:
  std::mutex mutex_;
  int end_, workers_, next_;
};

// Renders rows [y_begin, y_end) of every worker's prepared scene into `img`
// (all workers must have been prepared with the same scene and size; y_end
// < 0: to the last row). Returns one share per worker, in order. Exceptions
// from any worker are rethrown. `progress` (optional): rows done of the
// range, after each band. `cancel` (optional): asked before each band is
// taken; true: the bands in flight finish and Cancelled is thrown.
//
// Adaptive bands (band_rows 0) with a target time (a launch limit, several
// devices, progress or cancel): a device's first band is 16 rows that
// calibrate its time per row, or, without a launch limit, in a later frame
// of the same prepare(), sized at once from its last frame's mean rate.
std::vector<DeviceShare> render_bands(const std::vector<DeviceRenderer*>& workers, Image& img, const TilePolicy& policy,
                                      const ProgressFn& progress = {}, int y_begin = 0, int y_end = -1,
                                      const CancelFn& cancel = {});

// The effective launch limit of `policy` for a device of this type string.
double launch_limit_ms(const TilePolicy& policy, const std::string& device_type);

}  // namespace clrt
