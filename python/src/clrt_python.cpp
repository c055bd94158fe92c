// clrt_python.cpp - the extension clrt._clrt (docs/guide/python.md): scenes,
// a renderer that keeps its programs and buffers between frames, the
// reference, and compare/accuracy/sweep/devices as the dicts of the
// command line's --json (built by the same app/ functions). Everything is
// the command line's code: the options go into its option structs
// (app/options.hpp) and are checked there, with its messages.
//
// Work runs on a thread of its own with the GIL released; the calling
// thread wakes every 20 ms to let Python handle signals, and on
// KeyboardInterrupt (or any exception a signal handler raises) asks the work
// to stop through its CancelFn (between bands, util/error.hpp's Cancelled).
#include <dlfcn.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <functional>
#include <future>
#include <mutex>
#include <new>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "app/accuracy_report.hpp"
#include "app/compare_report.hpp"
#include "app/devices_report.hpp"
#include "app/engine.hpp"
#include "app/options.hpp"
#include "app/report_header.hpp"
#include "app/sweep_report.hpp"
#include "cl/cl.hpp"
#include "cl/device.hpp"
#include "eval/accuracy.hpp"
#include "eval/sweep.hpp"
#include "image/image.hpp"
#include "image/image_file.hpp"
#include "image/image_io.hpp"
#include "reference/reference.hpp"
#include "render/renderer.hpp"
#include "scene/scene_json.hpp"
#include "util/doing.hpp"
#include "util/edit_distance.hpp"
#include "util/error.hpp"
#include "util/json_text.hpp"
#include "util/log.hpp"
#include "util/timer.hpp"

#ifndef CLRT_IMAGEIO_FROM_PYTHON
#define CLRT_IMAGEIO_FROM_PYTHON ""
#endif

namespace py = pybind11;

