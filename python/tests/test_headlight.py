"""The Python module against the library: arrays, settings from the option
table, errors, writing, threads. Run by `meson test --suite python` (pytest
when installed; otherwise this file runs its test_ functions itself)."""
import collections.abc
import os
import pathlib
import re
import tempfile
import threading

import numpy as np

import headlight

SMALL = dict(width=64, height=48, ssgi_samples=8)


def osmesa_renderer():
    return headlight.Renderer(backend="osmesa")


def test_render_gives_arrays_over_the_frames_memory():
    r = osmesa_renderer()
    r.set_scene("builtin:cornell")
    frame = r.render(**SMALL)
    targets = frame.targets
    assert {"position", "normal", "albedo", "material", "depth", "lit"} <= set(targets)
    for name, array in targets.items():
        channels = len(frame.channels[name])
        assert array.shape == ((48, 64) if channels == 1 else (48, 64, channels)), name
        assert not array.flags.writeable, name  # a view of the frame's memory: read-only
        if name == "ids":  # labels: uint32, as in ids.exr (a copy)
            assert array.dtype == np.uint32
            continue
        assert array.dtype == np.float32, name
        assert not array.flags.owndata, name  # a view of the frame's pixels, no copy
    assert frame.channels["normal"] == ["normal.X", "normal.Y", "normal.Z"]
    lit = frame["lit"]
    assert np.shares_memory(lit, frame["lit"])
    # The arrays keep the frame alive.
    del frame
    assert np.isfinite(lit).all() and lit[24, 32, 3] == 1.0


def test_rows_are_top_first():
    r = osmesa_renderer()
    r.set_scene("builtin:cornell")
    position = r.render(**SMALL)["position"]
    # World +Y is up in the Cornell box: the top row sees higher points.
    assert position[2, 32, 1] > position[45, 32, 1]


def test_camera_matrices_project_the_centre_pixel_to_the_centre():
    r = osmesa_renderer()
    r.set_scene("builtin:cornell")
    frame = r.render(**SMALL)
    assert frame.view.shape == (4, 4) and frame.projection.shape == (4, 4)
    p = np.append(frame["position"][24, 32, :3], 1.0)
    clip = frame.projection @ frame.view @ p
    ndc = clip[:3] / clip[3]
    # Pixel (32, 24) of 64 x 48 has its centre half a pixel off the middle.
    assert abs(ndc[0] - 1 / 64) < 0.02 and abs(ndc[1] + 1 / 48) < 0.03, ndc
    assert frame.near > 0 and frame.far > frame.near


def test_pass_times_and_settings_as_used():
    r = osmesa_renderer()
    r.set_scene("builtin:cornell")
    frame = r.render(width=32, height=32, ssgi_samples=4, ssgi_radius=None, shadows=False, exposure=0.5)
    assert "gbuffer" in frame.times and all(ms >= 0 for ms in frame.times.values())
    assert frame.settings["ssgi-samples"] == "4"
    assert frame.settings["shadows"] == "off"
    assert float(frame.settings["ssgi-radius"]) > 0  # None is "auto", resolved from the scene
    assert frame.settings["exposure"] == "0.5"


def test_antialias_changes_lit_alone_and_is_timed():
    r = osmesa_renderer()
    r.set_scene("builtin:spheres")
    centre = r.render(**SMALL, antialias=1)
    antialiased = r.render(**SMALL)  # the default: 8 samples
    assert antialiased.settings["antialias"] == "8" and centre.settings["antialias"] == "1"
    for name in ("position", "normal", "depth", "ssgi"):
        assert np.array_equal(centre[name], antialiased[name]), name
    alpha = antialiased["lit"][..., 3]
    assert ((alpha > 0) & (alpha < 1)).any()  # soft silhouettes
    assert set(np.unique(centre["lit"][..., 3])) <= {0.0, 1.0}
    assert "antialias" in antialiased.times and "antialias" not in centre.times


