// eval_grids.cpp - sweep and accuracy cells over the ranks of a job.
#include "dist/eval_grids.hpp"

#include <memory>
#include <optional>
#include <utility>

#include "dist/eval_wire.hpp"
#include "util/error.hpp"

namespace clrt::dist {

DeviceLabel device_label(const DeviceInfo& d) {
  return {d.name, d.index, d.platform_index, d.device_index};
}

void put_label(Writer& w, const DeviceLabel& d) {
  w.put_text(d.name);
  w.put<int32_t>(d.index), w.put<int32_t>(d.platform_index), w.put<int32_t>(d.device_index);
}

DeviceLabel get_label(Reader& r) {
  DeviceLabel d;
  d.name = r.get_text();
  d.index = r.get<int32_t>(), d.platform_index = r.get<int32_t>(), d.device_index = r.get<int32_t>();
  return d;
}

void check_same_devices(const std::vector<DeviceInfo>& local, const std::vector<DeviceLabel>& root,
                        const std::string& option) {
  bool same = local.size() == root.size();
  for (size_t k = 0; same && k < local.size(); ++k) same = local[k].name == root[k].name;
  if (same) return;
  const auto list = [](auto names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
    return s.empty() ? std::string("none") : s;
  };
  std::vector<std::string> here, there;
  for (const auto& d : local) here.push_back(d.name);
  for (const auto& d : root) there.push_back(d.name);
  throw UserError(option + " selects " + list(here) + " on this rank but " + list(there) +
                  " on rank 0 (every rank must measure the devices its rows name)");
}

namespace {

void put_scene(Writer& w, const Scene& scene) {
  const Bytes b = encode_scene(scene);
  w.put<uint64_t>(b.size());
  w.put_raw(b.data(), b.size());
}

Scene get_scene(Reader& r) {
  Bytes b(size_t(r.get_count(1)));
  if (!b.empty()) r.get_raw(b.data(), b.size());
  return decode_scene(b);
}

// This rank's devices, selected once (by the thread that runs cells).
template <class T>
class Once {
 public:
  explicit Once(std::function<T()> make) : make_(std::move(make)) {}
  const T& get() {
    if (!value_) value_ = make_();
    return *value_;
  }

