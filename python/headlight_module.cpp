// The Python module `headlight` (pybind11): a renderer that hands back numpy
// arrays. Settings come from settingOptions(), the table the CLI reads: a
// keyword is a row's name with '-' -> '_', its value is parsed and checked by
// the row exactly as the CLI's --flag would be. docs/EMBEDDING.md has the API.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>

#include "headlight/context.hpp"
#include "headlight/error.hpp"
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
struct PyRenderer {
  std::optional<Context> context;
  std::optional<Renderer> renderer;

  explicit PyRenderer(const ContextOptions& options) {
    context.emplace(options);
    renderer.emplace(*context);
  }
  ~PyRenderer() {
    // Destruction takes the backend lock (ContextAccess::lockBackend), which a
    // render on another thread may hold while it waits for the GIL: give the
    // GIL up first. ~Renderer makes the context current itself when it is not.
    py::gil_scoped_release release;
    renderer.reset();
    context.reset();
  }
  // A Python object may be used from any thread, one at a time (the GIL
  // orders the calls); the context follows it.
  void ensureCurrent() {
    if (!context->isCurrent()) context->makeCurrent();
  }
};

// Python value -> the text the CLI would get, so the row parses and checks it.
std::string optionText(const OptionSpec& spec, const py::handle& value) {
  if (value.is_none()) return "auto";
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "on" : "off";
  if (py::isinstance<py::int_>(value)) return py::str(value).cast<std::string>();
  if (py::isinstance<py::float_>(value)) return py::repr(value).cast<std::string>();  // shortest exact text
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  throw SettingsError(std::string(spec.name) + ": expected a number, bool, str or None (auto), got " +
                      py::str(py::type::of(value)).cast<std::string>());
}

