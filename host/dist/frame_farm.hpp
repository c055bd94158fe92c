// frame_farm.hpp - one frame rendered by every rank of a job, master-worker:
// rank 0 hands out bands of rows (tiles) one at a time as ranks ask for
// them - Whitted cost varies strongly across an image, so a static split
// would wait for the slowest rank - renders tiles itself meanwhile, and
// gathers the rows into the frame. Every pixel is computed by the same
// kernel as in one process, so the frame is bit-identical to a
// single-process render (tests/dist/).
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "dist/communicator.hpp"
#include "dist/farm.hpp"
#include "image/image.hpp"
#include "render/renderer.hpp"
#include "util/progress.hpp"

namespace clrt::dist {

struct FarmSettings {
  int width = 0, height = 0;
  FrameContents contents;  // what the frame holds (every rank's kernel writes it)
  // Rows per tile; 0 = guided: a tile is an even share of what is left over
  // 2 x ranks, at least kMinTilePixels pixels, so tiles shrink towards the
  // end of the frame and no rank waits long for the last one.
  int tile_rows = 0;
  ProgressFn progress{};  // rank 0: rows done of the frame
  // A test hook (clrt render's hidden --mpi-test-stall): this rank stops
  // taking part in MPI right after sending its first rows, as a link that
  // stalls in the middle of a message would. -1: none.
  int test_stall_rank = -1;
};
constexpr long long kMinTilePixels = 32768;

struct FarmStats {
  std::vector<RankShare> ranks;  // rank 0: one per rank, in rank order
  int tiles = 0;
  double wall_ms = 0;
  long long bytes_received = 0;  // rows sent to rank 0
  double gather_ms = 0;          // rank 0's MPI thread: the polls that completed those messages (straight into the frame)
};

// Collective: every rank calls it. `prepare` constructs and prepares this
// rank's renderer (its own --device) for the frame; a failure on any rank -
// there or while rendering - stops every rank: rank 0 throws the failing
// rank's error, the others JobAborted. Returns the frame on rank 0 and an
// empty image on the others; `stats` on rank 0.
Image farm_frame(Communicator& comm, const std::function<Renderer&()>& prepare, const FarmSettings& settings,
                 FarmStats* stats);

// The tile rule of FarmSettings: rows of the next tile when `left` rows
// remain for `ranks` ranks in a frame `width` wide, at most `max_rows` (a
// tile's message stays under kMaxTileBytes: rows_per_message()).
int next_tile_rows(int left, int ranks, int width, int tile_rows, int max_rows);

}  // namespace clrt::dist