def test_gpu_times_and_forms():
    r = osmesa_renderer()
    r.set_scene("builtin:cornell")
    computed = r.render(width=32, height=32, fullscreen_form="compute")
    assert set(computed.forms) >= {"direct", "ssgi", "ssgi-blur", "composite"}
    assert all(form == "compute" for form in computed.forms.values())
    assert "gbuffer" not in computed.forms  # geometry passes have no form
    assert all(ms >= 0 for ms in computed.gpu_times.values()) and "ssgi" in computed.gpu_times
    fragment = r.render(width=32, height=32, fullscreen_form="fragment")
    assert all(form == "fragment" for form in fragment.forms.values())
    assert computed.settings["fullscreen-form"] == "compute"


def test_settings_table_is_the_clis():
    names = [row["name"] for row in headlight.settings()]
    assert "ssgi_samples" in names and "shadow_map_size" in names and "width" in names
    row = next(row for row in headlight.settings() if row["name"] == "ssgi_radius")
    assert row["auto"] != ""


def expect(exception, call, *words):
    try:
        call()
    except exception as error:
        for word in words:
            assert word in str(error), (word, str(error))
        return error
    raise AssertionError(f"expected {exception.__name__}")


def test_errors_are_exceptions_with_the_librarys_message():
    r = osmesa_renderer()
    expect(headlight.SettingsError, lambda: r.render(**SMALL), "no scene")
    r.set_scene("builtin:cornell")
    error = expect(headlight.SettingsError, lambda: r.render(ssgi_samples=100000), "ssgi-samples")
    assert isinstance(error, ValueError) and isinstance(error, headlight.Error)
    expect(headlight.SettingsError, lambda: r.render(ssgi_sample=4), "unknown setting 'ssgi_sample'", "ssgi_samples")
    expect(headlight.SettingsError, lambda: r.render(ssgi_method="fancy"), "ssgi-method", "fancy")
    expect(headlight.SettingsError, lambda: r.render(width=1.5), "width")
    expect(headlight.SceneError, lambda: r.set_scene("/no/such/scene.gltf"), "/no/such/scene.gltf")
    expect(headlight.SceneError, lambda: r.set_scene("builtin:nothing"), "nothing")
    expect(headlight.SettingsError, lambda: headlight.Renderer(backend="vulkan"), "vulkan")
    # The renderer still works after each error.
    assert r.render(**SMALL)["lit"].shape == (48, 64, 4)


def test_a_missing_device_is_an_error_not_a_crash():
    expect(headlight.ContextError, lambda: headlight.Renderer(backend="egl", device=99), "99")
    expect(headlight.ContextError, lambda: headlight.Renderer(backend="egl", device="no-such-device"), "no-such-device")
    # Backend auto too: a device asked for is never silently replaced by OSMesa (issue 30)...
    expect(headlight.ContextError, lambda: headlight.Renderer(device=7), "EGL device 0")
    expect(headlight.ContextError, lambda: headlight.Renderer(device="nvidia"), "nvidia")
    # ...unless the caller allows it.
    assert headlight.Renderer(device=7, device_fallback=True).backend in ("egl", "osmesa")
    expect(headlight.SettingsError, lambda: headlight.Renderer(device_fallback="yes"), "device_fallback")


def test_write_writes_the_clis_files():
    r = osmesa_renderer()
    r.set_scene("builtin:cornell")
    with tempfile.TemporaryDirectory() as folder:
        paths = r.render(**SMALL).write(folder)
        names = sorted(os.path.basename(p) for p in paths)
        assert "lit.exr" in names and "preview.png" in names and "depth.exr" in names
        assert all(pathlib.Path(p).stat().st_size > 0 for p in paths)


