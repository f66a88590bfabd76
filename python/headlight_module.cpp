// The Python module `headlight` (pybind11): a renderer that hands back numpy
// arrays. Settings come from settingOptions(), the table the CLI reads: a
// keyword is a row's name with '-' -> '_', its value is parsed and checked by
// the row exactly as the CLI's --flag would be. docs/EMBEDDING.md has the API.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "headlight/camera.hpp"
#include "headlight/context.hpp"
#include "headlight/error.hpp"
#include "headlight/limits.hpp"
#include "headlight/output.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/settings.hpp"
#include "headlight/targets.hpp"
#include "headlight/version.hpp"

namespace py = pybind11;
using namespace headlight;

namespace {

// A context and the renderer made with it; the renderer goes first.
//
// A Python object may be used from any thread, one call at a time: each call
// takes `inUse` (with the GIL released, so a call on another thread can
// finish), makes the context current on the calling thread and releases it
// again at the end, so that the next call may come from another thread (an
// EGL context current on one thread cannot be made current on another).
struct PyRenderer {
  std::optional<Context> context;
  std::optional<Renderer> renderer;
  std::mutex inUse;
  ResourceLimits limits;

  explicit PyRenderer(const ContextOptions& options) {
    context.emplace(options);
    renderer.emplace(*context);
    context->releaseCurrent();
  }
  ~PyRenderer() {
    // Destruction takes the backend lock (ContextAccess::lockBackend), which a
    // render on another thread may hold while it waits for the GIL: give the
    // GIL up first. ~Renderer makes the context current itself when it is not.
    py::gil_scoped_release release;
    const std::lock_guard<std::mutex> lock(inUse);
    renderer.reset();
    context.reset();
  }

  // Call with the GIL released.
  template <class Work>
  auto onThisThread(Work&& work) {
    const std::lock_guard<std::mutex> lock(inUse);
    struct Release {
      Context& context;
      ~Release() { context.releaseCurrent(); }
    } release{*context};
    context->makeCurrent();
    return work();
  }
};

py::object own(const py::handle& value) { return py::reinterpret_borrow<py::object>(value); }

std::string typeName(const py::handle& value) { return py::str(py::type::of(value).attr("__name__")); }

bool isNumpyBool(const py::handle& value) {
  return py::hasattr(value, "dtype") && py::str(value.attr("dtype").attr("kind")).cast<std::string>() == "b";
}

// Integers and reals as Python's numbers ABCs define them, so numpy's
// scalars (np.int64(64), np.float32(0.5)) count as numbers; bool is not one.
bool isIntegral(const py::handle& value) {
  static const py::object integral = py::module_::import("numbers").attr("Integral");
  return !py::isinstance<py::bool_>(value) && !isNumpyBool(value) && py::isinstance(value, integral);
}
bool isReal(const py::handle& value) {
  static const py::object real = py::module_::import("numbers").attr("Real");
  return !py::isinstance<py::bool_>(value) && !isNumpyBool(value) && py::isinstance(value, real);
}

// Python value -> the text the CLI would get, so the row parses and checks it.
std::string optionText(const OptionSpec& spec, const py::handle& value) {
  if (value.is_none()) return "auto";
  if (py::isinstance<py::bool_>(value) || isNumpyBool(value)) return py::bool_(own(value)) ? "on" : "off";
  if (isIntegral(value)) return py::str(py::int_(own(value))).cast<std::string>();
  if (isReal(value)) return py::repr(py::float_(own(value))).cast<std::string>();  // shortest exact text
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  throw SettingsError(std::string(spec.name) + ": expected a number, bool, str or None (auto), got " + typeName(value),
                      {std::string(spec.name)});
}

// A str argument, or a SettingsError naming `what` and the type given.
std::string textArgument(const py::handle& value, std::string_view what, std::string_view expected) {
  if (py::isinstance<py::str>(value)) {
    std::string text = value.cast<std::string>();
    // No C++ API or file system takes a NUL inside a name, and a message
    // built from it would end there ("builtin:cornell\0x" reported as "builtin:cornell").
    if (text.find('\0') != std::string::npos)
      throw SettingsError(std::string(what) + ": " + py::repr(value).cast<std::string>() + " contains a NUL character",
                          {std::string(what)});
    return text;
  }
  throw SettingsError(std::string(what) + ": expected " + std::string(expected) + ", got " + typeName(value) + " " +
                          py::repr(value).cast<std::string>(),
                      {std::string(what)});
}

// A path: str or os.PathLike.
std::string pathArgument(const py::handle& value, std::string_view what) {
  static const py::object pathLike = py::module_::import("os").attr("PathLike");
  if (py::isinstance(value, pathLike))
    return textArgument(py::str(py::module_::import("os").attr("fspath")(value)), what, "a path (str or os.PathLike)");
  return textArgument(value, what, "a path (str or os.PathLike)");
}

std::string pythonName(std::string_view rowName) {
  std::string name(rowName);
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

// render()'s keywords for an explicit camera, as Renderer::render's Camera
// and job files take one: eye, target and up (a look-at) or a 4x4 world ->
// view matrix, and a vertical field of view in degrees or an orthographic
// view's height in world units.
constexpr std::string_view kCameraKeywords[] = {"eye", "target", "up", "fov", "ortho_size", "view"};
constexpr float kDefaultFovDegrees = 40.0f;  // job files' default

bool isCameraKeyword(std::string_view name) {
  return std::find(std::begin(kCameraKeywords), std::end(kCameraKeywords), name) != std::end(kCameraKeywords);
}

[[noreturn]] void badArgument(const std::string& name, const std::string& expected, const py::handle& value) {
  throw SettingsError(name + ": expected " + expected + ", got " + py::repr(value).cast<std::string>(), {name});
}

// A list of frame target names (targets=, png=): anything else is a
// SettingsError naming the argument and the known targets.
std::vector<std::string> targetNames(const std::string& argument, const py::object& given) {
  if (py::isinstance<py::str>(given) || !py::isinstance<py::sequence>(given))
    badArgument(argument, "a list of target names", given);
  std::vector<std::string> names;
  for (const py::handle& item : given) {
    if (!py::isinstance<py::str>(item)) badArgument(argument, "a list of target names", given);
    const std::string name = item.cast<std::string>();
    if (findFrameTarget(name) == nullptr) {
      std::string known;
      for (const FrameTarget& target : frameTargets())
        if (target.image) (known += known.empty() ? "" : ", ") += target.name;
      throw SettingsError(argument + ": unknown target '" + name + "' (known: " + known + ")", {argument});
    }
    names.push_back(name);
  }
  return names;
}

float finiteNumber(const py::handle& value, const std::string& name, const std::string& expected) {
  if (!isReal(value)) badArgument(name, expected, value);
  const double number = py::float_(own(value));
  if (!std::isfinite(number) || std::abs(number) > kMaxWorldMagnitude) badArgument(name, expected, value);
  return float(number);
}

glm::vec3 vec3Argument(const py::handle& value, const std::string& name) {
  const std::string expected = "3 finite numbers (x, y, z)";
  if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value)) {
    if (!py::hasattr(value, "__len__") || !py::hasattr(value, "__getitem__")) badArgument(name, expected, value);
  }
  if (py::len(value) != 3) badArgument(name, expected, value);
  glm::vec3 v;
  for (int i = 0; i < 3; ++i) v[i] = finiteNumber(value[py::int_(i)], name, expected);
  return v;
}

