"""set_scene's environment keyword: an equirectangular .hdr lights the scene
and shows behind it; the render keywords environment_intensity and
environment_background apply; a bad map raises naming the file. Run by
`meson test --suite python` (pytest when installed, else as a script)."""
import os
import tempfile

import numpy as np

import headlight


def write_uniform_hdr(path, width=64, height=32):
    # Radiance RGBE, flat scanlines: (128, 128, 128, 128) is 0.5 in each channel.
    with open(path, "wb") as out:
        out.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (height, width))
        out.write(b"\x80\x80\x80\x80" * (width * height))


def test_environment_lights_and_shows_behind_the_scene():
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "uniform.hdr")
        write_uniform_hdr(path)
        r = headlight.Renderer(backend="osmesa")
        r.set_scene("builtin:spheres", environment=path)
        lit = r.render(width=32, height=24, environment_intensity=2.0)["lit"]
        background = lit[:, :, 3] == 0.0
        assert background.any()
        assert np.allclose(lit[background][:, :3], 1.0, atol=2e-3)  # 0.5 x 2
        dark = r.render(width=32, height=24, environment_background=False)["lit"]
        assert (dark[background][:, :3] == 0.0).all()


def test_a_map_that_is_not_2_to_1_raises_naming_the_file():
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "wide.hdr")
        write_uniform_hdr(path, 96, 32)
        r = headlight.Renderer(backend="osmesa")
        try:
            r.set_scene("builtin:cornell", environment=path)
        except headlight.SceneError as error:
            assert path in str(error) and "96x32" in str(error)
        else:
            raise AssertionError("a 3:1 map was accepted")


if __name__ == "__main__":
    for name, test in list(globals().items()):
        if name.startswith("test_"):
            test()
            print("ok", name)