def test_write_png_and_preview_background():
    r = osmesa_renderer()
    r.set_scene("builtin:cornell")
    frame = r.render(preview_background="#ff0000", **SMALL)
    assert frame.settings["preview-background"] == "#ff0000"
    with tempfile.TemporaryDirectory() as folder:
        paths = frame.write(folder, png=["normal", "depth"])
        names = sorted(os.path.basename(p) for p in paths)
        assert "normal.png" in names and "depth.png" in names and "normal.exr" in names
        # PNG's signature, and an 8-bit RGB image (colour type 2) of the frame's size.
        header = pathlib.Path(folder, "normal.png").read_bytes()[:26]
        assert header[:8] == b"\x89PNG\r\n\x1a\n"
        assert int.from_bytes(header[16:20], "big") == 64 and int.from_bytes(header[20:24], "big") == 48
        assert header[24] == 8 and header[25] == 2
    expect(headlight.SettingsError, lambda: frame.write("/tmp/unused", png=["preview"]), "png")
    expect(headlight.SettingsError, lambda: frame.write("/tmp/unused", png="normal"), "png")
    expect(headlight.SettingsError, lambda: r.render(preview_background="blue", **SMALL), "preview-background")


def test_two_threads_writing_one_folder_never_mix_their_files():
    # Each frame.write takes the folder's lock as a render does: a second
    # thread is refused (or, told to wait, waits) like a second process, so
    # the folder holds one frame's whole set (issue 32: 5 of 8 trials mixed).
    import json
    r = osmesa_renderer()
    r.set_scene("builtin:cornell")
    frames = [r.render(**SMALL), r.render(width=32, height=24, ssgi_samples=8)]
    with tempfile.TemporaryDirectory() as folder:
        for trial in range(4):
            out = os.path.join(folder, str(trial))
            errors = []

            def write(frame):
                try:
                    frame.write(out)
                except headlight.IoError as error:
                    errors.append(str(error))

            threads = [threading.Thread(target=write, args=(frame,)) for frame in frames]
            for thread in threads:
                thread.start()
            for thread in threads:
                thread.join()
            assert len(errors) <= 1, errors
            assert all("another thread of this process" in error for error in errors), errors
            manifest = json.loads(pathlib.Path(out, "frame.json").read_text())
            assert manifest["complete"]
            # Every listed file is the one written with this list (frames of
            # two sizes differ in bytes), and nothing else is in the folder.
            for entry in manifest["files"]:
                assert pathlib.Path(out, entry["name"]).stat().st_size == entry["bytes"], entry
            listed = {entry["name"] for entry in manifest["files"]}
            assert listed == {name for name in os.listdir(out) if not name.startswith(".")} - {"frame.json"}


def egl_available():
    # On this thread: backends follow each other on one thread (a context is
    # released through its own API before another backend's is made current).
    return can_make("egl")


def skip(reason):
    """A visible skip: pytest's when it runs the file, else a printed line."""
    try:
        import pytest
    except ImportError:
        print("SKIP", reason)
        return
    pytest.skip(reason)


def can_make(backend):
    try:
        headlight.Renderer(backend=backend)
        return True
    except headlight.ContextError:
        return False