namespace clrt {
namespace {

// ---- errors --------------------------------------------------------------------
// clrt.Error (RuntimeError) and its kinds; UsageError is a ValueError too.
PyObject* g_error = nullptr;
PyObject* g_usage_error = nullptr;
PyObject* g_scene_error = nullptr;
PyObject* g_device_error = nullptr;

// A UserError from reading a scene: clrt.SceneError.
struct SceneError : UserError {
  using UserError::UserError;
};

PyObject* new_exception(py::module_& m, const char* name, py::tuple bases, const char* doc) {
  const std::string qualified = std::string("clrt.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (!type) throw py::error_already_set();
  m.add_object(name, py::handle(type));
  return type;
}

void translate(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const SceneError& e) {
    PyErr_SetString(g_scene_error, e.what());
  } catch (const UserError& e) {
    PyErr_SetString(g_usage_error, e.what());
  } catch (const DeviceError& e) {
    PyErr_SetString(g_device_error, e.what());
  } catch (const cl::Error& e) {
    PyErr_SetString(g_device_error, describe(e).c_str());
  } catch (const Cancelled&) {
    PyErr_SetNone(PyExc_KeyboardInterrupt);  // (a stop no signal asked for: not reached)
  } catch (const std::bad_alloc&) {
    const std::string step = failed_step();
    PyErr_SetString(PyExc_MemoryError, ("out of memory" + (step.empty() ? std::string() : " while " + step)).c_str());
  } catch (const CheckFailure& e) {
    PyErr_SetString(g_error, e.what());
  } catch (const py::builtin_exception&) {
    throw;  // (pybind11's own: its translator)
  } catch (const py::error_already_set&) {
    throw;
  } catch (const std::exception& e) {
    PyErr_SetString(g_error, (std::string("internal error: ") + e.what()).c_str());  // (clrt's exit status 3)
  }
}

// ---- messages of the layers below ----------------------------------------------
// Warnings and --verbose lines are queued (they come from any thread) and
// given to Python when the call returns: warnings.warn (clrt.Warning), the
// rest to sys.stderr, where a notebook shows them.
PyObject* g_warning = nullptr;
std::mutex g_log_mutex;
std::vector<std::pair<LogLevel, std::string>> g_log;

void queue_log(LogLevel level, const std::string& message) {
  std::lock_guard<std::mutex> lock(g_log_mutex);
  g_log.emplace_back(level, message);
}

// With the GIL held.
void flush_log() {
  std::vector<std::pair<LogLevel, std::string>> messages;
  {
    std::lock_guard<std::mutex> lock(g_log_mutex);
    messages.swap(g_log);
  }
  for (const auto& [level, message] : messages) {
    if (level == LogLevel::Warning) {
      if (PyErr_WarnEx(g_warning, message.c_str(), 1) != 0) throw py::error_already_set();
    } else {
      py::module_::import("sys").attr("stderr").attr("write")("clrt: " + message + "\n");
    }
  }
}

// ---- work without the GIL, stopped by Ctrl-C --------------------------------------
// Runs work(cancel) on a thread of its own with the GIL released; the
// calling thread checks for signals every 20 ms. When a signal's handler
// raises (SIGINT: KeyboardInterrupt), `cancel` turns true, the work stops at
// its next check, and that exception is raised here; otherwise the work's
// result or exception.
template <class Result>
Result run_released(const std::function<Result(const CancelFn&)>& work) {
  auto stop = std::make_shared<std::atomic<bool>>(false);
  const CancelFn cancel = [stop] { return stop->load(std::memory_order_relaxed); };
  std::packaged_task<Result()> task([&] { return work(cancel); });
  std::future<Result> done = task.get_future();
  bool interrupted = false;
  {
    py::gil_scoped_release release;
    std::thread worker(std::move(task));
    while (done.wait_for(std::chrono::milliseconds(20)) != std::future_status::ready) {
      if (interrupted) continue;
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) {  // the handler's exception is now set
        interrupted = true;
        stop->store(true);
      }
    }
    worker.join();
  }
  if (interrupted) {
    {
      py::error_scope keep;  // (the signal's exception, while the log is flushed)
      try {
        flush_log();
      } catch (const py::error_already_set&) {
      }
    }
    throw py::error_already_set();
  }
  try {
    Result r = done.get();
    flush_log();
    return r;
  } catch (...) {
    flush_log();
    throw;
  }
}

// ---- arguments ------------------------------------------------------------------
// Keyword arguments into the command line's option structs: one name per
// option, as in the guide; the checks and messages are the structs' own.
template <class T>
T arg_as(const py::handle& value, const std::string& name, const char* type_name) {
  try {
    return value.cast<T>();
  } catch (const py::cast_error&) {
    throw UserError(name + ": expected " + type_name + " (got " +
                    std::string(py::str(py::type::handle_of(value).attr("__name__"))) + ")");
  }
}

int int_arg(const py::handle& v, const std::string& name) {
  if (py::isinstance<py::bool_>(v) || !py::isinstance<py::int_>(v))
    throw UserError(name + ": expected int (got " + std::string(py::str(py::type::handle_of(v).attr("__name__"))) + ")");
  return arg_as<int>(v, name, "int");
}
double float_arg(const py::handle& v, const std::string& name) {
  if (py::isinstance<py::bool_>(v)) throw UserError(name + ": expected a number (got bool)");
  return arg_as<double>(v, name, "a number");
}
bool bool_arg(const py::handle& v, const std::string& name) {
  if (!py::isinstance<py::bool_>(v)) throw UserError(name + ": expected True or False");
  return v.cast<bool>();
}
std::string str_arg(const py::handle& v, const std::string& name) {
  if (!py::isinstance<py::str>(v)) throw UserError(name + ": expected str");
  return v.cast<std::string>();
}

// --depth's range (None, the scene's, is the caller's).
int depth_arg(const py::handle& v) {
  const int depth = int_arg(v, "depth");
  if (depth < 0 || depth > CLRT_MAX_DEPTH)
    throw UserError("--depth must be in [0, " + std::to_string(CLRT_MAX_DEPTH) + "] (got " + std::to_string(depth) +
                    ")");
  return depth;
}

// The options each call takes (besides its positional ones).
const std::vector<std::string> kImageArgs = {"depth", "spp", "adaptive", "subsample", "aspect", "ray_cut", "ray_budget"};
const std::vector<std::string> kDeviceKernelArgs = {"device", "precision", "lanes", "accel", "specialize", "ftz",
                                                    "cache", "verbose", "kernel_dir", "cl_options"};
const std::vector<std::string> kLaunchArgs = {"local", "band_rows", "max_launch_ms"};

std::vector<std::string> join(std::initializer_list<std::vector<std::string>> lists) {
  std::vector<std::string> out;
  for (const auto& l : lists) out.insert(out.end(), l.begin(), l.end());
  return out;
}

// Fills `o` from `kwargs` (those of `allowed`; the others are the caller's,
// `own`); UserError for any other name, with a suggestion.
void apply_options(RenderOptions& o, const py::kwargs& kwargs, const std::vector<std::string>& allowed,
                   const std::vector<std::string>& own = {}) {
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    if (std::find(own.begin(), own.end(), name) != own.end()) continue;
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
      const std::string near = closest_match(name, join({allowed, own}));
      throw UserError("unexpected argument '" + name + "'" + (near.empty() ? "" : "; did you mean '" + near + "'?"));
    }
    const bool none = value.is_none();
    if (name == "depth") {
      o.image.depth = none ? ImageOptions::kSceneDepth : depth_arg(value);
    } else if (name == "spp") {
      o.image.spp = int_arg(value, name);
    } else if (name == "adaptive") {
      o.image.adaptive = none ? -1 : float_arg(value, name);
      if (!none && !(o.image.adaptive >= 0 && o.image.adaptive <= 1e6))
        throw UserError("--adaptive must be in [0, 1e6] (got " + std::string(py::str(value)) + ")");
    } else if (name == "subsample") {
      const std::string mode = none ? "off" : str_arg(value, name);
      if (mode == "off")
        o.image.subsample = Subsample::Off;
      else if (mode == "shade")
        o.image.subsample = Subsample::Shade;
      else if (mode == "interpolate")
        o.image.subsample = Subsample::Interpolate;
      else
        throw UserError("--subsample: expected shade or interpolate (got \"" + mode + "\")");
    } else if (name == "aspect") {
      o.image.aspect = none ? "" : str_arg(value, name);
      if (!o.image.aspect.empty() && o.image.aspect != "viewport" && o.image.aspect != "image")
        throw UserError("--aspect: expected viewport or image (got \"" + o.image.aspect + "\")");
    } else if (name == "ray_cut") {
      o.image.no_ray_cut = !bool_arg(value, name);
    } else if (name == "ray_budget") {
      o.image.ray_budget = none ? kRayBudget : float_arg(value, name);
      if (!(o.image.ray_budget >= 1 && o.image.ray_budget <= 1e300))
        throw UserError("--ray-budget must be in [1, 1e300] (got " + std::string(py::str(value)) + ")");
    } else if (name == "device") {
      o.device.device = none ? "" : py::isinstance<py::int_>(value) ? std::to_string(int_arg(value, name))
                                                                     : str_arg(value, name);
    } else if (name == "precision") {
      o.kernel.precision = str_arg(value, name);
    } else if (name == "lanes") {
      o.kernel.lanes = none ? 0 : int_arg(value, name);
    } else if (name == "accel") {
      o.kernel.accel = str_arg(value, name);
    } else if (name == "specialize") {
      o.kernel.no_specialize = !bool_arg(value, name);
    } else if (name == "ftz") {
      o.kernel.no_ftz = !bool_arg(value, name);
    } else if (name == "cache") {
      o.kernel.no_cache = !bool_arg(value, name);
    } else if (name == "verbose") {
      o.kernel.verbose = bool_arg(value, name);
    } else if (name == "kernel_dir") {
      o.kernel.kernel_dir = none ? "" : str_arg(value, name);
    } else if (name == "cl_options") {
      o.kernel.cl_options = none ? "" : str_arg(value, name);
    } else if (name == "local") {
      if (none)
        o.launch.local_size.clear();
      else if (py::isinstance<py::tuple>(value) && py::len(value) == 2)
        o.launch.local_size = std::to_string(int_arg(value[py::int_(0)], name)) + "x" +
                              std::to_string(int_arg(value[py::int_(1)], name));
      else
        o.launch.local_size = str_arg(value, name);
    } else if (name == "band_rows") {
      o.launch.band_rows = int_arg(value, name);
    } else if (name == "max_launch_ms") {
      o.launch.max_launch_ms = none ? -1 : float_arg(value, name);
    }
  }
}