std::string pythonName(std::string_view rowName) {
  std::string name(rowName);
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

RenderSettings settingsFromKwargs(const py::kwargs& kwargs) {
  RenderSettings settings;
  if (kwargs.contains("preset")) applyPreset(settings, kwargs["preset"].cast<std::string>());
  const auto rows = settingOptions();
  for (const auto& [key, value] : kwargs) {
    std::string name = key.cast<std::string>();
    if (name == "preset") continue;
    for (char& c : name)
      if (c == '_') c = '-';
    const Option<RenderSettings>* row = nullptr;
    for (const auto& option : rows)
      if (option.spec.name == name) row = &option;
    if (row == nullptr) {
      std::string known = "preset";
      for (const auto& option : rows) known += ", " + pythonName(option.spec.name);
      throw SettingsError("unknown setting '" + key.cast<std::string>() + "' (known: " + known + ")");
    }
    row->set(settings, parseOptionValue(row->spec, optionText(row->spec, value)));
  }
  return settings;
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
py::array imageArray(const ImageF& image, py::handle owner) {
  const py::ssize_t c = image.channelCount();
  return py::array_t<float>(
      {py::ssize_t(image.height), py::ssize_t(image.width), c},
      {py::ssize_t(sizeof(float)) * image.width * c, py::ssize_t(sizeof(float)) * c, py::ssize_t(sizeof(float))},
      image.pixels.data(), owner);
}

}  // namespace

PYBIND11_MODULE(headlight, m) {
  m.doc() = "Headlight: a headless deferred renderer (OpenGL 4.5 via EGL or OSMesa) with numpy outputs";
  m.attr("__version__") = kVersion;
  // numpy now, on the importing thread: pybind11 would otherwise import it
  // lazily on the first array, which, on a worker thread while other threads
  // render, hung (tools/thread_stress.py).
  py::module_::import("numpy");

  // The library's exception classes, with its messages. SettingsError is a
  // ValueError too; the others are RuntimeErrors.
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  static py::exception<ContextError> contextError(m, "ContextError", error.ptr());
  static py::exception<SceneError> sceneError(m, "SceneError", error.ptr());
  static py::exception<IoError> ioError(m, "IoError", error.ptr());
  static py::exception<GlError> glError(m, "GlError", error.ptr());
  static py::handle settingsError =
      PyErr_NewException("headlight.SettingsError", py::make_tuple(error, py::handle(PyExc_ValueError)).ptr(), nullptr);
  m.attr("SettingsError") = settingsError;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ContextError& e) {
      PyErr_SetString(contextError.ptr(), e.what());
    } catch (const SceneError& e) {
      PyErr_SetString(sceneError.ptr(), e.what());
    } catch (const IoError& e) {
      PyErr_SetString(ioError.ptr(), e.what());
    } catch (const GlError& e) {
      PyErr_SetString(glError.ptr(), e.what());
    } catch (const SettingsError& e) {
      PyErr_SetString(settingsError.ptr(), e.what());
    } catch (const Error& e) {
      PyErr_SetString(error.ptr(), e.what());
    }
  });

  py::class_<Frame, std::shared_ptr<Frame>>(m, "Frame",
                                            "One render: every target as a numpy array (H x W x C float32, rows top "
                                            "first, sharing the frame's memory), the camera and the pass times.")
      .def_property_readonly(
          "targets",
          [](py::object self) {
            py::dict targets;
            for (const auto& [name, image] : self.cast<const Frame&>().targets())
              targets[py::str(name)] = imageArray(*image, self);
            return targets;
          },
          "dict: target name ('position', 'normal', ..., 'lit') -> array; empty targets are left out")
      .def(
          "__getitem__",
          [](py::object self, const std::string& name) {
            const FrameTarget* row = findFrameTarget(name);
            const Frame& frame = self.cast<const Frame&>();
            if (row == nullptr || row->image == nullptr || (frame.*(row->image)).empty())
              throw py::key_error("no target '" + name + "' in this frame");
            return imageArray(frame.*(row->image), self);
          },
          "frame['lit']: one target's array")
      .def_property_readonly(
          "channels",
          [](const Frame& frame) {
            py::dict channels;
            for (const auto& [name, image] : frame.targets()) channels[py::str(name)] = image->channels;
            return channels;
          },
          "dict: target name -> channel names, e.g. 'normal' -> ['normal.X', 'normal.Y', 'normal.Z']")
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
          [](const Frame& f) {
            py::dict times;
            for (const PassTime& t : f.timings) times[py::str(t.pass)] = t.milliseconds;
            return times;
          },
          "dict: pass -> milliseconds, in the order the passes ran")
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
          [](const Frame& frame, const std::filesystem::path& folder) {
            std::vector<std::filesystem::path> paths;
            for (const WrittenFile& file : writeFrame(frame, folder)) paths.push_back(file.path);
            return paths;
          },
          py::arg("folder"),
          "writes <folder>/<target>.exr and preview.png as `headlight render` does; returns the paths");

  py::class_<PyRenderer>(m, "Renderer",
                         "A GL context and a renderer. Use one per thread at a time; renders release the GIL.")
      .def(py::init([](const std::string& backend, const py::object& device, bool strict) {
             ContextOptions options;
             options.backend = parseBackend(backend);
             options.errorPolicy = strict ? GlErrorPolicy::Throw : GlErrorPolicy::Warn;
             if (py::isinstance<py::int_>(device)) {
               options.eglDevice = device.cast<int>();
               if (options.eglDevice < 0) throw SettingsError("device: expected an index >= 0 or a name");
             } else if (py::isinstance<py::str>(device)) {
               options.eglDeviceName = device.cast<std::string>();
             } else if (!device.is_none()) {
               throw SettingsError("device: expected None, an EGL device index or an EGL device name");
             }
             py::gil_scoped_release release;
             return std::make_unique<PyRenderer>(options);
           }),
           py::arg("backend") = "auto", py::arg("device") = py::none(), py::arg("strict") = true,
           "backend: 'auto' (EGL, then OSMesa), 'egl' or 'osmesa'; device: EGL device index or name "
           "(e.g. 'EGL_MESA_device_software', '/dev/dri/renderD128'); strict: GL errors raise GlError")
      .def(
          "set_scene",
          [](PyRenderer& self, const std::string& scene, bool allowExternalPaths) {
            py::gil_scoped_release release;
            self.ensureCurrent();
            self.renderer->setScene(loadScene(scene, {.allowExternalPaths = allowExternalPaths}));
          },
          py::arg("scene"), py::arg("allow_external_paths") = false,
          "a glTF file (.gltf/.glb) or 'builtin:cornell' / 'builtin:spheres'")
      .def(
          "render",
          [](PyRenderer& self, const py::kwargs& kwargs) {
            RenderSettings settings = settingsFromKwargs(kwargs);
            py::gil_scoped_release release;
            self.ensureCurrent();
            return std::make_shared<Frame>(self.renderer->render(settings));
          },
          "render(width=640, height=480, **settings) -> Frame; settings are settingOptions() rows "
          "('-' -> '_'), e.g. ssgi_samples=16, ssgi_radius=None (auto), shadows=False, preset='fast'")
      .def_property_readonly("backend",
                             [](PyRenderer& self) { return std::string(backendName(self.context->backend())); })
      .def_property_readonly("device", [](PyRenderer& self) { return self.context->description(); })
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
}