def test_renderers_on_two_threads():
    """One renderer per thread, EGL and OSMesa at once (when EGL exists), many
    frames each; every frame equals the first frame of its thread, and all
    OSMesa threads (and all EGL threads) agree with each other."""
    backends = ["osmesa", "osmesa"] + (["egl", "egl"] if egl_available() else [])
    frames = {}
    failures = []

    def work(index, backend):
        try:
            r = headlight.Renderer(backend=backend)
            r.set_scene("builtin:cornell")
            first = r.render(**SMALL)["lit"].copy()
            frames[index] = first
            for i in range(10):
                lit = r.render(**SMALL)["lit"]
                if not np.array_equal(lit, first):
                    failures.append(f"{backend} thread {index} frame {i}: differs by {np.abs(lit - first).max()}")
        except Exception as error:  # noqa: BLE001 - reported below
            failures.append(f"{backend} thread {index}: {error!r}")

    threads = [threading.Thread(target=work, args=(i, b)) for i, b in enumerate(backends)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not failures, failures
    for i, backend in enumerate(backends):
        j = backends.index(backend)
        assert np.array_equal(frames[i], frames[j]), (backend, i, j)
    # Both backends are llvmpipe here: the same picture up to rounding.
    assert np.abs(frames[0] - frames[len(backends) - 1]).max() < 1e-3


def test_frame_is_a_read_only_mapping_of_target_name_to_array():
    r = osmesa_renderer()
    r.set_scene("builtin:cornell")
    frame = r.render(**SMALL)
    assert isinstance(frame, collections.abc.Mapping)
    keys = list(frame.keys())
    assert keys[:5] == ["position", "normal", "albedo", "material", "depth"] and "lit" in keys
    assert list(frame) == keys and len(frame) == len(keys)
    frame_without_ssgi = r.render(**SMALL, ssgi=False)
    assert "ssgi" in frame and "ssgi" not in frame_without_ssgi and "ssgi" not in frame_without_ssgi.keys()
    assert "lit" in frame and "nonsense" not in frame and 3 not in frame
    assert [name for name, _ in frame.items()] == keys
    for (name, array), value in zip(frame.items(), frame.values()):
        assert np.shares_memory(array, value) and np.shares_memory(array, frame[name]), name
    assert frame_without_ssgi.get("ssgi") is None and frame.get("lit").shape == (48, 64, 4)
    expect(KeyError, lambda: frame_without_ssgi["ssgi"], "ssgi", "lit")
    def assign():
        frame["lit"] = None

    expect(TypeError, assign)  # read-only
    assert dict(frame).keys() == frame.targets.keys()


def test_every_error_class_the_library_throws_is_exported():
    header = pathlib.Path(__file__).resolve().parents[2] / "lib/include/headlight/error.hpp"
    classes = re.findall(r"class (\w+) : public Error", header.read_text())
    assert {"ContextError", "SceneError", "IoError", "GlError", "SettingsError", "LimitError"} <= set(classes)
    for name in classes + ["Error"]:
        assert issubclass(getattr(headlight, name), headlight.Error), name
    assert issubclass(headlight.Error, RuntimeError) and issubclass(headlight.SettingsError, ValueError)
    r = osmesa_renderer()
    r.set_scene("builtin:cornell", max_memory=64)
    error = expect(headlight.LimitError, lambda: r.render(width=4096, height=4096), "more than max-memory allows")
    assert error.settings == ["max-memory"]  # the settings the message names, by their names
    expect(headlight.SettingsError, lambda: r.set_scene("builtin:cornell", max_memroy=64), "max_memory")
    error = expect(headlight.SettingsError, lambda: r.render(ssgi_samples=0), "ssgi-samples: must be in")
    assert error.settings == ["ssgi-samples"]


def look_at(eye, target, up=(0.0, 1.0, 0.0)):
    eye, target, up = (np.asarray(v, dtype=np.float64) for v in (eye, target, up))
    f = (target - eye) / np.linalg.norm(target - eye)
    s = np.cross(f, up)
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    m = np.identity(4)
    m[0, :3], m[1, :3], m[2, :3] = s, u, -f
    m[:3, 3] = -m[:3, :3] @ eye
    return m


def test_render_takes_an_explicit_camera():
    r = osmesa_renderer()
    r.set_scene("builtin:cornell")
    target = (0.0, 1.0, 0.0)
    # An orbit: four views around the box, each from where it was asked for.
    lits = []
    for angle in np.linspace(0, 2 * np.pi, 4, endpoint=False):
        eye = (3.5 * np.sin(angle), 1.5, 3.5 * np.cos(angle))
        frame = r.render(**SMALL, eye=eye, target=target, fov=45)
        assert np.allclose(frame.camera_position, eye, atol=1e-5)
        assert np.allclose(frame.view, look_at(eye, target), atol=1e-5)
        assert not frame.orthographic
        # perspective: projection[1, 1] = 1 / tan(fov / 2)
        assert abs(frame.projection[1, 1] - 1 / np.tan(np.radians(45) / 2)) < 1e-4
        lits.append(frame["lit"].copy())
    assert all(np.abs(lits[0] - other).max() > 0.1 for other in lits[1:])
    # The centre of the image looks along eye -> target.
    eye = (0.3, 1.2, 3.0)
    frame = r.render(width=65, height=49, ssgi_samples=8, eye=eye, target=target)
    hit = frame["position"][24, 32, :3]
    ray = np.subtract(target, eye) / np.linalg.norm(np.subtract(target, eye))
    along = hit - np.asarray(eye)
    assert np.linalg.norm(along - ray * (along @ ray)) < 0.05 * np.linalg.norm(along)
    # A view matrix, orthographic: the frame keeps the matrix; ortho_size is the view's height.
    view = look_at((0.0, 1.0, 4.0), target)
    frame = r.render(**SMALL, view=view, ortho_size=2.5)
    assert frame.orthographic and np.allclose(frame.view, view, atol=1e-5)
    assert abs(frame.projection[1, 1] - 2 / 2.5) < 1e-5
    # Mistakes are SettingsErrors naming the keyword.
    expect(headlight.SettingsError, lambda: r.render(eye=eye), "eye and target go together")
    expect(headlight.SettingsError, lambda: r.render(eye=eye, target=target, fov=180), "fov")
    expect(headlight.SettingsError, lambda: r.render(eye=eye, target=eye), "the same point")
    expect(headlight.SettingsError, lambda: r.render(eye=(0, 1), target=target), "eye: expected 3 finite numbers")
    expect(headlight.SettingsError, lambda: r.render(view=np.zeros((4, 4))), "not invertible")
    expect(headlight.SettingsError, lambda: r.render(view=view, eye=eye, target=target), "give one")
    expect(headlight.SettingsError, lambda: r.render(camera=0, eye=eye, target=target), "camera")
    expect(headlight.SettingsError, lambda: r.render(fov=30), "needs eye and target, or view")


def test_a_renderer_is_usable_from_any_thread_one_call_at_a_time():
    """Issue 15 (a): a renderer made on one thread renders on another and back."""
    backend = "egl" if egl_available() else "osmesa"
    r = headlight.Renderer(backend=backend)
    r.set_scene("builtin:cornell")
    here = r.render(**SMALL)["lit"].copy()
    there = []
    worker = threading.Thread(target=lambda: there.append(r.render(**SMALL)["lit"].copy()))
    worker.start()
    worker.join()
    assert there and np.array_equal(here, there[0]), backend
    assert np.array_equal(r.render(**SMALL)["lit"], here)
    made = []
    worker = threading.Thread(target=lambda: made.append(headlight.Renderer(backend=backend)))
    worker.start()
    worker.join()
    made[0].set_scene("builtin:cornell")
    assert np.array_equal(made[0].render(**SMALL)["lit"], here)
    if backend != "egl":
        skip("no EGL here: only OSMesa, which never refused another thread, was checked")


def test_backends_follow_each_other_on_one_thread():
    """Issue 15 (b): EGL then OSMesa (and the reverse) on one thread, the first
    alive while the second renders, then dropped."""
    if not egl_available():
        skip("no EGL context can be made here: the EGL/OSMesa switch is not checked")
        return
    for first, second in (("egl", "osmesa"), ("osmesa", "egl")):
        a = headlight.Renderer(backend=first)
        a.set_scene("builtin:cornell")
        reference = a.render(**SMALL)["lit"].copy()
        b = headlight.Renderer(backend=second)
        b.set_scene("builtin:cornell")
        assert np.abs(b.render(**SMALL)["lit"] - reference).max() < 1e-3, (first, second)
        assert np.array_equal(a.render(**SMALL)["lit"], reference), (first, second)
        del a
        assert np.abs(b.render(**SMALL)["lit"] - reference).max() < 1e-3, (first, second)
        c = headlight.Renderer(backend=first)  # after a context of its backend was destroyed here
        c.set_scene("builtin:cornell")
        assert np.array_equal(c.render(**SMALL)["lit"], reference), (first, second)


def test_numpy_scalars_are_numbers_and_wrong_types_get_the_librarys_words():
    """Issue 15 (c)."""
    r = osmesa_renderer()
    r.set_scene(pathlib.Path("builtin:cornell").as_posix())
    frame = r.render(width=np.int64(64), height=np.int32(48), ssgi_samples=np.uint8(8), exposure=np.float32(0.5),
                     shadows=np.bool_(False))
    assert frame["lit"].shape == (48, 64, 4)
    assert frame.settings["exposure"] == "0.5" and frame.settings["shadows"] == "off"
    r.render(**SMALL, eye=np.array([0.0, 1.0, 3.5], dtype=np.float32), target=[np.int64(0), 1, 0])
    expect(headlight.SettingsError, lambda: r.render(preset=5), "preset: expected one of", "int")
    expect(headlight.SettingsError, lambda: r.render(width=np.float64(1.5)), "width: expected an integer")
    expect(headlight.SettingsError, lambda: r.render(width=[64]), "width: expected a number", "list")
    expect(headlight.SettingsError, lambda: headlight.Renderer(device=2**40), "device: expected an EGL device index")
    expect(headlight.SettingsError, lambda: headlight.Renderer(device=-1), "device")
    expect(headlight.SettingsError, lambda: headlight.Renderer(backend=5), "backend: expected")
    expect(headlight.SettingsError, lambda: headlight.Renderer(strict="yes"), "strict")
    expect(headlight.SettingsError, lambda: r.set_scene(5), "scene: expected a path")
    expect(headlight.SettingsError, lambda: r.set_scene("builtin:cornell", allow_external_paths=1), "allow_external")
    expect(headlight.SceneError, lambda: r.set_scene(pathlib.Path("/no/such.gltf")), "/no/such.gltf")
    with tempfile.TemporaryDirectory() as folder:
        assert any(p.endswith("lit.exr") for p in map(str, frame.write(pathlib.Path(folder))))
    expect(headlight.SettingsError, lambda: frame.write(3), "folder: expected a path")


def test_set_scene_material_variant_picks_the_variants_materials():
    import base64
    import json
    import struct
    positions = struct.pack("<9f", -1, -1, 0, 1, -1, 0, 0, 1, 0)
    document = {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,"
                     + base64.b64encode(positions).decode()}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 3,
                       "min": [-1, -1, 0], "max": [1, 1, 0]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1]}},
                      {"pbrMetallicRoughness": {"baseColorFactor": [0, 1, 0, 1]}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0, "extensions": {
            "KHR_materials_variants": {"mappings": [{"material": 1, "variants": [0]}]}}}]}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0,
        "extensionsUsed": ["KHR_materials_variants"],
        "extensions": {"KHR_materials_variants": {"variants": [{"name": "Green"}]}},
    }
    r = osmesa_renderer()
    with tempfile.TemporaryDirectory() as folder:
        path = pathlib.Path(folder) / "variants.gltf"
        path.write_text(json.dumps(document))
        r.set_scene(path)
        default = r.render(**SMALL)["albedo"][24, 32]
        r.set_scene(path, material_variant="Green")
        green = r.render(**SMALL)["albedo"][24, 32]
        expect(headlight.SceneError, lambda: r.set_scene(path, material_variant="Blue"), "'Blue'", "'Green'")
    assert default[0] > 0.9 and default[1] < 0.1
    assert green[1] > 0.9 and green[0] < 0.1