// ---- scenes ---------------------------------------------------------------------
// A parsed scene as its file says (not yet fitted to an image size), and its
// name: the path it was loaded from, or the name given to from_dict.
struct PyScene {
  std::shared_ptr<const Scene> scene;
  std::string name;
  bool from_file = false;
};

PyScene load_scene_file(const std::string& path) {
  PyScene s;
  s.name = path;
  s.from_file = true;
  s.scene = run_released<std::shared_ptr<const Scene>>([&](const CancelFn&) {
    try {
      return std::make_shared<const Scene>(load_scene(path));
    } catch (const UserError& e) {
      throw SceneError(e.what());
    }
  });
  return s;
}

PyScene parse_scene_text(const std::string& text, const std::string& name) {
  PyScene s;
  s.name = name;
  try {
    s.scene = std::make_shared<const Scene>(parse_scene(text, name));
  } catch (const UserError& e) {
    throw SceneError(e.what());
  }
  return s;
}

// A Scene, or a path to load one from.
PyScene scene_arg(const py::handle& value) {
  if (py::isinstance<PyScene>(value)) return value.cast<PyScene>();
  if (py::isinstance<py::str>(value)) return load_scene_file(value.cast<std::string>());
  if (py::hasattr(value, "__fspath__")) return load_scene_file(py::str(value.attr("__fspath__")()));
  throw UserError("scene: expected a clrt.Scene or a path (got " +
                  std::string(py::str(py::type::handle_of(value).attr("__name__"))) + ")");
}

std::string scene_repr(const PyScene& s) {
  const Scene& sc = *s.scene;
  std::string r = "<clrt.Scene '" + s.name + "': " + std::to_string(sc.spheres.size()) + " spheres, " +
                  std::to_string(sc.lights.size()) + " lights";
  if (!sc.planes.empty()) r += ", " + std::to_string(sc.planes.size()) + " planes";
  if (!sc.triangles.empty()) r += ", " + std::to_string(sc.triangles.size()) + " triangles";
  return r + ", depth " + std::to_string(sc.recursion_depth) + ">";
}

// ---- images ---------------------------------------------------------------------
using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// The memory of a renderer's arrays that Python has dropped, for its next
// frames: a frame into memory already touched takes no page faults and no
// zeroing (a fresh 4 MB buffer took 2-5 ms at 600x600 on the 2-core machine).
struct BufferPool {
  static constexpr size_t kKept = 2;
  std::mutex mutex;
  std::vector<std::vector<float>> free;