glm::mat4 matrixArgument(const py::handle& value, const std::string& name) {
  const std::string expected = "a 4x4 matrix of finite numbers (rows first, as numpy writes it)";
  py::array_t<double> array;
  try {
    array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  } catch (const py::error_already_set&) {
  }
  if (!array || array.ndim() != 2 || array.shape(0) != 4 || array.shape(1) != 4) badArgument(name, expected, value);
  glm::mat4 m;
  const auto in = array.unchecked<2>();
  for (int row = 0; row < 4; ++row)
    for (int column = 0; column < 4; ++column) {
      if (!std::isfinite(in(row, column))) badArgument(name, expected, value);
      m[column][row] = float(in(row, column));  // glm is column-major
    }
  return m;
}

// pass -> value(pass) for each of the frame's passes in the order they ran,
// leaving out those whose value is None.
template <class Value>
py::dict passDict(const Frame& frame, Value value) {
  py::dict passes;
  for (const PassTime& time : frame.timings) {
    py::object item = value(time);
    if (!item.is_none()) passes[py::str(time.pass)] = item;
  }
  return passes;
}

std::optional<Camera> cameraFromKwargs(const py::kwargs& kwargs) {
  auto given = [&](const char* name) { return kwargs.contains(name) && !kwargs[name].is_none(); };
  const bool lookAt = given("eye") || given("target");
  const bool view = given("view");
  if (!lookAt && !view) {
    for (const char* name : {"up", "fov", "ortho_size"})
      if (given(name)) throw SettingsError(std::string(name) + ": needs eye and target, or view", {name});
    return std::nullopt;
  }
  if (lookAt && view) throw SettingsError("eye/target and view: give one", {"eye", "target", "view"});
  if (lookAt && !(given("eye") && given("target")))
    throw SettingsError("eye and target go together", {"eye", "target"});
  if (given("camera")) throw SettingsError("camera (an index) and an explicit camera: give one", {"camera"});
  if (given("fov") && given("ortho_size"))
    throw SettingsError("fov and ortho_size: give one (perspective or orthographic)", {"fov", "ortho_size"});
  Camera camera;
  camera.name = "Python camera";
  if (lookAt) {
    const glm::vec3 eye = vec3Argument(kwargs["eye"], "eye");
    const glm::vec3 target = vec3Argument(kwargs["target"], "target");
    const glm::vec3 up = given("up") ? vec3Argument(kwargs["up"], "up") : glm::vec3(0.0f, 1.0f, 0.0f);
    const glm::vec3 forward = target - eye;
    if (glm::length(forward) == 0.0f) throw SettingsError("eye and target: the same point", {"eye", "target"});
    if (glm::length(glm::cross(glm::normalize(forward), up)) < 1e-6f)
      throw SettingsError("up: parallel to the view direction (or zero)", {"up"});
    camera.worldFromCamera = glm::inverse(glm::lookAt(eye, target, up));
  } else {
    const glm::mat4 viewMatrix = matrixArgument(kwargs["view"], "view");
    const float determinant = glm::determinant(viewMatrix);
    if (!std::isfinite(determinant) || std::abs(determinant) < 1e-12f)
      throw SettingsError("view: not invertible (determinant " + std::to_string(determinant) + ")", {"view"});
    camera.worldFromCamera = glm::inverse(viewMatrix);
  }
  if (given("ortho_size")) {
    const float height = finiteNumber(kwargs["ortho_size"], "ortho_size", "the view's height in world units, > 0");
    if (!(height > 0.0f)) badArgument("ortho_size", "the view's height in world units, > 0", kwargs["ortho_size"]);
    camera.projection = Camera::Projection::Orthographic;
    camera.ymag = camera.xmag = 0.5f * height;
  } else {
    const float fov = given("fov") ? finiteNumber(kwargs["fov"], "fov", "degrees in (0, 180)") : kDefaultFovDegrees;
    if (!(fov > 0.0f && fov < 180.0f)) badArgument("fov", "degrees in (0, 180)", kwargs["fov"]);
    camera.yfov = glm::radians(fov);
  }
  return camera;
}