def test_targets_bounds_and_orbit():
    r = osmesa_renderer()
    r.set_scene("builtin:cornell")
    # targets=: only these come back, and passes only others need are skipped.
    depth_only = r.render(width=32, height=24, targets=["depth"])
    assert list(depth_only) == ["depth"], list(depth_only)
    assert "ssgi" not in depth_only.times and "composite" not in depth_only.times
    expect(headlight.SettingsError, lambda: r.render(width=32, height=24, targets=["colour"]), "colour")
    expect(headlight.SettingsError, lambda: r.render(width=32, height=24, targets="depth"), "targets")
    # The scene's bounds, without a probe render: the Cornell box spans -1..1 in x and z, 0..2 in y.
    (lo, hi) = r.bounds
    assert all(abs(a - b) < 1e-5 for a, b in zip(lo, (-1, 0, -1))), lo
    assert all(abs(a - b) < 1e-5 for a, b in zip(hi, (1, 2, 1))), hi
    # The turntable of `render --views N --orbit`: each view looks at the centre from one distance.
    views = r.orbit(4, width=32, height=24, fov=35)
    assert len(views) == 4
    distances = [sum((e - t) ** 2 for e, t in zip(v["eye"], v["target"])) ** 0.5 for v in views]
    assert max(distances) - min(distances) < 1e-4 * max(distances), distances
    assert all(v["target"] == views[0]["target"] and v["fov"] == 35 for v in views)
    frame = r.render(width=32, height=24, **views[1])
    assert frame["lit"].shape == (24, 32, 4)
    expect(headlight.SettingsError, lambda: r.orbit(0), "views")
    high = r.orbit(1, width=32, height=24, fov=35, elevation=60, distance=2)[0]
    offset = [e - t for e, t in zip(high["eye"], high["target"])]
    length = sum(o * o for o in offset) ** 0.5
    assert abs(offset[1] / length - np.sin(np.radians(60))) < 1e-4, offset
    assert abs(length - 2 * distances[0]) < 1e-3 * length, (length, distances[0])
    empty = osmesa_renderer()
    expect(headlight.SettingsError, lambda: empty.bounds, "no scene")