  // A buffer of n floats, or an empty one.
  std::vector<float> take(size_t n) {
    std::lock_guard<std::mutex> lock(mutex);
    for (auto it = free.begin(); it != free.end(); ++it)
      if (it->size() == n) {
        std::vector<float> v = std::move(*it);
        free.erase(it);
        return v;
      }
    return {};
  }
  void give(std::vector<float>&& v) {
    std::lock_guard<std::mutex> lock(mutex);
    if (free.size() < kKept) free.push_back(std::move(v));
  }
};

// An empty Unit frame of this size, in a buffer from `pool` where it has one.
Image unit_frame(int width, int height, BufferPool* pool) {
  const size_t n = size_t(width) * height * 3;
  std::vector<float> memory = pool ? pool->take(n) : std::vector<float>{};
  if (memory.size() != n) return Image(width, height, FrameContents{PixelFormat::Unit, false});
  Image img;
  img.width = width, img.height = height, img.contents = FrameContents{PixelFormat::Unit, false};
  img.unit = std::move(memory);
  return img;
}

// A Unit frame's colour as an (H, W, 3) float32 array that owns it (no
// copy: the frame's buffer moves into the array), given back to `pool`
// (when it still exists) once Python drops the array.
py::array_t<float> unit_array(Image& img, const std::shared_ptr<BufferPool>& pool = nullptr) {
  struct Owned {
    std::vector<float> data;
    std::weak_ptr<BufferPool> pool;
  };
  auto* owned = new Owned{std::move(img.unit), pool};
  img.unit.clear();
  py::capsule free_when_done(owned, [](void* p) {
    auto* o = static_cast<Owned*>(p);
    if (auto keep = o->pool.lock()) keep->give(std::move(o->data));
    delete o;
  });
  return py::array_t<float>({py::ssize_t(img.height), py::ssize_t(img.width), py::ssize_t(3)}, owned->data.data(),
                            free_when_done);
}

// An (H, W, 3) array as a Unit image (its values as they are).
Image image_from_array(const FloatArray& a) {
  if (a.ndim() != 3 || a.shape(2) != 3 || a.shape(0) < 1 || a.shape(1) < 1)
    throw UserError("image: expected an array of shape (height, width, 3)");
  if (a.shape(0) > kMaxImageEdge || a.shape(1) > kMaxImageEdge || a.shape(0) * a.shape(1) > kMaxImagePixels)
    throw UserError("image: too large");
  Image img(int(a.shape(1)), int(a.shape(0)), FrameContents{PixelFormat::Unit, false});
  std::copy(a.data(), a.data() + img.unit.size(), img.unit.begin());
  return img;
}

py::array_t<uint8_t> to_uint8(const FloatArray& a) {
  py::array_t<uint8_t> out(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()));
  const float* in = a.data();
  uint8_t* o = out.mutable_data();
  const size_t n = size_t(a.size());
  py::gil_scoped_release release;
  for (size_t i = 0; i < n; ++i) o[i] = to_u8(from_unit(in[i]));
  return out;
}

py::bytes encode_array(const FloatArray& a, const std::string& format) {
  const Image img = image_from_array(a);
  const std::string bytes = run_released<std::string>([&](const CancelFn&) { return encode_image(img, "image", {}, format); });
  return py::bytes(bytes);
}

void save_array(const FloatArray& a, const std::string& path, const std::string& format) {
  const Image img = image_from_array(a);
  run_released<int>([&](const CancelFn&) {
    check_output_format(path, format);
    write_image(img, path, {{"Software", "clrt " + clrt_version() + " (Python)"}}, format);
    return 0;
  });
}

// The options of a call on `scene` at width x height (the rest from its
// keyword arguments: apply_options).
RenderOptions options_for(const PyScene& scene, int width, int height) {
  RenderOptions o;
  o.scene_path = scene.name;
  o.image.width = width;
  o.image.height = height;
  return o;
}

// What an Image's info says of every frame.
py::dict frame_info(const RenderOptions& o, int depth, const std::string& device, double frame_ms) {
  py::dict info;
  info["scene"] = o.scene_path;
  info["width"] = o.image.width;
  info["height"] = o.image.height;
  info["depth"] = depth;
  info["spp"] = o.image.spp;
  info["device"] = device;
  info["frame_ms"] = frame_ms;
  return info;
}

// aovs=: "depth,normal", or a list or tuple of names, or None (no layers);
// the layer bits (UserError as --aov's, "aovs: ..."). 
unsigned layers_arg(const py::handle& value) {
  if (value.is_none()) return 0;
  std::string list;
  if (py::isinstance<py::str>(value)) {
    list = str_arg(value, "aovs");
  } else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    for (const py::handle item : value) list += (list.empty() ? "" : ",") + str_arg(item, "aovs");
  } else {
    throw UserError("aovs: expected a comma-separated str or a list of layer names");
  }
  try {
    return parse_layers(list);
  } catch (const UserError& e) {
    throw UserError(std::string("--aov: ") + e.what());  // (the command line's message)
  }
}

