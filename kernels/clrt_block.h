/* clrt_block.h - the pixels of a work-item: a block of CLRT_LANES pixels,
 * CLRT_PACKET_COLS wide and CLRT_PACKET_ROWS high, one per SIMD lane
 * (clrt_lanes.h), row by row. Lanes beyond the tile's edge are traced and
 * never stored.
 *
 * A launch shades the tile columns first_column + column_step c (kernel
 * arguments): every column, or with subsampling (clrt_subsample.h) every
 * other one, those of one parity of the image's columns. A block then spans
 * tile columns first_column + column_step (px + lane column). */
#ifndef CLRT_BLOCK_H
#define CLRT_BLOCK_H

#include "clrt_lanes.h"

typedef struct pixel_block {
  int px, py;              /* the first lane's column in the launch's columns, its row in the tile */
  int first_col, col_step; /* tile column of the launch's column c: first_col + col_step c */
  int columns;             /* the launch's columns in the tile */
  int tile_w, tile_h;
} pixel_block;

/* Work-item (gx, gy)'s block in a tile of tile_w x tile_h pixels, in a
 * launch over the tile columns first_column + column_step c. */
CLRT_INLINE pixel_block block_of(const int gx, const int gy, const int first_column, const int column_step,
                                 const int tile_w, const int tile_h) {
  pixel_block b;
  b.px = gx * CLRT_PACKET_COLS;
  b.py = gy * CLRT_PACKET_ROWS;
  b.tile_w = tile_w;
  b.tile_h = tile_h;
  b.first_col = first_column;
  b.col_step = column_step;
  b.columns = (tile_w - first_column + column_step - 1) / column_step;
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