 private:
  std::function<T()> make_;
  std::optional<T> value_;
};

}  // namespace

Bytes encode_sweep_input(const SweepInput& in) {
  Writer w;
  put_scene(w, in.scene);
  w.put<int32_t>(in.depth_from), w.put<int32_t>(in.depth_to);
  w.put<uint64_t>(in.devices.size());
  for (const DeviceLabel& d : in.devices) put_label(w, d);
  return std::move(w.bytes);
}

SweepInput decode_sweep_input(const Bytes& b) {
  Reader r(b);
  SweepInput in;
  in.scene = get_scene(r);
  in.depth_from = r.get<int32_t>(), in.depth_to = r.get<int32_t>();
  in.devices.resize(size_t(r.get_count(1)));
  for (DeviceLabel& d : in.devices) d = get_label(r);
  expect_done(r, "a sweep's input");
  return in;
}

std::vector<SweepRow> sweep_across_ranks(Communicator& comm, const SweepInput& in,
                                         const std::function<std::vector<DeviceInfo>()>& local_devices,
                                         const RenderSettings& settings, const SweepSettings& s, GridStats* stats) {
  // Cells: the reference of each depth, then (depth, device) in run_sweep's
  // row order.
  const int depths = in.depth_to - in.depth_from + 1, devices = int(in.devices.size());
  const int cells = depths + depths * devices;
  Once<std::vector<DeviceInfo>> mine([&] {
    auto devs = local_devices();
    check_same_devices(devs, in.devices, "--devices");
    return devs;
  });
  const auto compute = [&](int cell) -> Bytes {
    Writer w;
    if (cell < depths) {
      const SweepReference ref = sweep_reference(in.scene, s, in.depth_from + cell);
      w.put(ref.ms);
      put_image(w, ref.image);
    } else {
      const int i = cell - depths;
      put_sweep_row(w, sweep_row(in.scene, mine.get()[size_t(i % devices)], settings, s, in.depth_from + i / devices));
    }
    return std::move(w.bytes);
  };

  // Rank 0: a row is finished (compared) once the reference of its depth
  // and the same device's row at the depth before have arrived; an image is
  // dropped as soon as nothing waits for it.
  std::vector<std::optional<SweepReference>> refs(static_cast<size_t>(depths));
  std::vector<SweepRow> rows(static_cast<size_t>(depths * devices));
  std::vector<int> state(rows.size(), 0);  // 0: not here, 1: here, 2: finished
  std::vector<int> unfinished(static_cast<size_t>(depths), devices);
  const auto advance = [&] {
    for (int d = 0; d < depths; ++d) {
      if (!refs[size_t(d)]) continue;
      for (int k = 0; k < devices; ++k) {
        const size_t i = size_t(d * devices + k), before = size_t((d - 1) * devices + k);
        if (state[i] != 1 || (d > 0 && state[before] != 2)) continue;
        SweepRow& row = rows[i];
        sweep_compare(row, *refs[size_t(d)], d > 0 ? &rows[before].bench.image : nullptr,
                      d > 0 ? rows[before].bench.kernel.median : 0);
        if (d > 0) rows[before].bench.image = Image();
        if (d == depths - 1) row.bench.image = Image();
        state[i] = 2;
        if (--unfinished[size_t(d)] == 0) refs[size_t(d)].reset();
      }
    }
  };
  const auto gather = [&](int cell, Bytes&& bytes) {
    Reader r(bytes);
    if (cell < depths) {
      SweepReference ref;
      ref.ms = r.get<double>();
      ref.image = get_image(r);
      refs[size_t(cell)] = std::move(ref);
    } else {
      const int i = cell - depths;
      SweepRow row = get_sweep_row(r);
      // Labelled with rank 0's device (the same name on every rank).
      const DeviceLabel& label = in.devices[size_t(i % devices)];
      row.device = label.name;
      row.device_index = label.index;
      row.device_pd = std::to_string(label.platform_index) + ":" + std::to_string(label.device_index);
      rows[size_t(i)] = std::move(row);
      state[size_t(i)] = 1;
    }
    expect_done(r, "a sweep cell's");
    advance();
  };
  GridSettings g;
  if (s.progress) g.progress = [&](int done, int total, const std::string& what) { s.progress(done, total, what); };
  g.cell_name = [&](int cell) {
    if (cell < depths) return "reference at depth " + std::to_string(in.depth_from + cell);
    const int i = cell - depths;
    return "depth " + std::to_string(in.depth_from + i / devices) + " on " + in.devices[size_t(i % devices)].name;
  };
  run_grid(comm, cells, compute, gather, g, stats);
  if (comm.rank() != 0) return {};
  for (int st : state)
    if (st != 2) throw DeviceError("MPI: a sweep row was not compared");
  return rows;
}

Bytes encode_accuracy_input(const AccuracyInput& in) {
  Writer w;
  w.put<uint64_t>(in.scenes.size());
  for (const NamedScene& ns : in.scenes) {
    w.put_text(ns.name);
    put_scene(w, ns.scene);
  }
  put_label(w, in.device);
  return std::move(w.bytes);
}

AccuracyInput decode_accuracy_input(const Bytes& b) {
  Reader r(b);
  AccuracyInput in;
  in.scenes.resize(size_t(r.get_count(1)));
  for (NamedScene& ns : in.scenes) {
    ns.name = r.get_text();
    ns.scene = get_scene(r);
  }
  in.device = get_label(r);
  expect_done(r, "an accuracy run's input");
  return in;
}

std::vector<AccuracyRow> accuracy_across_ranks(Communicator& comm, const AccuracyInput& in,
                                               const std::function<DeviceInfo()>& local_device,
                                               const AccuracySettings& s, GridStats* stats) {
  // Cells: the reference of each scene, then (scene, variant) in
  // measure_accuracy's row order.
  const int scenes = int(in.scenes.size()), variants = int(s.variants.size());
  const int cells = scenes + scenes * variants;
  Once<DeviceInfo> mine([&] {
    DeviceInfo dev = local_device();
    check_same_devices({dev}, {in.device}, "--device");
    return dev;
  });
  const auto compute = [&](int cell) -> Bytes {
    Writer w;
    if (cell < scenes) {
      put_image(w, accuracy_reference(in.scenes[size_t(cell)].scene, s));
    } else {
      const int i = cell - scenes;
      Image image;
      const AccuracyRow row = measure_accuracy_variant(in.scenes[size_t(i / variants)],
                                                       s.variants[size_t(i % variants)], mine.get(), s, image);
      put_accuracy_row(w, row);
      put_image(w, image);
    }
    return std::move(w.bytes);
  };

  // Rank 0: a row is finished once its scene's reference is here; the
  // reference is dropped when its scene's rows are.
  std::vector<std::optional<Image>> refs(static_cast<size_t>(scenes));
  std::vector<AccuracyRow> rows(static_cast<size_t>(scenes * variants));
  std::vector<Image> images(rows.size());
  std::vector<int> state(rows.size(), 0);  // 0: not here, 1: here, 2: finished
  std::vector<int> unfinished(static_cast<size_t>(scenes), variants);
  const auto advance = [&](int scene) {
    if (!refs[size_t(scene)]) return;
    for (int v = 0; v < variants; ++v) {
      const size_t i = size_t(scene * variants + v);
      if (state[i] != 1) continue;
      if (rows[i].supported) rows[i].error = compare_images(images[i], *refs[size_t(scene)]);
      images[i] = Image();
      state[i] = 2;
      if (--unfinished[size_t(scene)] == 0) refs[size_t(scene)].reset();
    }
  };
  const auto gather = [&](int cell, Bytes&& bytes) {
    Reader r(bytes);
    if (cell < scenes) {
      refs[size_t(cell)] = get_image(r);
      expect_done(r, "an accuracy cell's");
      return advance(cell);
    }
    const int i = cell - scenes;
    rows[size_t(i)] = get_accuracy_row(r);
    images[size_t(i)] = get_image(r);
    expect_done(r, "an accuracy cell's");
    state[size_t(i)] = 1;
    advance(i / variants);
  };
  GridSettings g;
  if (s.progress) g.progress = [&](int done, int total, const std::string& what) { s.progress(done, total, what); };
  g.cell_name = [&](int cell) {
    if (cell < scenes) return in.scenes[size_t(cell)].name + ": reference";
    const int i = cell - scenes;
    return in.scenes[size_t(i / variants)].name + ": " + s.variants[size_t(i % variants)].name();
  };
  run_grid(comm, cells, compute, gather, g, stats);
  if (comm.rank() != 0) return {};
  for (int st : state)
    if (st != 2) throw DeviceError("MPI: an accuracy row was not compared");
  return rows;
}

}  // namespace clrt::dist
