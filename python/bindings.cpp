// The compiled part of the Python module (`caligo._caligo`): the scene parser, the path
// tracer, the real-time pipeline and the EXR reader and writer, with numpy arrays out. The
// Python side (caligo/__init__.py) merges keyword settings into the scene's JSON and names
// the public functions; this file is the only one that includes pybind11.
//
// Rendering releases the GIL and runs on a thread of its own while the calling thread waits in
// short slices, taking the GIL back each time to run Python's signal handlers (Ctrl-C raises
// KeyboardInterrupt there) and the progress callback. An interrupt or an exception from the
// callback stops the render between pixels and joins its threads before it propagates.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include "core/error.h"
#include "image/compare.h"
#include "image/exr_io.h"
#include "layers.h"
#include "realtime/pipeline.h"
#include "realtime/reference_compare.h"
#include "render/progressive.h"
#include "render/render.h"
#include "scene/builtins.h"
#include "scene/pbrt_import.h"
#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace py = pybind11;

namespace caligo::python {
namespace {

// A parsed scene and the text it came from (the Python side re-parses the text with keyword
// settings merged in).
struct ParsedScene {
  SceneDesc desc;
  std::string text, label, base_dir;
};

ParsedScene parse_text(const std::string& text, const std::string& label, const std::string& base_dir) {
  return {parse_scene_text(text, label, base_dir), text, label, base_dir};
}

// A built-in's name or a scene file's path.
ParsedScene parse_named(const std::string& name) {
  if (const BuiltinScene* builtin = find_builtin(name)) return parse_text(builtin->json, "builtin:" + name, ".");
  if (is_pbrt_path(name) && std::filesystem::is_regular_file(name)) {
    PbrtConversion converted = convert_pbrt_file(name);
    const std::string dir = std::filesystem::path(name).parent_path().string();
    SceneDesc desc = parse_pbrt(converted, name, dir);
    return {std::move(desc), std::move(converted.json), name, dir};
  }
  SceneDesc desc = parse_scene_file(name);  // every check of the command line's reading
  std::ifstream in(name, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return {std::move(desc), text.str(), name, std::filesystem::path(name).parent_path().string()};
}

void check_resolution(Vec2i r, const std::string& file) {
  constexpr uint64_t kMaxPixels = uint64_t(1) << 26;  // as the command line allows
  if (uint64_t(r.x) * uint64_t(r.y) > kMaxPixels)
    throw InputError(SourceLocation{file, "/camera/resolution"},
                     std::to_string(r.x) + "x" + std::to_string(r.y) + " has more than 2^26 pixels");
}

py::array to_array(const Layer& layer) {
  const auto h = py::ssize_t(layer.height), w = py::ssize_t(layer.width), c = py::ssize_t(layer.channels.size());
  py::array_t<float> out = c == 1 ? py::array_t<float>({h, w}) : py::array_t<float>({h, w, c});
  std::copy(layer.pixels.begin(), layer.pixels.end(), out.mutable_data());
  return out;
}

py::dict to_dict(const Image& image) {
  py::dict out;
  for (const Layer& layer : split_layers(image)) out[py::str(layer.name)] = to_array(layer);
  return out;
}

Layer from_array(const std::string& name, const py::handle& value) {
  const auto array = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!array) throw InputError(SourceLocation{"python", ""}, "layer " + name + ": expected an array of numbers");
  if (array.ndim() != 2 && array.ndim() != 3)
    throw InputError(SourceLocation{"python", ""},
                     "layer " + name + ": expected an array of shape (height, width) or (height, width, channels)");
  Layer layer;
  layer.name = name;
  layer.height = int(array.shape(0));
  layer.width = int(array.shape(1));
  const int channels = array.ndim() == 3 ? int(array.shape(2)) : 1;
  if (layer.width < 1 || layer.height < 1 || array.shape(0) > 65536 || array.shape(1) > 65536)
    throw InputError(SourceLocation{"python", ""}, "layer " + name + ": each side must be 1 to 65536 pixels");
  layer.channels = channel_names(name, channels);
  layer.pixels.assign(array.data(), array.data() + array.size());
  return layer;
}

// Runs `work` on a thread of its own while this (Python) thread waits with the GIL released,
// waking every 50 ms to run signal handlers and `on_wake`. A Python exception from either stops
// the work through `stop`, waits for it and propagates; the work's own exception propagates.
template <typename Work, typename Wake>
void run_interruptibly(std::atomic<bool>& stop, Work&& work, Wake&& on_wake) {
  std::mutex mutex;
  std::condition_variable done_cv;
  bool done = false;
  std::exception_ptr failure;
  std::thread worker([&] {
    try {
      work();
    } catch (...) {
      failure = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mutex);
    done = true;
    done_cv.notify_all();
  });
  const auto finish = [&] {
    stop = true;
    py::gil_scoped_release release;
    worker.join();
  };
  for (;;) {
    bool finished = false;
    {
      py::gil_scoped_release release;
      std::unique_lock<std::mutex> lock(mutex);
      finished = done_cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; });
    }
    if (finished) break;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      on_wake();
    } catch (...) {
      finish();
      throw;
    }
  }
  {
    py::gil_scoped_release release;
    worker.join();
  }
  if (failure) std::rethrow_exception(failure);
}