RenderSettings settingsFromKwargs(const py::kwargs& kwargs) {
  RenderSettings settings;
  if (kwargs.contains("preset")) {
    std::string known;
    for (std::string_view name : presetNames()) (known += known.empty() ? "" : ", ") += name;
    applyPreset(settings, textArgument(kwargs["preset"], "preset", "one of " + known + " (a str)"));
  }
  const auto rows = settingOptions();
  for (const auto& [key, value] : kwargs) {
    std::string name = key.cast<std::string>();
    if (name == "preset" || name == "targets" || isCameraKeyword(name)) continue;
    for (char& c : name)
      if (c == '_') c = '-';
    const Option<RenderSettings>* row = nullptr;
    for (const auto& option : rows)
      if (option.spec.name == name) row = &option;
    if (row == nullptr) {
      std::string known = "preset";
      for (const auto& option : rows) known += ", " + pythonName(option.spec.name);
      for (std::string_view keyword : kCameraKeywords) (known += ", ") += keyword;
      known += ", targets";
      throw SettingsError("unknown setting '" + key.cast<std::string>() + "' (known: " + known + ")");
    }
    row->set(settings, parseOptionValue(row->spec, optionText(row->spec, value)));
  }
  return settings;
}

// set_scene's limit keywords: the rows of limitOptions() ('-' -> '_').
ResourceLimits limitsFromKwargs(const py::kwargs& kwargs) {
  ResourceLimits limits;
  for (const auto& [key, value] : kwargs) {
    std::string name = key.cast<std::string>();
    for (char& c : name)
      if (c == '_') c = '-';
    const Option<ResourceLimits>* row = nullptr;
    for (const auto& option : limitOptions())
      if (option.spec.name == name) row = &option;
    if (row == nullptr) {
      std::string known = "allow_external_paths";
      for (const auto& option : limitOptions()) known += ", " + pythonName(option.spec.name);
      throw SettingsError("unknown set_scene keyword '" + key.cast<std::string>() + "' (known: " + known + ")");
    }
    row->set(limits, parseOptionValue(row->spec, optionText(row->spec, value)));
  }
  return limits;
}

// The frame's non-empty targets by name, in frameTargets() order.
const ImageF* findTarget(const Frame& frame, const std::string& name) {
  const FrameTarget* row = findFrameTarget(name);
  if (row == nullptr || row->image == nullptr || (frame.*(row->image)).empty()) return nullptr;
  return &(frame.*(row->image));
}

py::list targetNames(const Frame& frame) {
  py::list names;
  for (const auto& [name, image] : frame.targets()) names.append(py::str(name));
  return names;
}

py::array_t<float> matrix(const glm::mat4& m) {
  py::array_t<float> array({4, 4});
  auto out = array.mutable_unchecked<2>();
  for (int row = 0; row < 4; ++row)
    for (int column = 0; column < 4; ++column) out(row, column) = m[column][row];  // glm is column-major
  return array;
}

// H x W x C float32 over the frame's own pixels: no copy; the array keeps
// the frame alive through `owner`.
// A read-only view of the frame's memory (the frame is shared: a write
// would change what frame.write() saves): H x W x C, or H x W for a
// one-channel target (depth).
// Frame's pickle state (multiprocessing pools return frames): every field,
// images as bytes. Version first, so a future layout can refuse an old one.
constexpr int kFrameStateVersion = 2;  // 2: the ids' names

// IdNames as plain tuples: (name, index, subIndex) per entry, four tables.
py::tuple idNamesState(const std::shared_ptr<const IdNames>& names) {
  if (!names) return py::make_tuple();
  auto table = [](const std::vector<IdName>& entries) {
    py::list rows;
    for (const IdName& e : entries) rows.append(py::make_tuple(e.name, e.index, e.subIndex));
    return rows;
  };
  return py::make_tuple(table(names->meshInstances), table(names->meshes), table(names->materials),
                        table(names->meshPrimitives));
}

std::shared_ptr<const IdNames> idNamesFromState(const py::tuple& state) {
  if (state.empty()) return nullptr;
  if (state.size() != 4) throw SettingsError("Frame state: the ids' names are not four tables");
  auto table = [](const py::handle& rows) {
    std::vector<IdName> entries;
    for (const py::handle& row : rows.cast<py::list>()) {
      const py::tuple e = row.cast<py::tuple>();
      entries.push_back({e[0].cast<std::string>(), e[1].cast<int>(), e[2].cast<int>()});
    }
    return entries;
  };
  return std::make_shared<const IdNames>(IdNames{table(state[0]), table(state[1]), table(state[2]), table(state[3])});
}

