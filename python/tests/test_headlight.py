"""The Python module against the library: arrays, settings from the option
table, errors, writing, threads. Run by `meson test --suite python` (pytest
when installed; otherwise this file runs its test_ functions itself)."""
import os
import pathlib
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
        assert array.dtype == np.float32, name
        assert array.shape == (48, 64, len(frame.channels[name])), name
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


def test_write_writes_the_clis_files():
    r = osmesa_renderer()
    r.set_scene("builtin:cornell")
    with tempfile.TemporaryDirectory() as folder:
        paths = r.render(**SMALL).write(folder)
        names = sorted(os.path.basename(p) for p in paths)
        assert "lit.exr" in names and "preview.png" in names and "depth.exr" in names
        assert all(pathlib.Path(p).stat().st_size > 0 for p in paths)


def egl_available():
    result = []
    # On a thread of its own: on Debian 12's Mesa, an OSMesa context made on a
    # thread where an EGL context was made and destroyed before fails to
    # compile shaders (docs/EMBEDDING.md, "Threads").
    t = threading.Thread(target=lambda: result.append(can_make("egl")))
    t.start()
    t.join()
    return result[0]


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


if __name__ == "__main__":
    tests = [(name, f) for name, f in sorted(globals().items()) if name.startswith("test_")]
    for name, test in tests:
        test()
        print("ok", name)
    print(len(tests), "passed")