// A frame's layers as {name: array}: "depth" (H, W) float32, "normal" and
// "albedo" (H, W, 3) float32, "id" (H, W) int32 (image/layers.hpp).
py::dict layer_arrays(const FrameLayers& f) {
  py::dict out;
  const py::ssize_t h = f.height, w = f.width;
  const auto copy = [](const auto& v, std::vector<py::ssize_t> shape) {
    using T = typename std::decay_t<decltype(v)>::value_type;
    py::array_t<T> a(shape);
    std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
  };
  if (f.layers & kLayerDepth) out["depth"] = copy(f.depth, {h, w});
  if (f.layers & kLayerNormal) out["normal"] = copy(f.normal, {h, w, 3});
  if (f.layers & kLayerAlbedo) out["albedo"] = copy(f.albedo, {h, w, 3});
  if (f.layers & kLayerId) out["id"] = copy(f.id, {h, w});
  return out;
}

// ---- the renderer -----------------------------------------------------------------
// One scene at one size on its devices: the programs and scene buffers are
// kept between frames (Renderer::prepare once per depth).
class PyRenderer {
 public:
  PyRenderer(const py::object& scene, int width, int height, const py::kwargs& kwargs) {
    scene_ = scene_arg(scene);
    o_ = options_for(scene_, width, height);
    apply_options(o_, kwargs, join({kImageArgs, kDeviceKernelArgs, kLaunchArgs}), {"aovs"});
    if (kwargs.contains("aovs")) layers_ = layers_arg(kwargs["aovs"]);
    o_.validate();
    fitted_ = o_.image.fit_scene(*scene_.scene, scene_.name);
    check_layers_fit(fitted_, layers_);
    flush_log();
    RenderSettings settings = o_.settings();
    // Colour on the float files' scale, stored so by the renderer (no pass
    // over the frame after it), and the AOV layers of aovs=.
    settings.kernel.output = FrameContents{PixelFormat::Unit, /*classes=*/false, uint8_t(layers_)};
    // The frame's stop, asked between bands (frame_cancel_: set for one
    // frame at a time, under mutex_).
    settings.cancel = [this] { return frame_cancel_ && frame_cancel_(); };
    run_released<int>([&](const CancelFn&) {
      renderer_ = std::make_unique<Renderer>(o_.device.devices(), settings);
      return 0;
    });
  }
  PyRenderer(const PyRenderer&) = delete;
  PyRenderer& operator=(const PyRenderer&) = delete;

  // Builds (or loads) the program for `depth` and uploads the scene, unless
  // done for it already: what render() does first at a new depth.
  py::dict prepare(const py::object& depth_in) {
    const int depth = depth_of(depth_in);
    run_released<int>([&](const CancelFn&) {
      std::lock_guard<std::mutex> lock(mutex_);
      prepare_locked(depth);
      return 0;
    });
    py::dict info;
    info["depth"] = depth;
    info["build_ms"] = last_build_ms_;
    info["build_cached"] = last_build_cached_;
    info["build_options"] = renderer_->options();
    return info;
  }

  // The frame at `depth` (None: the constructor's, else the scene's).
  py::tuple render(const py::object& depth_in) {
    const int depth = depth_of(depth_in);
    Image frame = unit_frame(o_.image.width, o_.image.height, pool_.get());
    FrameLayers layers;
    const FrameStats stats = run_released<FrameStats>([&](const CancelFn& cancel) {
      std::lock_guard<std::mutex> lock(mutex_);  // (one frame at a time per renderer)
      prepare_locked(depth);
      frame_cancel_ = cancel;
      struct Reset {
        CancelFn& c;
        ~Reset() { c = nullptr; }
      } reset{frame_cancel_};
      renderer_->render_into(frame);
      if (layers_) layers = renderer_->layers();
      return renderer_->stats();
    });
    py::dict info = frame_info(o_, depth, renderer_->device_names(), stats.wall_ms);
    info["precision"] = o_.kernel.precision;
    info["kernel_ms"] = stats.kernel_ms;
    info["launches"] = stats.launches;
    info["build_ms"] = last_build_ms_;
    info["build_cached"] = last_build_cached_;
    if (layers_) info["aovs"] = layer_list(layers_);
    return py::make_tuple(unit_array(frame, pool_), info, layer_arrays(layers));
  }

  std::string device() const { return renderer_->device_names(); }
  std::string build_options() const { return renderer_->options(); }
  int width() const { return o_.image.width; }
  int height() const { return o_.image.height; }
  const PyScene& scene() const { return scene_; }

 private:
  int depth_of(const py::object& depth_in) const {
    return depth_in.is_none() ? o_.image.effective_depth(fitted_) : depth_arg(depth_in);
  }
  // (with mutex_ held)
  void prepare_locked(int depth) {
    if (depth == prepared_depth_) return;
    prepared_depth_ = -1;
    renderer_->prepare(fitted_, o_.image.width, o_.image.height, depth, o_.image.sampling());
    prepared_depth_ = depth;
    last_build_ms_ = renderer_->stats().build_ms;
    last_build_cached_ = renderer_->stats().build_cached;
  }