py::tuple matrixState(const glm::mat4& m) {
  return py::make_tuple(py::bytes(reinterpret_cast<const char*>(&m[0][0]), sizeof(glm::mat4)));
}

glm::mat4 matrixFromState(const py::handle& state) {
  const std::string bytes = state.cast<py::tuple>()[0].cast<std::string>();
  if (bytes.size() != sizeof(glm::mat4)) throw SettingsError("Frame state: a matrix of the wrong size");
  glm::mat4 m;
  std::memcpy(&m[0][0], bytes.data(), sizeof(glm::mat4));
  return m;
}

py::tuple frameState(const Frame& f) {
  py::dict images;
  for (const FrameTarget& target : frameTargets()) {
    if (target.image == nullptr || (f.*target.image).empty()) continue;
    const ImageF& image = f.*target.image;
    images[py::str(std::string(target.name))] = py::make_tuple(
        image.width, image.height, image.channels,
        py::bytes(reinterpret_cast<const char*>(image.pixels.data()), image.pixels.size() * sizeof(float)));
  }
  py::list timings, skipped;
  for (const PassTime& t : f.timings)
    timings.append(py::make_tuple(t.pass, t.milliseconds, t.gpuMilliseconds, t.form, t.detail));
  for (const SkippedWork& s : f.skipped) skipped.append(py::make_tuple(s.work, s.reason));
  const CameraView& v = f.view;
  return py::make_tuple(
      kFrameStateVersion, images, settingsAsText(f.settings),
      py::make_tuple(matrixState(v.view), matrixState(v.projection),
                     py::make_tuple(v.position.x, v.position.y, v.position.z), v.nearPlane, v.farPlane, v.orthographic),
      timings, skipped, f.glRenderer, f.glVersion, f.backend, f.sceneSource, f.sceneHash, f.ignored,
      idNamesState(f.idNames));
}

std::shared_ptr<Frame> frameFromState(const py::tuple& state) {
  if (state.size() != 13 || state[0].cast<int>() != kFrameStateVersion)
    throw SettingsError("Frame state: not a headlight " + std::string(kVersion) + " frame");
  auto f = std::make_shared<Frame>();
  for (const auto& [name, value] : state[1].cast<py::dict>()) {
    const FrameTarget* target = findFrameTarget(name.cast<std::string>());
    if (target == nullptr || target->image == nullptr)
      throw SettingsError("Frame state: unknown target " + name.cast<std::string>());
    const py::tuple parts = value.cast<py::tuple>();
    ImageF& image = (*f).*(target->image);
    image.width = parts[0].cast<int>();
    image.height = parts[1].cast<int>();
    image.channels = parts[2].cast<std::vector<std::string>>();
    const std::string bytes = parts[3].cast<std::string>();
    const std::size_t count =
        std::size_t(std::max(image.width, 0)) * std::size_t(std::max(image.height, 0)) * image.channels.size();
    if (bytes.size() != count * sizeof(float))
      throw SettingsError("Frame state: " + name.cast<std::string>() + "'s pixels do not fit its size");
    image.pixels.resize(count);
    std::memcpy(image.pixels.data(), bytes.data(), bytes.size());
  }
  applySettingsText(f->settings, state[2].cast<std::map<std::string, std::string>>());
  const py::tuple view = state[3].cast<py::tuple>();
  f->view.view = matrixFromState(view[0]);
  f->view.projection = matrixFromState(view[1]);
  const py::tuple position = view[2].cast<py::tuple>();
  f->view.position = glm::vec3(position[0].cast<float>(), position[1].cast<float>(), position[2].cast<float>());
  f->view.nearPlane = view[3].cast<float>();
  f->view.farPlane = view[4].cast<float>();
  f->view.orthographic = view[5].cast<bool>();
  for (const py::handle& t : state[4].cast<py::list>()) {
    const py::tuple time = t.cast<py::tuple>();
    f->timings.push_back({time[0].cast<std::string>(), time[1].cast<double>(), time[2].cast<double>(),
                          time[3].cast<std::string>(), time.size() > 4 ? time[4].cast<std::string>() : std::string()});
  }
  for (const py::handle& s : state[5].cast<py::list>())
    f->skipped.push_back({s.cast<py::tuple>()[0].cast<std::string>(), s.cast<py::tuple>()[1].cast<std::string>()});
  f->glRenderer = state[6].cast<std::string>();
  f->glVersion = state[7].cast<std::string>();
  f->backend = state[8].cast<std::string>();
  f->sceneSource = state[9].cast<std::string>();
  f->sceneHash = state[10].cast<std::string>();
  f->ignored = state[11].cast<std::vector<std::string>>();
  f->idNames = idNamesFromState(state[12].cast<py::tuple>());
  return f;
}