def test_ids_are_uint32_labels_named_by_id_names():
    r = osmesa_renderer()
    r.set_scene("builtin:cornell")
    frame = r.render(width=64, height=48, antialias=1)
    ids = frame["ids"]
    assert ids.dtype == np.uint32 and ids.shape == (48, 64, 4)
    assert frame.channels["ids"] == ["instance.id", "mesh.id", "material.id", "primitive.id"]
    names = frame.id_names
    assert set(names) == {"background", "channels", "instance", "mesh", "material", "primitive"}
    assert names["background"] == 0
    # Background pixels are 0, geometry pixels name a mesh instance; a segmentation mask is one comparison.
    geometry = frame["position"][..., 3] > 0
    assert (ids[~geometry] == 0).all() and (ids[geometry, 0] > 0).all()
    by_name = {entry["name"]: entry["id"] for entry in names["instance"]}
    left_wall = ids[..., 0] == by_name["left wall"]
    assert left_wall.sum() > 64 * 48 // 20
    # The left wall's pixels are its material's colour, cornell red.
    red = [entry for entry in names["material"] if entry["name"] == "cornell red"][0]
    assert (ids[left_wall, 2] == red["id"]).all()
    assert (frame["albedo"][left_wall, 0] > frame["albedo"][left_wall, 1]).all()
    # Not asked for: no ids and no names.
    lit_only = r.render(width=32, height=24, targets=["lit"])
    assert "ids" not in lit_only and lit_only.id_names is None