  PyScene scene_;
  RenderOptions o_;
  Scene fitted_;
  std::unique_ptr<Renderer> renderer_;
  std::mutex mutex_;
  std::shared_ptr<BufferPool> pool_ = std::make_shared<BufferPool>();
  unsigned layers_ = 0;  // aovs=
  int prepared_depth_ = -1;
  double last_build_ms_ = 0;
  bool last_build_cached_ = false;
  CancelFn frame_cancel_;
};

// ---- the functions ------------------------------------------------------------------
py::tuple reference(const py::object& scene_in, int width, int height, const py::kwargs& kwargs) {
  const PyScene scene = scene_arg(scene_in);
  RenderOptions o = options_for(scene, width, height);
  apply_options(o, kwargs, kImageArgs);
  o.image.validate();
  const Scene fitted = o.image.fit_scene(*scene.scene, scene.name);
  flush_log();
  const int depth = o.image.effective_depth(fitted);
  Image frame = unit_frame(width, height, nullptr);
  const double ms = run_released<double>([&](const CancelFn& cancel) {
    const auto t0 = Clock::now();
    const Image img = render_reference(fitted, width, height, depth, o.image.sampling(), cancel);
    const double wall = ms_since(t0);
    for (size_t i = 0; i < img.rgb.size(); ++i) frame.unit[i] = to_unit(img.rgb[i]);
    return wall;
  });
  return py::make_tuple(unit_array(frame), frame_info(o, depth, "host (scalar double)", ms));
}

py::object compare(const py::object& scene_in, int width, int height, const py::kwargs& kwargs) {
  const PyScene scene = scene_arg(scene_in);
  RenderOptions o = options_for(scene, width, height);
  const std::vector<std::string> own = {"image", "fail_percent", "fail_max"};
  apply_options(o, kwargs, join({kImageArgs, kDeviceKernelArgs, kLaunchArgs}), own);
  Thresholds limits;
  std::string image_path;
  if (kwargs.contains("image") && !kwargs["image"].is_none()) image_path = str_arg(kwargs["image"], "image");
  if (kwargs.contains("fail_percent") && !kwargs["fail_percent"].is_none()) {
    limits.fail_percent = float_arg(kwargs["fail_percent"], "fail_percent");
    if (!(limits.fail_percent >= 0 && limits.fail_percent <= 100))
      throw UserError("--fail-percent must be in [0, 100]");
  }
  if (kwargs.contains("fail_max") && !kwargs["fail_max"].is_none()) {
    limits.fail_max = int_arg(kwargs["fail_max"], "fail_max");
    if (limits.fail_max < 0 || limits.fail_max > 255) throw UserError("--fail-max must be in [0, 255]");
  }
  const std::string text = run_released<std::string>([&](const CancelFn& cancel) {
    RenderOptions opts = o;
    Image img;
    if (!image_path.empty()) {  // its size sets the image's (as --image does)
      img = read_image(image_path, kMaxImageEdge, kMaxImagePixels);
      opts.image.width = img.width;
      opts.image.height = img.height;
    }
    opts.validate();
    const Scene fitted = opts.image.fit_scene(*scene.scene, scene.name);
    const int depth = opts.image.effective_depth(fitted);
    const CompareRun run =
        run_compare(fitted, opts, depth, limits, image_path.empty() ? nullptr : &img, image_path, cancel);
    return json_text(compare_json(run, opts));
  });
  return py::module_::import("json").attr("loads")(text);
}

std::string depths_arg(const py::handle& v) {
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (py::isinstance<py::int_>(v) && !py::isinstance<py::bool_>(v)) return std::to_string(v.cast<int>());
  if (py::isinstance(v, py::module_::import("builtins").attr("range"))) {
    const int start = v.attr("start").cast<int>(), stop = v.attr("stop").cast<int>(), step = v.attr("step").cast<int>();
    if (step != 1 || stop <= start) throw UserError("depths: a range needs step 1 and at least one depth");
    return std::to_string(start) + ":" + std::to_string(stop - 1);
  }
  if ((py::isinstance<py::tuple>(v) || py::isinstance<py::list>(v)) && py::len(v) == 2)
    return std::to_string(int_arg(v[py::int_(0)], "depths")) + ":" + std::to_string(int_arg(v[py::int_(1)], "depths"));
  throw UserError("depths: expected \"A:B\", N, (A, B) or range(A, B + 1)");
}