py::dict render_scene(const ParsedScene& parsed, int threads, const py::object& progress) {
  RenderSettings settings = render_settings(parsed.desc);
  check_resolution(settings.resolution, parsed.label);
  if (threads < 0 || threads > 1024) throw InputError(SourceLocation{"python", ""}, "threads: expected 0 to 1024");
  settings.threads = threads;
  std::shared_ptr<const Scene> scene;
  {
    py::gil_scoped_release release;
    scene = Scene::build(parsed.desc);  // meshes and grids load here, with their located errors
  }
  Film film(settings.resolution, settings.aovs);
  ProgressiveSchedule schedule;
  std::atomic<int> done{0}, reported{-1};
  ProgressiveHooks hooks;
  if (!progress.is_none()) {
    // Passes make progress visible; the film ends bit for bit as one pass would leave it.
    schedule.checkpoint_every = 0.5;
    hooks.on_pass = [&](int samples, int, double) { done = samples; };
    hooks.save_checkpoint = [](const Film&) {};
  }
  std::atomic<bool> stop{false};
  run_interruptibly(
      stop, [&] { render_progressive(film, *scene, settings, schedule, hooks, &stop); },
      [&] {
        if (progress.is_none() || done == reported) return;
        reported = int(done);
        progress(int(reported), settings.spp);
      });
  if (!progress.is_none() && reported != settings.spp) progress(settings.spp, settings.spp);
  return to_dict(film.resolve());
}

py::dict times_of(const PassTimes& t) {
  py::dict d;
  d["depth"] = t.depth;
  d["shadows"] = t.shadows;
  d["accumulation"] = t.accumulation;
  d["gather"] = t.gather;
  d["upsample"] = t.upsample;
  d["temporal"] = t.temporal;
  d["surfaces"] = t.surfaces;
  d["composite"] = t.composite;
  d["total"] = t.total;
  d["volumetric"] = t.volumetric();
  d["per_light"] = t.per_light;
  return d;
}

py::dict realtime_frames(const ParsedScene& parsed, int frames, const std::string& method) {
  if (frames < 1 || frames > 100000) throw InputError(SourceLocation{"python", ""}, "frames: expected 1 to 100000");
  if (method != "march" && method != "froxel")
    throw InputError(SourceLocation{"python", ""}, "method: expected \"march\" or \"froxel\", got \"" + method + "\"");
  RealtimeSettings settings = realtime_settings(parsed.desc);
  check_resolution(settings.resolution, parsed.label);
  settings.froxel = method == "froxel";
  std::unique_ptr<RealtimePipeline> pipeline;
  {
    py::gil_scoped_release release;
    pipeline = std::make_unique<RealtimePipeline>(Scene::build(parsed.desc), settings);
  }
  py::list images, times;
  for (int i = 0; i < frames; ++i) {
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // between frames
    Image image;
    PassTimes t;
    {
      py::gil_scoped_release release;
      const RealtimeFrame& frame = pipeline->render(float(i) / parsed.desc.realtime.fps, uint32_t(i));
      image = to_image(frame.color);
      t = frame.times;
    }
    images.append(to_dict(image)["beauty"]);
    times.append(times_of(t));
  }
  py::dict out;
  out["frames"] = images;
  out["times"] = times;
  return out;
}

