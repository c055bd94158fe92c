// eval_grids.hpp - `clrt sweep` and `clrt accuracy` across the ranks of a
// job (dist/grid.hpp): the same rows, in the same order, with the same
// images compared, as run_sweep and measure_accuracy in one process; only
// the timings differ (each cell is timed on the rank that ran it).
//
// The cells. The double reference of a depth (sweep) or a scene (accuracy)
// is a cell of its own, and so is each (depth, device) bench or (scene,
// variant) measurement; a measuring cell sends its OpenCL image back with
// its row, and rank 0 compares it with the reference (and, in a sweep, with
// the same device's image at the depth before) as both arrive. So every
// reference is rendered once in the job, as in one process - not once per
// rank that measures a variant of its scene - and the references, handed
// out first, render beside the measurements instead of before them. The
// price is one image per measuring cell on the wire (width x height x 32
// bytes: 11.5 MB at 600x600).
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "cl/device.hpp"
#include "dist/communicator.hpp"
#include "dist/grid.hpp"
#include "dist/wire.hpp"
#include "eval/accuracy.hpp"
#include "eval/sweep.hpp"
#include "scene/scene.hpp"

namespace clrt::dist {

// What rows say of a device: rank 0's selection is the job's. Every rank
// selects its own devices with the same option; they must have the same
// names, in the same order (a row measured on another device would carry
// the wrong name).
struct DeviceLabel {
  std::string name;
  int index = 0, platform_index = 0, device_index = 0;
};
DeviceLabel device_label(const DeviceInfo& d);
void put_label(Writer& w, const DeviceLabel& d);
DeviceLabel get_label(Reader& r);
// UserError unless `local` names the devices of `root`, in order
// ("--devices selects ... on this rank, ... on rank 0").
void check_same_devices(const std::vector<DeviceInfo>& local, const std::vector<DeviceLabel>& root,
                        const std::string& option);

// What rank 0 shares before a distributed sweep (dist::share_from_root).
struct SweepInput {
  Scene scene;
  int depth_from = 0, depth_to = 0;
  std::vector<DeviceLabel> devices;
};
Bytes encode_sweep_input(const SweepInput& in);
SweepInput decode_sweep_input(const Bytes& b);

// Collective. `local_devices`: this rank's devices (called once, by the
// first cell that needs them; checked against in.devices). Rank 0: the rows
// of run_sweep, labelled with rank 0's devices, and `stats`; the others: none.
std::vector<SweepRow> sweep_across_ranks(Communicator& comm, const SweepInput& in,
                                         const std::function<std::vector<DeviceInfo>()>& local_devices,
                                         const RenderSettings& settings, const SweepSettings& s, GridStats* stats);

struct AccuracyInput {
  std::vector<NamedScene> scenes;
  DeviceLabel device;
};
Bytes encode_accuracy_input(const AccuracyInput& in);
AccuracyInput decode_accuracy_input(const Bytes& b);

// Collective, like sweep_across_ranks: rank 0 gets measure_accuracy's rows
// (s.progress: cells done; each variant's timed runs back to back on its
// rank, not interleaved with the other variants).
std::vector<AccuracyRow> accuracy_across_ranks(Communicator& comm, const AccuracyInput& in,
                                               const std::function<DeviceInfo()>& local_device,
                                               const AccuracySettings& s, GridStats* stats);

}  // namespace clrt::dist