py::array imageArray(const ImageF& image, py::handle owner) {
  const py::ssize_t c = image.channelCount(), h = image.height, w = image.width;
  // The ids are labels: uint32 as in ids.exr. The frame holds them as exact
  // floats, so the array is a copy, made once and kept on the Frame object.
  if (&image == &owner.cast<const Frame&>().ids) {
    py::dict kept = owner.attr("__dict__");
    if (!kept.contains("_ids")) {
      py::array_t<std::uint32_t> ids({h, w, c});
      std::uint32_t* to = ids.mutable_data();
      for (std::size_t i = 0; i < image.pixels.size(); ++i) to[i] = std::uint32_t(image.pixels[i]);
      ids.attr("setflags")(py::arg("write") = false);
      kept["_ids"] = ids;
    }
    return kept["_ids"];
  }
  const py::ssize_t rowStride = py::ssize_t(sizeof(float)) * w * c, pixelStride = py::ssize_t(sizeof(float)) * c;
  py::array array = c == 1 ? py::array_t<float>({h, w}, {rowStride, pixelStride}, image.pixels.data(), owner)
                           : py::array_t<float>({h, w, c}, {rowStride, pixelStride, py::ssize_t(sizeof(float))},
                                                image.pixels.data(), owner);
  array.attr("setflags")(py::arg("write") = false);
  return array;
}

}  // namespace