py::object sweep(const py::object& scene_in, int width, int height, const py::kwargs& kwargs) {
  const PyScene scene = scene_arg(scene_in);
  RenderOptions o = options_for(scene, width, height);
  const std::vector<std::string> own = {"depths", "devices", "repeat", "omp"};
  std::vector<std::string> allowed = join({kImageArgs, kDeviceKernelArgs, kLaunchArgs});
  allowed.erase(std::find(allowed.begin(), allowed.end(), "depth"));
  apply_options(o, kwargs, allowed, own);
  const std::string depths = kwargs.contains("depths") ? depths_arg(kwargs["depths"]) : "0:10";
  std::string devices;
  if (kwargs.contains("devices") && !kwargs["devices"].is_none())
    devices = py::isinstance<py::int_>(kwargs["devices"]) ? std::to_string(int_arg(kwargs["devices"], "devices"))
                                                          : str_arg(kwargs["devices"], "devices");
  int repeat = 3;
  if (kwargs.contains("repeat")) repeat = int_arg(kwargs["repeat"], "repeat");
  if (repeat < 1 || repeat > kMaxRepeat)
    throw UserError("--repeat must be in [1, " + std::to_string(kMaxRepeat) + "] (got " + std::to_string(repeat) + ")");
  const bool omp = kwargs.contains("omp") && bool_arg(kwargs["omp"], "omp");
  o.validate();
  SweepSettings s = sweep_settings(o, repeat, omp);
  parse_depth_range(depths, s.depth_from, s.depth_to);
  const Scene fitted = o.image.fit_scene(*scene.scene, scene.name);
  flush_log();
  const std::string text = run_released<std::string>([&](const CancelFn& cancel) {
    SweepSettings settings = s;
    settings.progress = [cancel](int, int, const std::string&) {
      if (cancel()) throw Cancelled("sweep cancelled");
    };
    RenderSettings render = o.settings();
    render.cancel = cancel;
    const auto devs = select_devices(devices.empty() ? o.device.device : devices);
    return json_text(sweep_json(run_sweep(fitted, devs, render, settings), scene.name, overrides_json({})));
  });
  return py::module_::import("json").attr("loads")(text);
}

py::object accuracy(const py::object& scenes_in, int width, int height, const py::kwargs& kwargs) {
  std::vector<PyScene> scenes;
  if (py::isinstance<py::list>(scenes_in) || py::isinstance<py::tuple>(scenes_in)) {
    for (const auto& s : scenes_in) scenes.push_back(scene_arg(s));
  } else {
    scenes.push_back(scene_arg(scenes_in));
  }
  if (scenes.empty()) throw UserError("scenes: empty list");
  AccuracyOptions a;
  a.image.width = width;
  a.image.height = height;
  RenderOptions o;  // (the options accuracy shares with the others)
  o.image = a.image;
  const std::vector<std::string> own = {"repeat", "variants"};
  const std::vector<std::string> allowed = {"depth",      "spp",   "adaptive", "aspect",  "device",
                                            "accel",      "specialize", "ftz",   "cache", "verbose",
                                            "kernel_dir", "cl_options"};
  apply_options(o, kwargs, allowed, own);
  a.image = o.image;
  a.device = o.device;
  a.kernel = o.kernel;
  if (kwargs.contains("repeat")) a.repeat = int_arg(kwargs["repeat"], "repeat");
  if (a.repeat < 1 || a.repeat > kMaxRepeat)
    throw UserError("--repeat must be in [1, " + std::to_string(kMaxRepeat) + "] (got " + std::to_string(a.repeat) +
                    ")");
  if (kwargs.contains("variants") && !kwargs["variants"].is_none()) {
    const py::object v = kwargs["variants"];
    if (py::isinstance<py::str>(v)) {
      a.variants = v.cast<std::string>();
    } else {
      a.variants.clear();
      for (const auto& name : v) a.variants += (a.variants.empty() ? "" : ",") + str_arg(name, "variants");
    }
  }
  a.check();
  AccuracySettings s = a.settings();
  std::vector<NamedScene> named;
  for (const PyScene& sc : scenes) named.push_back({sc.name, a.image.fit_scene(*sc.scene, sc.name)});
  flush_log();
  const std::string text = run_released<std::string>([&](const CancelFn& cancel) {
    AccuracySettings settings = s;
    settings.progress = [cancel](int, int, const std::string&) {
      if (cancel()) throw Cancelled("accuracy cancelled");
    };
    const DeviceInfo dev = a.device.one();
    return accuracy_json(measure_accuracy(named, dev, settings), settings, dev.name, {});
  });
  return py::module_::import("json").attr("loads")(text);
}

py::object devices(bool check, const std::string& precision) {
  const std::string text = run_released<std::string>(
      [&](const CancelFn& cancel) { return json_text(devices_json(check, precision, nullptr, cancel)); });
  return py::module_::import("json").attr("loads")(text);
}

// The folder of this extension's file, for the imaging module's lookup.
std::string extension_dir() {
  Dl_info info{};
  if (!::dladdr(reinterpret_cast<void*>(&extension_dir), &info) || !info.dli_fname) return "";
  std::error_code ec;
  const std::filesystem::path file = std::filesystem::canonical(info.dli_fname, ec);
  return ec ? std::string() : file.parent_path().string();
}

}  // namespace
}  // namespace clrt

