// eval_wire.hpp - the results of evaluation cells as bytes between ranks:
// images, sweep rows and accuracy rows, every field (exact: doubles travel
// as bits, so a row gathered from another rank equals the row computed
// there). Malformed bytes are a DeviceError (dist/wire.hpp's Reader).
#pragma once
#include "dist/communicator.hpp"
#include "dist/wire.hpp"
#include "eval/accuracy.hpp"
#include "eval/compare.hpp"
#include "eval/sweep.hpp"
#include "image/image.hpp"
#include "util/stats.hpp"

namespace clrt::dist {

// A whole image: size, contents and every buffer they hold.
void put_image(Writer& w, const Image& img);
Image get_image(Reader& r);
Bytes encode_image(const Image& img);
Image decode_image(const Bytes& b);

void put_stats(Writer& w, const Stats& s);
Stats get_stats(Reader& r);
void put_comparison(Writer& w, const Comparison& c);
Comparison get_comparison(Reader& r);
void put_bench(Writer& w, const BenchResult& b);  // with its images
BenchResult get_bench(Reader& r);

void put_sweep_row(Writer& w, const SweepRow& row);  // with bench.image and bench.reference_image
SweepRow get_sweep_row(Reader& r);
void put_accuracy_row(Writer& w, const AccuracyRow& row);
AccuracyRow get_accuracy_row(Reader& r);
// The same as whole messages (decode: DeviceError on bytes left over).
Bytes encode_sweep_row(const SweepRow& row);
SweepRow decode_sweep_row(const Bytes& b);
Bytes encode_accuracy_row(const AccuracyRow& row);
AccuracyRow decode_accuracy_row(const Bytes& b);
// DeviceError unless `r` has read its whole message ("MPI: WHAT message
// with bytes left over").
void expect_done(const Reader& r, const char* what);

}  // namespace clrt::dist