PYBIND11_MODULE(headlight, m) {
  m.doc() = "Headlight: a headless deferred renderer (OpenGL 4.5 via EGL or OSMesa) with numpy outputs";
  m.attr("__version__") = kVersion;
  // numpy now, on the importing thread: pybind11 would otherwise import it
  // lazily on the first array, which, on a worker thread while other threads
  // render, hung (tools/thread_stress.py).
  py::module_::import("numpy");

  // Every exception class the library throws (headlight/error.hpp), with its
  // messages, under headlight.Error. SettingsError is a ValueError too; the
  // others are RuntimeErrors. An error's `settings` attribute lists the
  // settings its message names (Error::settings()).
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  static py::exception<ContextError> contextError(m, "ContextError", error.ptr());
  static py::exception<SceneError> sceneError(m, "SceneError", error.ptr());
  static py::exception<IoError> ioError(m, "IoError", error.ptr());
  static py::exception<GlError> glError(m, "GlError", error.ptr());
  static py::exception<LimitError> limitError(m, "LimitError", error.ptr());
  static py::handle settingsError =
      PyErr_NewException("headlight.SettingsError", py::make_tuple(error, py::handle(PyExc_ValueError)).ptr(), nullptr);
  m.attr("SettingsError") = settingsError;
  py::register_exception_translator([](std::exception_ptr p) {
    auto raise = [](py::handle type, const Error& e) {
      py::object instance = type(py::str(e.what()));
      instance.attr("settings") = py::cast(e.settings());
      PyErr_SetObject(type.ptr(), instance.ptr());
    };
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ContextError& e) {
      raise(contextError, e);
    } catch (const SceneError& e) {
      raise(sceneError, e);
    } catch (const IoError& e) {
      raise(ioError, e);
    } catch (const GlError& e) {
      raise(glError, e);
    } catch (const LimitError& e) {
      raise(limitError, e);
    } catch (const SettingsError& e) {
      raise(settingsError, e);
    } catch (const Error& e) {
      raise(error, e);
    }
  });

  py::class_<Frame, std::shared_ptr<Frame>>(m, "Frame", py::dynamic_attr(),
                                            "One render: every target as a numpy array (H x W x C float32, rows top "
                                            "first, sharing the frame's memory; ids uint32), the camera and the "
                                            "pass times.")
      // Picklable, so a multiprocessing pool can return frames: every field, images as bytes.
      .def(py::pickle([](const Frame& frame) { return frameState(frame); },
                      [](const py::tuple& state) { return frameFromState(state); }))
      .def_property_readonly(
          "targets",
          [](py::object self) {
            py::dict targets;
            for (const auto& [name, image] : self.cast<const Frame&>().targets())
              targets[py::str(name)] = imageArray(*image, self);
            return targets;
          },
          "dict: target name ('position', 'normal', ..., 'lit') -> array; empty targets are left out")
      // A read-only mapping of target name -> array (collections.abc.Mapping
      // is registered below): keys, values, items, get, in, len, iteration.
      .def(
          "__getitem__",
          [](py::object self, const py::object& key) {
            const Frame& frame = self.cast<const Frame&>();
            const ImageF* image = py::isinstance<py::str>(key) ? findTarget(frame, key.cast<std::string>()) : nullptr;
            if (image == nullptr) {
              std::string known;
              for (const auto& [name, target] : frame.targets()) (known += known.empty() ? "" : ", ") += name;
              throw py::key_error("no target " + py::repr(key).cast<std::string>() + " in this frame (it has " + known +
                                  ")");
            }
            return imageArray(*image, self);
          },
          "frame['lit']: one target's array")
      .def("__len__", [](const Frame& frame) { return frame.targets().size(); })
      .def("__contains__",
           [](const Frame& frame, const py::object& key) {
             return py::isinstance<py::str>(key) && findTarget(frame, key.cast<std::string>()) != nullptr;
           })
      .def("__iter__", [](const Frame& frame) { return py::iter(targetNames(frame)); })
      .def(
          "keys", [](const Frame& frame) { return targetNames(frame); }, "the target names, in output order")
      .def(
          "values",
          [](py::object self) {
            py::list values;
            for (const auto& [name, image] : self.cast<const Frame&>().targets())
              values.append(imageArray(*image, self));
            return values;
          },
          "the target arrays, in output order")
      .def(
          "items",
          [](py::object self) {
            py::list items;
            for (const auto& [name, image] : self.cast<const Frame&>().targets())
              items.append(py::make_tuple(py::str(name), imageArray(*image, self)));
            return items;
          },
          "(name, array) pairs, in output order")
      .def(
          "get",
          [](py::object self, const py::object& key, const py::object& fallback) -> py::object {
            const Frame& frame = self.cast<const Frame&>();
            const ImageF* image = py::isinstance<py::str>(key) ? findTarget(frame, key.cast<std::string>()) : nullptr;
            return image ? py::object(imageArray(*image, self)) : fallback;
          },
          py::arg("key"), py::arg("default") = py::none())
      .def_property_readonly(
          "channels",
          [](const Frame& frame) {
            py::dict channels;
            for (const auto& [name, image] : frame.targets()) channels[py::str(name)] = image->channels;
            return channels;
          },
          "dict: target name -> channel names, e.g. 'normal' -> ['normal.X', 'normal.Y', 'normal.Z']")
      .def_property_readonly(
          "id_names",
          [](const Frame& f) -> py::object {
            if (!f.idNames) return py::none();
            return py::module_::import("json").attr("loads")(idNamesJson(*f.idNames));
          },
          "dict as frame.json's ids: 'instance', 'mesh', 'material', 'primitive' -> a list of {'id', 'name', and "
          "the file's index: 'node' and 'copy', 'mesh', 'material', 'mesh' and 'primitive'}; id k is entry k - 1, "
          "0 the background. None without the ids target")
      .def_property_readonly(
          "view", [](const Frame& f) { return matrix(f.view.view); }, "4x4 world -> view (looks down -Z)")
      .def_property_readonly(
          "projection", [](const Frame& f) { return matrix(f.view.projection); },
          "4x4 view -> clip, OpenGL's -1..1 depth")
      .def_property_readonly(
          "camera_position",
          [](const Frame& f) { return py::make_tuple(f.view.position.x, f.view.position.y, f.view.position.z); })
      .def_property_readonly("near", [](const Frame& f) { return f.view.nearPlane; })
      .def_property_readonly("far", [](const Frame& f) { return f.view.farPlane; })
      .def_property_readonly("orthographic", [](const Frame& f) { return f.view.orthographic; })
      .def_property_readonly(
          "times",
          [](const Frame& f) { return passDict(f, [](const PassTime& t) { return py::float_(t.milliseconds); }); },
          "dict: pass -> milliseconds, in the order the passes ran (wall time, bounded by glFinish)")
      .def_property_readonly(
          "gpu_times",
          [](const Frame& f) {
            return passDict(f, [](const PassTime& t) {
              return t.gpuMilliseconds >= 0 ? py::object(py::float_(t.gpuMilliseconds)) : py::object(py::none());
            });
          },
          "dict: pass -> the GPU's own milliseconds (GL_TIME_ELAPSED; absent where the driver gave none)")
      .def_property_readonly(
          "forms",
          [](const Frame& f) {
            return passDict(f, [](const PassTime& t) {
              return t.form.empty() ? py::object(py::none()) : py::object(py::str(t.form));
            });
          },
          "dict: fullscreen pass -> 'fragment' or 'compute', how it ran (the fullscreen-form setting)")
      .def_property_readonly(
          "settings", [](const Frame& f) { return settingsAsText(f.settings); },
          "the settings as used (auto resolved), by row name, as text")
      .def_readonly("gl_renderer", &Frame::glRenderer)
      .def_readonly("gl_version", &Frame::glVersion)
      .def_readonly("backend", &Frame::backend)
      .def_readonly("scene_source", &Frame::sceneSource)
      .def_readonly("scene_hash", &Frame::sceneHash)
      .def_property_readonly("width", [](const Frame& f) { return f.settings.width; })
      .def_property_readonly("height", [](const Frame& f) { return f.settings.height; })
      .def(
          "write",
          [](const Frame& frame, const py::object& folder, const py::object& png) {
            const std::filesystem::path path = pathArgument(folder, "folder");
            OutputOptions options;
            if (!png.is_none()) options.pngTargets = targetNames("png", png);
            std::vector<std::filesystem::path> paths;
            py::gil_scoped_release release;
            for (const WrittenFile& file : writeFrame(frame, path, options)) paths.push_back(file.path);
            return paths;
          },
          py::arg("folder"), py::arg("png") = py::none(),
          "writes <folder>/<target>.exr and preview.png as `headlight render` does, and <target>.png for each "
          "target named in png (e.g. png=['normal', 'depth']: as `render --png`); returns the paths");

  // render()'s and submit()'s keywords: the settings, an explicit camera and the targets to read back.
  struct RenderRequest {
    RenderSettings settings;
    std::optional<Camera> camera;
    std::vector<std::string> targets;  // targets=['depth', 'lit']: passes only other targets need are skipped
  };
  static const auto renderRequest = [](const py::kwargs& kwargs) {
    RenderRequest request;
    request.camera = cameraFromKwargs(kwargs);
    request.settings = settingsFromKwargs(kwargs);
    if (kwargs.contains("targets") && !kwargs["targets"].is_none())
      request.targets = targetNames("targets", kwargs["targets"]);
    return request;
  };

  py::class_<PyRenderer>(m, "Renderer",
                         "A GL context and a renderer. Usable from any thread, one call at a time (the context is "
                         "made current on the calling thread for each call); calls release the GIL.")
      .def(py::init([](const py::object& backend, const py::object& device, const py::object& strict,
                       const py::object& deviceFallback) {
             ContextOptions options;
             options.backend = parseBackend(textArgument(backend, "backend", "'auto', 'egl' or 'osmesa'"));
             if (!py::isinstance<py::bool_>(strict) && !isNumpyBool(strict))
               throw SettingsError("strict: expected True or False, got " + py::repr(strict).cast<std::string>(),
                                   {"strict"});
             options.errorPolicy = py::bool_(strict) ? GlErrorPolicy::Throw : GlErrorPolicy::Warn;
             if (isIntegral(device)) {
               const py::int_ index(device);
               if (index < py::int_(0) || index > py::int_(INT_MAX))
                 throw SettingsError("device: expected an EGL device index 0.." + std::to_string(INT_MAX) +
                                         " or a name, got " + py::repr(index).cast<std::string>(),
                                     {"device"});
               options.eglDevice = index.cast<int>();
             } else if (py::isinstance<py::str>(device)) {
               options.eglDeviceName = device.cast<std::string>();
             } else if (!device.is_none()) {
               throw SettingsError("device: expected None, an EGL device index or an EGL device name, got " +
                                       py::repr(device).cast<std::string>(),
                                   {"device"});
             }
             if (!py::isinstance<py::bool_>(deviceFallback) && !isNumpyBool(deviceFallback))
               throw SettingsError(
                   "device_fallback: expected True or False, got " + py::repr(deviceFallback).cast<std::string>(),
                   {"device_fallback"});
             options.deviceFallback = py::bool_(deviceFallback);
             py::gil_scoped_release release;
             return std::make_unique<PyRenderer>(options);
           }),
           py::arg("backend") = "auto", py::arg("device") = py::none(), py::arg("strict") = true,
           py::arg("device_fallback") = false,
           "backend: 'auto' (EGL, then OSMesa), 'egl' or 'osmesa'; device: EGL device index or name "
           "(e.g. 'EGL_MESA_device_software', '/dev/dri/renderD128'), a ContextError naming the devices there "
           "are if it cannot be used, unless device_fallback; strict: GL errors raise GlError")
      .def(
          "set_scene",
          [](PyRenderer& self, const py::object& scene, const py::object& allowExternalPaths,
             const py::object& environment, const std::string& materialVariant, const py::object& animation,
             const py::object& time, const py::kwargs& kwargs) {
            SceneLoadOptions options;
            if (!environment.is_none()) options.environment = pathArgument(environment, "environment");
            options.materialVariant = materialVariant;
            // The rows' own parsing: an index or a name; seconds, checked in range.
            const auto& rows = sceneLoadOptions();
            if (!animation.is_none())
              findOption(rows, "animation")
                  .set(options,
                       parseOptionValue(findOption(rows, "animation").spec, py::str(animation).cast<std::string>()));
            if (!time.is_none()) {
              if (!py::isinstance<py::int_>(time) && !py::isinstance<py::float_>(time))
                throw SettingsError("time: expected seconds, got " + py::repr(time).cast<std::string>(), {"time"});
              findOption(rows, "time").set(options, OptionValue(time.cast<double>()));
            }
            if (!py::isinstance<py::bool_>(allowExternalPaths))
              throw SettingsError("allow_external_paths: expected True or False, got " +
                                      py::repr(allowExternalPaths).cast<std::string>(),
                                  {"allow-external-paths"});
            options.allowExternalPaths = allowExternalPaths.cast<bool>();
            const std::string name = pathArgument(scene, "scene");
            const ResourceLimits limits = limitsFromKwargs(kwargs);
            py::gil_scoped_release release;
            Scene loaded = loadScene(name, options, limits);
            self.onThisThread([&] {
              self.renderer->setLimits(limits);
              self.renderer->setScene(std::move(loaded));
            });
          },
          py::arg("scene"), py::arg("allow_external_paths") = false, py::arg("environment") = py::none(),
          py::arg("material_variant") = "", py::arg("animation") = py::none(), py::arg("time") = py::none(),
          "set_scene(scene, allow_external_paths=False, environment=None, material_variant='', animation=None, "
          "time=None, **limits): a glTF "
          "file (.gltf/.glb) or 'builtin:cornell' / 'builtin:spheres'; environment: an equirectangular .hdr/.exr that "
          "replaces the sky (render's environment_intensity, environment_rotation, environment_background apply); "
          "material_variant: a KHR_materials_variants name ('': the file's default materials); animation: an "
          "animation's index or name to pose the file by at time seconds (time alone: animation 0; neither: the "
          "static pose); limits are "
          "limitOptions() rows ('-' -> '_'): max_memory (MiB), max_instances, "
          "max_triangles, max_texels; over one: LimitError")
      .def(
          "render",
          [](PyRenderer& self, const py::kwargs& kwargs) {
            const RenderRequest request = renderRequest(kwargs);
            py::gil_scoped_release release;
            return self.onThisThread([&] {
              return std::make_shared<Frame>(self.renderer->render(
                  request.settings, request.camera ? &*request.camera : nullptr, request.targets));
            });
          },
          "render(width=640, height=480, **settings, eye=None, target=None, up=(0, 1, 0), fov=40, ortho_size=None, "
          "view=None, targets=None) -> Frame. targets: the target names to read back (None: all; passes only "
          "other targets need are skipped). Settings are settingOptions() rows ('-' -> '_'), e.g. ssgi_samples=16, "
          "ssgi_radius=None (auto), shadows=False, preset='fast'. An explicit camera: eye and target (and up), or "
          "view (4x4 world -> view matrix); with fov (vertical, degrees) or ortho_size (the view's height in world "
          "units, orthographic). Without one: the scene's camera (the camera setting), or one fitted to the bounds.")
      .def(
          "submit",
          [](PyRenderer& self, const py::kwargs& kwargs) {
            const RenderRequest request = renderRequest(kwargs);
            py::gil_scoped_release release;
            self.onThisThread([&] {
              self.renderer->submit(request.settings, request.camera ? &*request.camera : nullptr, request.targets);
            });
          },
          "submit(**render's arguments): queues a frame and returns without waiting for it; collect() gives it. "
          "Submit the next view before collecting this one and the GPU draws one while the other comes back "
          "(at most two submitted and not collected). Pass times are then the CPU's; gpu_times the GPU's.")
      .def(
          "collect",
          [](PyRenderer& self) {
            py::gil_scoped_release release;
            return self.onThisThread([&] { return std::make_shared<Frame>(self.renderer->collect()); });
          },
          "collect() -> Frame: the oldest submitted frame (SettingsError when none is)")
      .def_property_readonly("backend",
                             [](PyRenderer& self) { return std::string(backendName(self.context->backend())); })
      .def_property_readonly("device", [](PyRenderer& self) { return self.context->description(); })
      .def_property_readonly(
          "bounds",
          [](PyRenderer& self) {
            const Bounds bounds = self.onThisThread([&] { return self.renderer->scene().worldBounds(); });
            if (bounds.empty()) throw SettingsError("bounds: no scene (call set_scene first)");
            return py::make_tuple(py::make_tuple(bounds.min.x, bounds.min.y, bounds.min.z),
                                  py::make_tuple(bounds.max.x, bounds.max.y, bounds.max.z));
          },
          "the scene's world bounds, ((min x, y, z), (max x, y, z)): to frame a camera without a probe render")
      .def(
          "orbit",
          [](PyRenderer& self, int views, int width, int height, double fov, const py::object& elevation,
             double distance) {
            if (views < 1) throw SettingsError("orbit: views must be at least 1, got " + std::to_string(views));
            if (width < 1 || height < 1) throw SettingsError("orbit: width and height must be positive");
            if (!(fov > 0.0 && fov < 180.0)) throw SettingsError("orbit: fov must be degrees in (0, 180)");
            if (!elevation.is_none() && !(elevation.cast<double>() >= -89.0 && elevation.cast<double>() <= 89.0))
              throw SettingsError("orbit: elevation must be None or degrees in -89..89");
            if (!(distance >= 0.1 && distance <= 100.0)) throw SettingsError("orbit: distance must be in 0.1..100");
            const Bounds bounds = self.onThisThread([&] { return self.renderer->scene().worldBounds(); });
            if (bounds.empty()) throw SettingsError("orbit: no scene (call set_scene first)");
            const glm::vec3 centre = 0.5f * (bounds.min + bounds.max);
            py::list cameras;
            for (int v = 0; v < views; ++v) {
              // The CLI's --views N --orbit turntable (fitCamera turned about +Y).
              const Camera camera = fitCamera(
                  bounds, float(width) / float(height), glm::radians(float(fov)),
                  2.0f * glm::pi<float>() * float(v) / float(views),
                  elevation.is_none() ? kFitElevationRadians : glm::radians(elevation.cast<float>()), float(distance));
              const glm::vec3 eye(camera.worldFromCamera[3]);
              const glm::vec3 up(camera.worldFromCamera[1]);
              py::dict view;
              view["eye"] = py::make_tuple(eye.x, eye.y, eye.z);
              view["target"] = py::make_tuple(centre.x, centre.y, centre.z);
              view["up"] = py::make_tuple(up.x, up.y, up.z);
              view["fov"] = fov;
              cameras.append(view);
            }
            return cameras;
          },
          py::arg("views"), py::arg("width") = 640, py::arg("height") = 480, py::arg("fov") = 40.0,
          py::arg("elevation") = py::none(), py::arg("distance") = 1.0,
          "orbit(views, width=640, height=480, fov=40, elevation=None (14.04), distance=1) -> [dict(eye, target, up, "
          "fov)]: "
          "the turntable of `headlight render --views N --orbit` (--orbit-elevation, --orbit-distance), each view "
          "ready for render(**view, width=..., height=...)")
      .def_property_readonly("gl_renderer", [](PyRenderer& self) { return self.context->renderer(); });

  m.def(
      "settings",
      [] {
        py::list rows;
        const RenderSettings defaults;
        for (const auto& option : settingOptions()) {
          py::dict row;
          row["name"] = pythonName(option.spec.name);
          row["type"] = optionValueName(option.spec);
          row["default"] = option.get ? formatOptionValue(option.spec, option.get(defaults)) : "";
          row["help"] = std::string(option.spec.help);
          row["auto"] = std::string(option.spec.autoMeaning);
          rows.append(row);
        }
        return rows;
      },
      "every render() keyword: name, value type, default, help, and what 'auto' (None) means");
  m.def("builtin_scenes", &builtinSceneNames);

  // Frame is a read-only mapping of target name -> array.
  py::module_::import("collections.abc").attr("Mapping").attr("register")(m.attr("Frame"));
}