PYBIND11_MODULE(_clrt, m) {
  using namespace clrt;
  m.doc() = "clrt: the OpenCL Whitted ray tracer and its double-precision reference (docs/guide/python.md)";
  m.attr("__version__") = clrt_version();

  g_error = new_exception(m, "Error", py::make_tuple(py::handle(PyExc_RuntimeError)),
                          "A clrt error: the message is the command line's.");
  g_usage_error = new_exception(m, "UsageError", py::make_tuple(py::handle(g_error), py::handle(PyExc_ValueError)),
                                "Bad input: an option, a path, an image (clrt's exit status 2).");
  g_scene_error = new_exception(m, "SceneError", py::make_tuple(py::handle(g_usage_error)),
                                "A scene that cannot be read: the parser's message, naming the file and key.");
  g_device_error = new_exception(m, "DeviceError", py::make_tuple(py::handle(g_error)),
                                 "The OpenCL runtime or a device failed (no platform, a build failure, ...).");
  {
    PyObject* w = PyErr_NewExceptionWithDoc("clrt.Warning", "A warning of clrt's (pixels not square, a long render, ...)",
                                            PyExc_UserWarning, nullptr);
    if (!w) throw py::error_already_set();
    m.add_object("Warning", py::handle(w));
    g_warning = w;
  }
  py::register_exception_translator(&translate);

  set_log_sink(&queue_log);
  imageio::set_library_location(extension_dir(), CLRT_IMAGEIO_FROM_PYTHON);

  py::class_<PyScene>(m, "Scene", "A scene, as its JSON file gives it (docs/reference/scene-format.md)")
      .def_static("load", &load_scene_file, py::arg("path"), "Reads a scene file (JSON); SceneError as clrt says it.")
      .def_static(
          "from_json", [](const std::string& text, const std::string& name) { return parse_scene_text(text, name); },
          py::arg("text"), py::arg("name") = "<json>", "Parses scene JSON text; `name` names it in messages.")
      .def_static(
          "from_dict",
          [](const py::object& d, const std::string& name) {
            if (!py::isinstance<py::dict>(d)) throw SceneError(name + ": expected a dict");
            const std::string text = py::str(py::module_::import("json").attr("dumps")(d));
            return parse_scene_text(text, name);
          },
          py::arg("d"), py::arg("name") = "<dict>",
          "A scene from a dict as the JSON file holds it, through the same parser and its checks.")
      .def("to_dict", [](const PyScene& s) { return py::module_::import("json").attr("loads")(scene_to_json(*s.scene)); },
           "The scene as a dict of its JSON form (meshes as their triangles).")
      .def("to_json", [](const PyScene& s) { return scene_to_json(*s.scene); })
      .def_property_readonly("name", [](const PyScene& s) { return s.name; })
      .def_property_readonly("path",
                             [](const PyScene& s) { return s.from_file ? py::object(py::str(s.name)) : py::none(); })
      .def_property_readonly("spheres", [](const PyScene& s) { return s.scene->spheres.size(); })
      .def_property_readonly("lights", [](const PyScene& s) { return s.scene->lights.size(); })
      .def_property_readonly("planes", [](const PyScene& s) { return s.scene->planes.size(); })
      .def_property_readonly("triangles", [](const PyScene& s) { return s.scene->triangles.size(); })
      .def_property_readonly("recursion_depth", [](const PyScene& s) { return s.scene->recursion_depth; })
      .def("__repr__", &scene_repr);

  py::class_<PyRenderer>(m, "_Renderer")
      .def(py::init<const py::object&, int, int, const py::kwargs&>(), py::arg("scene"), py::arg("width") = 600,
           py::arg("height") = 600)
      .def("_render", &PyRenderer::render, py::arg("depth") = py::none())
      .def("prepare", &PyRenderer::prepare, py::arg("depth") = py::none(),
           "Builds (or loads from the program cache) the program for `depth` and uploads the scene, as render() "
           "does first at a new depth; returns build_ms, build_cached and build_options.")
      .def_property_readonly("device", &PyRenderer::device)
      .def_property_readonly("build_options", &PyRenderer::build_options)
      .def_property_readonly("width", &PyRenderer::width)
      .def_property_readonly("height", &PyRenderer::height)
      .def_property_readonly("scene", &PyRenderer::scene);

  m.def("_reference", &reference, py::arg("scene"), py::arg("width") = 600, py::arg("height") = 600);
  m.def("compare", &compare, py::arg("scene"), py::arg("width") = 600, py::arg("height") = 600,
        "OpenCL (or the image file `image`) against the reference: `clrt compare --json`'s dict.");
  m.def("sweep", &sweep, py::arg("scene"), py::arg("width") = 600, py::arg("height") = 600,
        "Bench figures and error per depth (and device): `clrt sweep --json`'s dict.");
  m.def("accuracy", &accuracy, py::arg("scenes"), py::arg("width") = 600, py::arg("height") = 600,
        "Kernel time against error per precision variant: `clrt accuracy --json`'s dict.");
  m.def("devices", &devices, py::kw_only(), py::arg("check") = false, py::arg("precision") = "robust",
        "Every OpenCL device (and with check=True its self-test): `clrt devices --json`'s dict.");
  m.def("to_uint8", &to_uint8, py::arg("image"),
        "8-bit values by the canvas rule (clamp, round half to even, NaN to 0), as clrt's 8-bit files hold them.");
  m.def("_encode", &encode_array, py::arg("image"), py::arg("format") = "png");
  m.def("_save", &save_array, py::arg("image"), py::arg("path"), py::arg("format") = "");
}