def test_frames_pickle_for_multiprocessing():
    import pickle
    r = osmesa_renderer()
    r.set_scene("builtin:cornell")
    frame = r.render(width=32, height=24, fullscreen_form="compute")
    copy = pickle.loads(pickle.dumps(frame))
    assert list(copy) == list(frame)
    for name in frame:
        assert np.array_equal(copy[name], frame[name]), name
        assert copy.channels[name] == frame.channels[name]
    assert copy.settings == frame.settings and copy.forms == frame.forms and copy.times == frame.times
    assert np.array_equal(copy.view, frame.view) and np.array_equal(copy.projection, frame.projection)
    assert (copy.near, copy.far, copy.camera_position) == (frame.near, frame.far, frame.camera_position)
    assert copy.gl_renderer == frame.gl_renderer and copy.scene_source == frame.scene_source
    assert copy.id_names == frame.id_names and copy["ids"].dtype == np.uint32
    # A copy writes the same set as the original.
    import tempfile, os
    with tempfile.TemporaryDirectory() as folder:
        written = copy.write(os.path.join(folder, "out"))
        assert any(str(path).endswith("lit.exr") for path in written)
    expect(headlight.SettingsError, lambda: headlight.Frame.__new__(headlight.Frame).__setstate__((99,)), "state")


