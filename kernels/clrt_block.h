/* clrt_block.h - the pixels of a work-item: a block of CLRT_LANES pixels,
 * CLRT_PACKET_COLS wide and CLRT_PACKET_ROWS high, one per SIMD lane
 * (clrt_lanes.h), row by row. Lanes beyond the tile's edge are traced and
 * never stored.
 *
 * Subsampling's strided launches (clrt_subsample.h: interpolate's both,
 * shade's first) take every other column of the tile, those of global
 * parity `pass`: a block then spans tile columns first_col + 2 (px + lane
 * column). */
#ifndef CLRT_BLOCK_H
#define CLRT_BLOCK_H

#include "clrt_lanes.h"

typedef struct pixel_block {
  int px, py;              /* the first lane's column in the launch's columns, its row in the tile */
  int first_col, col_step; /* tile column of the launch's column c: first_col + col_step c */
  int columns;             /* the launch's columns in the tile */
  int tile_w, tile_h;
} pixel_block;

/* Work-item (gx, gy)'s block in a tile at image column x0 of tile_w x
 * tile_h pixels, for launch `pass`. */
CLRT_INLINE pixel_block block_of(const int gx, const int gy, const int x0, const int tile_w, const int tile_h,
                                 const int pass) {
  pixel_block b;
  b.px = gx * CLRT_PACKET_COLS;
  b.py = gy * CLRT_PACKET_ROWS;
  b.tile_w = tile_w;
  b.tile_h = tile_h;
#if CLRT_SUBSAMPLE
  const int strided = CLRT_SUBSAMPLE == CLRT_SUBSAMPLE_INTERPOLATE || pass == 0;
  b.first_col = strided ? (pass - x0) & 1 : 0; /* global columns of parity `pass` */
  b.col_step = strided ? 2 : 1;
  b.columns = strided ? (tile_w - b.first_col + 1) / 2 : tile_w;
#else
  b.first_col = 0;
  b.col_step = 1;
  b.columns = tile_w;
#endif
  return b;
}

/* Whether the block has a pixel in the tile (the launch is padded to a
 * multiple of the local size). */
CLRT_INLINE int block_in_tile(const pixel_block* b) {
  return b->px < b->columns && b->py < b->tile_h;
}

/* The tile column and row of lane j. */
CLRT_INLINE int lane_tile_x(const pixel_block* b, const int j) {
  return b->first_col + b->col_step * (b->px + j % CLRT_PACKET_COLS);
}
CLRT_INLINE int lane_tile_y(const pixel_block* b, const int j) {
  return b->py + j / CLRT_PACKET_COLS;
}
/* Whether lane j's pixel is in the tile (else it is never stored). */
CLRT_INLINE int lane_in_tile(const pixel_block* b, const int j) {
  return lane_tile_x(b, j) < b->tile_w && lane_tile_y(b, j) < b->tile_h;
}

/* The same for every lane at once. */
CLRT_INLINE lint lanes_tile_x(const pixel_block* b) {
  return b->first_col + b->col_step * (b->px + LANE_IOTA % CLRT_PACKET_COLS);
}
CLRT_INLINE lint lanes_tile_y(const pixel_block* b) {
  return b->py + LANE_IOTA / CLRT_PACKET_COLS;
}

#endif /* CLRT_BLOCK_H */
