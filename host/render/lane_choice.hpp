// lane_choice.hpp - how many pixels a work-item shades (SIMD lanes) when
// --lanes does not say: where more than one count is a candidate, a short
// timed probe on the scene decides, and the answer is remembered for the
// process (DeviceRenderer::prepare() runs it).
//
// Why a probe and not a rule: whether a block of lanes or one ray per
// work-item walks the hierarchy faster depends on the scene, the image size
// and the device together. The size rule it replaced (one ray per work-item
// from 100 000 spheres whose median is under 8 px) picked the slower mode at
// 640x360 on 100 000 spheres (2.3x) and the faster one at 1920x1080
// (docs/results/wide-hierarchy.md). The image never depends on the choice:
// every lane count renders the same pixels (tests/render/test_lanes.cpp).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "cl/device.hpp"
#include "render/build_options.hpp"
#include "render/scene_buffers.hpp"

namespace clrt {

// The lane counts to choose from: cfg.lanes when set; else default_lanes(),
// followed, where the kernel walks a hierarchy with blocks of lanes (`bvh`
// and default_lanes() > 1) unless cfg.probe_lanes is off, by 8 (4x2 blocks,
// where the default is 16: faster on large scenes at 640x360, 3-7%) and 1
// (one ray per work-item). One candidate: no probe.
std::vector<int> lane_candidates(const KernelConfig& cfg, const DeviceInfo& dev, bool bvh);

// The rows a probe renders of a `height`-row image: kProbeBands bands of
// whole rows spread evenly over the image (a scene's cost per row varies
// from top to bottom), about 1/kProbeShare of the rows in all, each a
// multiple of kProbeBlockRows rows starting on a multiple of it, clipped to
// the image. kProbeBlockRows is the tallest block of lanes (16 lanes: 4x4,
// packet_rows()): a band of 5 rows cost a 16-lane kernel two rows of blocks,
// 8 rows of work against one ray per work-item's 5, and the probe chose one
// ray per work-item on 1 000 spheres at 640x360 where blocks render the frame
// 1.4x faster (docs/results/wide-hierarchy.md).
constexpr int kProbeBands = 4, kProbeShare = 16, kProbeBlockRows = 4;
struct RowBand {
  int y0 = 0, rows = 0;
};
std::vector<RowBand> probe_bands(int height);

// Rounds of the probe: each candidate renders the bands once per round, the
// candidates taking turns, and a candidate's time is its fastest round (the
// machine's load comes and goes; the fastest round is the one least
// disturbed). The first launch of a program is a round of its own that is
// not timed (PoCL compiles its work-group function there). Eight rounds:
// with two, a band's time moved by up to 2x from round to round on 1 000
// spheres at 640x360 and the probe picked the 1.4x slower mode in 2 of 6
// runs; with four it picked the faster in 5 of 5 there, but the slower
// (one ray per work-item, 1.2x) in 7 of 50 runs on the million-triangle
// mesh, and with eight in none of 50 (docs/results/wide-hierarchy.md).
// That was before PoCL's workers were pinned (cl/pocl_workers.hpp: a short
// launch took twice its time in about half the rounds); since, five rounds
// of three candidates picked the faster blocks of 8 in 52 of 52 runs on the
// mesh and blocks of 16 in 10 of 10 on 4 000 triangles, for about the work
// eight rounds of two took (1.2-1.4 frames, once per scene and device in a
// process; the third program's build and first launch add 4-6% to a
// one-frame `clrt render` of 10^5 spheres or the mesh at 640x360).
// ("Blocks of 8 as a candidate", docs/results/wide-hierarchy.md.)
constexpr int kProbeRounds = 5;

// What identifies a probe's answer: the device, the program's options (the
// scene's features, precision and outputs), and a hash of everything the
// kernel reads (parameters - image size, depth, samples - and the scene's
// packed primitives and hierarchy). Equal keys: the same work on the same
// device.
std::string lane_choice_key(const DeviceInfo& dev, const std::string& options, const SceneData& data,
                            const std::vector<clrt_wide_node>* nodes);

// The process's remembered choices (thread-safe: devices prepare on threads
// of their own). recall_lanes() returns 0 for a key never probed.
int recall_lanes(const std::string& key);
void remember_lanes(const std::string& key, int lanes);

}  // namespace clrt