py::dict compare_arrays(const py::handle& a, const py::handle& b) {
  const Image ia = join_layers({from_array("beauty", a)}), ib = join_layers({from_array("beauty", b)});
  ImageMetrics m;
  try {
    m = compare_images(ia, ib);
  } catch (const std::invalid_argument& e) {
    throw InputError(SourceLocation{"python", ""}, e.what());
  }
  py::dict d;
  d["rmse"] = m.rmse;
  d["relative_mse"] = m.relative_mse;
  d["mean_difference"] = m.mean_difference;
  d["max_abs_difference"] = m.max_abs_difference;
  d["pixels"] = m.pixels;
  return d;
}

void write_layers(const std::string& path, const py::dict& layers, bool half) {
  std::vector<Layer> list;
  for (const auto& [key, value] : layers) {
    if (!py::isinstance<py::str>(key)) throw InputError(SourceLocation{"python", ""}, "layer names must be strings");
    list.push_back(from_array(key.cast<std::string>(), value));
  }
  const Image image = join_layers(list);
  py::gil_scoped_release release;
  write_exr(path, image, half);  // written beside and renamed: never a half-written file
}

}  // namespace
}  // namespace caligo::python

PYBIND11_MODULE(_caligo, m) {
  using namespace caligo;
  using namespace caligo::python;
  m.doc() = "Caligo's compiled core; use the caligo package";
  static py::exception<InputError> scene_error(m, "SceneError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      py::object error = py::reinterpret_borrow<py::object>(scene_error.ptr())(py::str(e.what()));
      error.attr("file") = py::str(e.where().file);
      error.attr("json_path") = py::str(e.where().json_path);
      PyErr_SetObject(scene_error.ptr(), error.ptr());
    } catch (const EnvironmentError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    }
  });

  py::class_<ParsedScene>(m, "ParsedScene")
      .def_property_readonly("file", [](const ParsedScene& s) { return s.label; })
      .def_property_readonly("text", [](const ParsedScene& s) { return s.text; })
      .def_property_readonly("base_dir", [](const ParsedScene& s) { return s.base_dir; })
      .def_property_readonly("resolution",
                             [](const ParsedScene& s) { return py::make_tuple(s.desc.camera.resolution.x, s.desc.camera.resolution.y); })
      .def_property_readonly("warnings", [](const ParsedScene& s) { return s.desc.warnings; })
      .def_property_readonly("files", [](const ParsedScene& s) { return s.desc.files; });
  m.def("parse_text", &parse_text, py::arg("text"), py::arg("label"), py::arg("base_dir"));
  m.def("parse_named", &parse_named, py::arg("name"));
  m.def("builtins", [] {
    std::vector<std::pair<std::string, std::string>> out;
    for (const BuiltinScene& b : builtin_scenes()) out.emplace_back(b.name, b.description);
    return out;
  });
  m.def("render", &render_scene, py::arg("scene"), py::arg("threads"), py::arg("progress"));
  m.def("realtime", &realtime_frames, py::arg("scene"), py::arg("frames"), py::arg("method"));
  m.def("compare", &compare_arrays, py::arg("a"), py::arg("b"));
  m.def("read_exr", [](const std::string& path) { return to_dict(read_exr(path)); }, py::arg("path"));
  m.def("write_exr", &write_layers, py::arg("path"), py::arg("layers"), py::arg("half"));
}