def test_submit_and_collect_pipeline_views_and_give_renders_frames():
    r = osmesa_renderer()
    r.set_scene("builtin:cornell")
    views = r.orbit(3, width=64, height=48)
    expected = [r.render(**SMALL, **view) for view in views]
    r.submit(**SMALL, **views[0])
    r.submit(**SMALL, **views[1])
    try:
        r.submit(**SMALL, **views[2])
        raise AssertionError("a third frame in flight was accepted")
    except headlight.SettingsError as error:
        assert "at most 2" in str(error)
    frames = [r.collect()]
    r.submit(**SMALL, **views[2])
    frames += [r.collect(), r.collect()]
    for got, want in zip(frames, expected):
        for name in want.targets:
            assert np.array_equal(got[name], want[name]), name
    try:
        r.collect()
        raise AssertionError("collect() with nothing submitted returned")
    except headlight.SettingsError as error:
        assert "no frame submitted" in str(error)




def test_a_nul_in_a_name_is_refused_and_named_whole():
    r = osmesa_renderer()
    try:
        r.set_scene("builtin:cornell\x00x")
        raise AssertionError("a scene name with a NUL was accepted")
    except headlight.SettingsError as error:
        assert "'builtin:cornell\\x00x' contains a NUL character" in str(error)


if __name__ == "__main__":
    tests = [(name, f) for name, f in sorted(globals().items()) if name.startswith("test_")]
    for name, test in tests:
        test()
        print("ok", name)
    print(len(tests), "passed")


def test_set_scene_animation_poses_the_file_at_a_time():
    # A triangle whose node moves along +X from 0 to 4 over 1 s (LINEAR):
    # at 0.5 s its pixels' world positions are 2 further along X.
    import base64
    import json
    import struct
    positions = struct.pack("<9f", -1, -1, 0, 1, -1, 0, 0, 1, 0)
    keys = struct.pack("<2f6f", 0, 1, 0, 0, 0, 4, 0, 0)
    data = positions + keys
    document = {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64,"
                     + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 8},
                        {"buffer": 0, "byteOffset": 44, "byteLength": 24}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 3,
                       "min": [-1, -1, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5126, "type": "SCALAR", "count": 2, "min": [0], "max": [1]},
                      {"bufferView": 2, "componentType": 5126, "type": "VEC3", "count": 2}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0,
        "animations": [{"name": "Slide", "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}],
                        "samplers": [{"input": 1, "output": 2}]}],
    }
    r = osmesa_renderer()
    view = dict(width=64, height=48, eye=(2, 0, 6), target=(2, 0, 0))
    with tempfile.TemporaryDirectory() as folder:
        path = pathlib.Path(folder) / "slide.gltf"
        path.write_text(json.dumps(document))
        r.set_scene(path, animation="Slide", time=0.5)
        posed = r.render(**view)["position"]
        r.set_scene(path, animation=0, time=5.0)  # after the last keyframe: the last holds
        last = r.render(**view)["position"]
        expect(headlight.SceneError, lambda: r.set_scene(path, animation="Run"), "'Run'", "'Slide'")
        expect(headlight.SettingsError, lambda: r.set_scene(path, time="soon"), "time")
    covered = posed[:, :, 3] == 1.0
    assert covered.any()
    assert posed[covered][:, 0].min() > 0.9  # the triangle spans x in [-1, 1] + 2
    assert posed[covered][:, 0].max() < 3.1
    assert last[last[:, :, 3] == 1.0][:, 0].min() > 2.9
