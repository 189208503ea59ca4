"""The parallax Python module against an independent second path: the `parallax` command line
(PARALLAX_CLI, set by CTest), whose PNG files are decoded here by a small PNG reader of our own
(zlib + the five row filters), not by parallax's reader."""

import json
import os
import re
import struct
import subprocess
import sys
import threading
import time
import zlib
from pathlib import Path

import numpy as np
import pytest

import parallax

CLI = os.environ.get("PARALLAX_CLI", "")
SOURCE = Path(os.environ.get("PARALLAX_SOURCE_DIR", Path(__file__).resolve().parents[3]))
SMALL = str(SOURCE / "displays" / "small.json")  # 320x180 px: fast under the sanitizers too
EYE = (10.0, 0.0, 600.0)


def cli(*args, cwd=None):
    assert CLI, "PARALLAX_CLI must name the parallax binary (CTest sets it)"
    env = dict(os.environ)
    # Under the sanitizers the interpreter needs the runtimes preloaded and leak checks off
    # (CPython's own); the CLI, instrumented itself, keeps its leak checks.
    if "PARALLAX_CLI_ASAN_OPTIONS" in env:
        env["ASAN_OPTIONS"] = env["PARALLAX_CLI_ASAN_OPTIONS"]
        env.pop("LD_PRELOAD", None)
    return subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, cwd=cwd,
                          env=env)


def read_png(path):
    """8-bit grey, RGB or RGBA PNG -> (H, W, channels) uint8."""
    data = Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    at, idat, header = 8, b"", None
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
        at += 12 + length
    width, height, depth, colour, _, _, interlace = header
    assert depth == 8 and interlace == 0
    channels = {0: 1, 2: 3, 6: 4}[colour]
    raw = zlib.decompress(idat)
    stride = width * channels
    out = np.zeros((height, stride), dtype=np.int32)
    previous = np.zeros(stride, dtype=np.int32)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        row = np.frombuffer(raw, np.uint8, stride, y * (stride + 1) + 1).astype(np.int32)
        if kind == 0:
            line = row
        elif kind == 2:
            line = (row + previous) & 255
        else:  # sub, average, paeth depend on the left neighbour: one byte at a time
            line = np.zeros(stride, dtype=np.int32)
            for x in range(stride):
                left = line[x - channels] if x >= channels else 0
                up = previous[x]
                upleft = previous[x - channels] if x >= channels else 0
                if kind == 1:
                    predictor = left
                elif kind == 3:
                    predictor = (left + up) // 2
                else:
                    p = left + up - upleft
                    pa, pb, pc = abs(p - left), abs(p - up), abs(p - upleft)
                    predictor = left if pa <= pb and pa <= pc else (up if pb <= pc else upleft)
                line[x] = (row[x] + predictor) & 255
        out[y] = line
        previous = line
    return out.astype(np.uint8).reshape(height, width, channels)


def rgb(codes):
    return np.repeat(codes, 3, axis=2) if codes.shape[2] == 1 else codes[:, :, :3]


@pytest.fixture(scope="module")
def scene():
    return parallax.load_scene()


@pytest.fixture(scope="module")
def small():
    return parallax.load_display(SMALL)


@pytest.fixture(scope="module")
def cli_render(tmp_path_factory):
    out = tmp_path_factory.mktemp("render")
    result = cli("render", "--display", SMALL, "--spp", 4, "-o", out)
    assert result.returncode == 0, result.stderr
    return out


@pytest.fixture(scope="module")
def layers(scene, small):
    return parallax.render(scene, small, spp=4)


def test_version_is_the_cli_version():
    run = cli("--version")
    assert run.returncode == 0
    assert parallax.version() == run.stdout.strip()
    assert parallax.version().startswith(f"parallax {parallax.__version__} (Embree ")


def test_design_is_the_cli_design_json(small):
    expected = json.loads(cli("design", SMALL, "--json", "--depth", 5).stdout)
    assert parallax.design(small, depth=5) == expected
    spheres = SOURCE / "scenes" / "spheres.json"
    framed = json.loads(cli("design", SMALL, "--json", "--scene", spheres, "--fit", "window").stdout)
    got = parallax.design(small, scene=parallax.load_scene(str(spheres)), fit="window")
    assert got == framed
    assert "scene" in got


def test_render_layers_are_the_cli_pngs(layers, cli_render):
    assert layers.image.shape == (180, 320, 3) and layers.image.dtype == np.float32
    assert layers.mask.shape == (180, 320, 3) and layers.mask.dtype == np.float32
    image_png = read_png(cli_render / "image.png")
    mask_png = read_png(cli_render / "mask.png")
    assert np.array_equal(layers.image_srgb8, rgb(image_png))
    assert np.array_equal(layers.mask_srgb8, rgb(mask_png))
    # Not a trivial picture: the scene's colours and the slits' open and closed pixels.
    assert len(np.unique(layers.image_srgb8)) > 50
    assert layers.mask_srgb8.min() == 0 and layers.mask_srgb8.max() > 250
    record = json.loads((cli_render / "render.json").read_text())
    for key in ("spp", "seed", "jitter", "bounces"):
        assert layers.record[key] == record[key]
    assert layers.record["filter"] == record["filter"]
    assert layers.record["framing"] == record["framing"]
    assert layers.record["design"] == record["design"]


def test_to_srgb8_is_the_srgb_curve():
    linear = np.linspace(0, 1, 1001, dtype=np.float32).reshape(1, -1, 1).repeat(3, axis=2)
    encoded = np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * linear ** (1 / 2.4) - 0.055)
    codes = parallax.to_srgb8(linear)
    assert codes.dtype == np.uint8
    assert np.abs(codes.astype(int) - np.round(encoded * 255)).max() <= 1


def test_simulate_is_the_cli_simulate(small, cli_render, tmp_path):
    out = tmp_path / "seen.png"
    result = cli("simulate", cli_render, "--display", SMALL, "--eye", "10,0,600", "-o", out)
    assert result.returncode == 0, result.stderr
    image = rgb(read_png(cli_render / "image.png"))
    mask = read_png(cli_render / "mask.png")[:, :, 0]  # grey: an H x W array
    seen = parallax.simulate(image, mask, small, eye=EYE)
    assert seen.shape == (180, 320, 3) and seen.dtype == np.float32
    assert np.array_equal(parallax.to_srgb8(seen), rgb(read_png(out)))


def test_quality_is_the_cli_reference_json(scene, small, cli_render):
    result = cli("simulate", cli_render, "--display", SMALL, "--reference", "--json",
                 "--eye", "10,0,600", "--eye", "-20,5,700", "-o", cli_render.parent / "q.png")
    assert result.returncode == 0, result.stderr
    expected = json.loads(result.stdout)
    image = rgb(read_png(cli_render / "image.png"))
    mask = rgb(read_png(cli_render / "mask.png"))
    got = parallax.quality(scene, small, image, mask, eyes=[EYE, (-20, 5, 700)])
    assert len(got["eyes"]) == 2
    for mine, theirs in zip(got["eyes"] + [got["mean"]], expected["eyes"] + [expected["mean"]]):
        for key in ("psnr", "ssim", "brightness", "crosstalk"):
            assert mine[key] == pytest.approx(theirs[key], rel=1e-12), key
    assert [e["own_view"] for e in got["eyes"]] == [e["own_view"] for e in expected["eyes"]]
    assert 20 < got["mean"]["psnr"] < 60


def test_sweep_spans_the_view_zone(layers, small):
    figures = parallax.design(small)
    eyes, pictures = parallax.sweep(layers.image, layers.mask, small, 5)
    assert pictures.shape == (5, 180, 320, 3)
    xs = [e[0] for e in eyes]
    assert xs == sorted(xs)
    assert xs[-1] - xs[0] == pytest.approx(figures["view_zone_width_mm"], rel=1e-6)
    assert all(e[2] == pytest.approx(figures["view_distance_mm"]) for e in eyes)
    # Different eyes, different views; each the same as one eye simulated alone.
    assert not np.array_equal(pictures[0], pictures[-1])
    assert np.array_equal(pictures[2], parallax.simulate(layers.image, layers.mask, small,
                                                         eye=eyes[2]))


def test_view_and_ideal_view_are_the_cli_pictures(scene, small, tmp_path):
    assert cli("view", "--size", "160x90", "--spp", 4, "-o", tmp_path / "v.png").returncode == 0
    picture = parallax.view(scene, size=(160, 90), spp=4)
    assert picture.shape == (90, 160, 3)
    assert np.array_equal(parallax.to_srgb8(picture), rgb(read_png(tmp_path / "v.png")))
    assert cli("view", "--eye", "0,3,9", "--look-at", "0,0,-5", "--fov", 30, "--size", "64x48",
               "-o", tmp_path / "w.png").returncode == 0
    picture = parallax.view(scene, eye=(0, 3, 9), look_at=(0, 0, -5), fov=30, size=(64, 48))
    assert np.array_equal(parallax.to_srgb8(picture), rgb(read_png(tmp_path / "w.png")))
    result = cli("view", "--display-eye", "20,0,600", "--display", SMALL, "--spp", 4,
                 "-o", tmp_path / "ideal.png")
    assert result.returncode == 0, result.stderr
    ideal = parallax.ideal_view(scene, small, eye=(20, 0, 600), spp=4)
    assert ideal.shape == (180, 320, 3)
    assert np.array_equal(parallax.to_srgb8(ideal), rgb(read_png(tmp_path / "ideal.png")))


def test_quilt_is_the_cli_quilt(scene, small, tmp_path):
    result = cli("render", "--quilt", "3x2", "--size", "64x36", "--spp", 4, "--display", SMALL,
                 "-o", tmp_path)
    assert result.returncode == 0, result.stderr
    made = parallax.quilt(scene, small, layout=(3, 2), size=(64, 36), spp=4)
    assert made.quilt.shape == (72, 192, 3)
    png = tmp_path / made.record["quilt"]["file_name"]
    assert np.array_equal(parallax.to_srgb8(made.quilt), rgb(read_png(png)))
    record = json.loads((tmp_path / "render.json").read_text())
    assert made.record["quilt"]["eyes_mm"] == record["quilt"]["eyes_mm"]
    auto = parallax.quilt(scene, small, size=(32, 18), spp=1)
    assert auto.record["quilt"]["columns"] == 9 and auto.record["quilt"]["rows"] == 1


def same_files(one, other):
    """The two folders hold the same files with the same bytes (render.json: the same record
    but for when and how fast it was made)."""
    names = sorted(p.relative_to(one).as_posix() for p in one.rglob("*") if p.is_file())
    assert names == sorted(p.relative_to(other).as_posix() for p in other.rglob("*") if p.is_file())
    timing = ("created", "seconds", "rays_per_second", "training_seconds")
    for name in names:
        a, b = (one / name).read_bytes(), (other / name).read_bytes()
        if name.endswith("render.json"):
            a, b = json.loads(a), json.loads(b)
            for key in timing:
                a.pop(key, None), b.pop(key, None)
                a.get("layers", {}).pop(key, None), b.get("layers", {}).pop(key, None)
                a.get("sequence", {}).pop(key, None), b.get("sequence", {}).pop(key, None)
        assert a == b, name


def test_the_look_is_the_clis(tmp_path):
    # load_scene(exposure=, view_transform=) is --exposure and --view-transform: the same view.
    looked = parallax.load_scene(exposure=1.5, view_transform="filmic")
    assert cli("view", "--size", "96x54", "--spp", 4, "--exposure", 1.5, "--view-transform",
               "filmic", "-o", tmp_path / "v.png").returncode == 0
    picture = parallax.view(looked, size=(96, 54), spp=4)
    assert np.array_equal(parallax.to_srgb8(picture), rgb(read_png(tmp_path / "v.png")))
    plain = parallax.view(parallax.load_scene(), size=(96, 54), spp=4)
    assert not np.array_equal(picture, plain)
    with pytest.raises(parallax.Error, match="view_transform=agx"):
        parallax.load_scene(view_transform="agx")


def test_render_files_are_the_cli_files(tmp_path):
    # Layers, solved layers (nmf, two time-multiplexed frames), direct mapping, a quilt and a
    # two-frame turntable sequence with its video: the same request, two spellings.
    cases = [
        ([], {}),
        (["--layers", "nmf", "--rank", "2", "--iterations", "2", "--train-eyes", "1"],
         {"layers": "nmf", "rank": 2, "iterations": 2, "train_eyes": 1}),
        (["--layers", "optimized-image", "--iterations", "1", "--train-eyes", "1",
          "--train-distances", "0.9,1.1"],
         {"layers": "optimized-image", "iterations": 1, "train_eyes": 1,
          "train_distances": "0.9,1.1"}),
        (["--direct-mapping"], {"direct_mapping": True}),
        (["--exposure", "1.5", "--view-transform", "filmic"],
         {"exposure": 1.5, "view_transform": "filmic"}),
        (["--focus-on", "box"], {"focus_on": "box"}),
        (["--quilt", "3x2", "--size", "48x27", "--linear"],
         {"quilt": (3, 2), "size": (48, 27), "linear": True}),
        (["--turntable", "90", "--frames", "1:2", "--fps", "2", "--video", "{out}/t.webm"],
         {"turntable": 90, "frames": "1:2", "fps": 2, "video": "{out}/t.webm"}),
    ]
    for k, (options, keywords) in enumerate(cases):
        by_cli, by_python = tmp_path / f"cli{k}", tmp_path / f"py{k}"
        result = cli("render", "--display", SMALL, "--spp", 1, "-o", by_cli,
                     *[o.replace("{out}", str(by_cli)) for o in options])
        assert result.returncode == 0, result.stderr
        parallax.render_files(by_python, display=SMALL, spp=1,
                              **{key: value.replace("{out}", str(by_python))
                                 if isinstance(value, str) else value
                                 for key, value in keywords.items()})
        same_files(by_cli, by_python)


def test_solved_layers_and_direct_mapping_in_memory(scene, small, tmp_path):
    made = parallax.render(scene, small, spp=1, layers="nmf", rank=2, iterations=2, train_eyes=1)
    assert len(made.frames) == 2 and made.record["layers"]["rank"] == 2
    result = cli("render", "--display", SMALL, "--spp", 1, "--layers", "nmf", "--rank", 2,
                 "--iterations", 2, "--train-eyes", 1, "-o", tmp_path)
    assert result.returncode == 0, result.stderr
    for k, (image, mask) in enumerate(made.frames):
        assert np.array_equal(parallax.to_srgb8(image), rgb(read_png(tmp_path / f"image-{k + 1}.png")))
        assert np.array_equal(parallax.to_srgb8(mask), rgb(read_png(tmp_path / f"mask-{k + 1}.png")))
    direct = parallax.render(scene, small, spp=1, direct_mapping=True)
    assert direct.record["method"] == "direct-mapping"
    with pytest.raises(parallax.Error, match=r"^rank: time-multiplexed frames need layers nmf$"):
        parallax.render(scene, small, rank=2)


def solved_as_the_cli(scene, small, out, keywords, flags):
    """render(**keywords) of a small optimized-image solve and `render FLAGS` of the same: the
    same image layer (the CLI's PNG); returns the Python result."""
    made = parallax.render(scene, small, spp=1, layers="optimized-image", iterations=2,
                           train_eyes=1, **keywords)
    result = cli("render", "--display", SMALL, "--spp", 1, "--layers", "optimized-image",
                 "--iterations", 2, "--train-eyes", 1, *flags, "-o", out)
    assert result.returncode == 0, result.stderr
    assert np.array_equal(parallax.to_srgb8(made.image), rgb(read_png(out / "image.png")))
    return made


def test_layers_for_the_panels_optics_are_the_clis(scene, small, tmp_path):
    # render(diffuser=, color_filters=, pupil=, pupil_samples=) are render --diffuser,
    # --color-filters, --pupil, --pupil-samples: the same image layer, recorded, and each
    # another layer than the plain solve's; refused with slits.
    plain = parallax.render(scene, small, spp=1, layers="optimized-image", iterations=2,
                            train_eyes=1)
    made = solved_as_the_cli(scene, small, tmp_path / "foil", {"diffuser": 0.4},
                             ["--diffuser", 0.4])
    assert made.record["layers"]["diffuser_sigma_mm"] == 0.4
    assert not np.array_equal(plain.image, made.image)
    made = solved_as_the_cli(scene, small, tmp_path / "filters", {"color_filters": True},
                             ["--color-filters"])
    assert made.record["layers"]["color_filters"] is True
    assert not np.array_equal(plain.image, made.image)
    made = solved_as_the_cli(scene, small, tmp_path / "pupil", {"pupil": 4, "pupil_samples": 3},
                             ["--pupil", 4, "--pupil-samples", 3])
    assert made.record["layers"]["pupil_mm"] == 4 and made.record["layers"]["pupil_samples"] == 3
    for keyword, value in (("diffuser", 0.4), ("color_filters", True), ("pupil", 4)):
        with pytest.raises(parallax.Error, match=rf"^{keyword}: applies to layers optimized-image"):
            parallax.render(scene, small, **{keyword: value})
    with pytest.raises(parallax.Error, match=r"^pupil_samples: must be a whole number from 1"):
        parallax.render(scene, small, layers="optimized-image", pupil=4, pupil_samples=0)


def test_training_samples_are_the_clis(scene, small, tmp_path):
    # render(train_spp=, seed=) is render --train-spp --seed: the same image layer, recorded;
    # the training eyes' jitter follows the seed.
    made = solved_as_the_cli(scene, small, tmp_path / "spp", {"train_spp": 3, "seed": 7},
                             ["--train-spp", 3, "--seed", 7])
    assert made.record["layers"]["train_spp"] == 3
    other = parallax.render(scene, small, spp=1, layers="optimized-image", iterations=2,
                            train_eyes=1, train_spp=3, seed=8)
    assert not np.array_equal(made.image, other.image)
    with pytest.raises(parallax.Error, match=r"^train_spp: must be a whole number from 1 to 64"):
        parallax.render(scene, small, layers="nmf", train_spp=65)
    with pytest.raises(parallax.Error, match=r"^train_spp: applies to layers optimized-image"):
        parallax.render(scene, small, train_spp=2)


def test_estimate_memory_is_the_clis_estimate(scene, small, tmp_path):
    # The same figure as `parallax --estimate`, within what the two processes hold besides
    # (the interpreter and numpy, about 10-60 MiB); a bigger picture needs more, by its pixels.
    result = cli("--estimate", "view", "--size", "1000x1000", "--spp", 1, "-o", str(tmp_path / "v.png"))
    assert result.returncode == 0 and not (tmp_path / "v.png").exists()
    cli_bytes = int(result.stdout.split("memory, ")[1].split(" bytes")[0])
    small_view = parallax.estimate_memory(parallax.view, size=(1000, 1000), spp=1)
    assert isinstance(small_view, int) and abs(small_view - cli_bytes) < 300 * 2**20
    big_view = parallax.estimate_memory(parallax.view, size=(2000, 2000), spp=1)
    # Float film and its array, per pixel; the estimate is the process's peak so far where that is
    # larger (under ASan the peak hides a 1000x1000 view's work): the lower bound only when the
    # smaller view's work shows above a 1x1 view's.
    tiny_view = parallax.estimate_memory(parallax.view, size=(1, 1), spp=1)
    assert tiny_view <= small_view <= big_view < small_view + 3e6 * 30
    if small_view - tiny_view > 1e6 * 12:
        assert big_view - small_view > 3e6 * 12
    assert parallax.estimate_memory(parallax.render, scene, small, spp=1) > 0
    with pytest.raises(parallax.Error, match="makes no memory estimate"):
        parallax.estimate_memory(parallax.design, small)
    assert parallax.view(size=(8, 8), spp=1).shape == (8, 8, 3)  # estimate-only is off again


def test_limits_are_the_clis(scene, small):
    # --max-time's refusal, spelled as Python's keywords; 0 restores the default.
    result = cli("render", "--display", SMALL, "--spp", 4096, "--max-time", "0.001", "-o", "/nonexistent")
    assert result.returncode == 2
    parallax.set_limits(max_time=0.001)
    try:
        with pytest.raises(parallax.Error) as caught:
            parallax.render(scene, small, spp=4096)
    finally:
        parallax.set_limits()
    assert str(caught.value) == as_keywords(result.stderr.strip()[len("error: "):])
    assert str(caught.value).startswith("spp=4096: needs ") and "raise max_time" in str(caught.value)
    with pytest.raises(parallax.Error, match="^max_memory: "):
        parallax.set_limits(max_memory=-1)


def test_assimp_crashes_are_refused_and_the_interpreter_goes_on():
    # assimp runs in a child process (docs/import.md, "Isolation"): its crash, abort or runaway
    # allocation is a parallax.Error naming the file, the CLI's line spelled as keywords.
    files = SOURCE / "fuzz" / "regressions" / "fuzz_assimp"
    parallax.set_limits(max_memory=1)
    try:
        # Debian 12's assimp (5.2) frees twice reading the FBX; 5.4 (Debian 13's) reads it.
        assimp = re.search(r"assimp (\d+)\.(\d+)", cli("--version").stdout)
        assert assimp
        cases = [("crash-cb1d3a87.x", "the X importer (assimp) crashed reading it (signal 11"),
                 ("timeout-25565c.dae", "the DAE importer (assimp) ran out of its memory "
                  "budget reading it (1 GiB, max_memory)")]
        if (int(assimp[1]), int(assimp[2])) < (5, 4):
            cases.append(("crash-2c65eb78.fbx", "the FBX importer (assimp) crashed reading it ("))
        else:
            assert parallax.load_scene(str(files / "crash-2c65eb78.fbx")) is not None
        for name, what in cases:
            with pytest.raises(parallax.Error) as caught:
                parallax.load_scene(str(files / name))
            assert str(caught.value).startswith(f"{files / name}: {what}")
            result = cli("--max-memory", "1", "info", files / name)
            assert result.returncode == 2
            # Which signal a heap corruption ends in depends on the heap the child inherits
            # (Python's or the CLI's): a double free may abort or crash. The line is the same.
            def without_signal(text):
                return re.sub(r"\(signal \d+, SIG[A-Z]+\)", "(signal)", text)
            assert without_signal(str(caught.value)) == without_signal(
                as_keywords(result.stderr.strip()[len("error: "):]))
    finally:
        parallax.set_limits()


def test_lenticular_render_is_the_cli_render(scene, tmp_path):
    # A Looking Glass calibration on a quarter-size panel (fast), read by both paths.
    path, display = quarter_portrait(tmp_path)
    assert display.kind == "lenticular"
    result = cli("render", "--display", path, "--spp", 1, "-o", tmp_path / "out")
    assert result.returncode == 0, result.stderr
    made = parallax.render(scene, display, spp=1)
    assert made.mask is None and made.mask_srgb8 is None
    assert made.image.shape == (512, 384, 3)
    assert np.array_equal(made.image_srgb8, rgb(read_png(tmp_path / "out" / "image.png")))
    assert made.record["design"] == json.loads((tmp_path / "out" / "render.json").read_text())["design"]
    seen = parallax.simulate(made.image_srgb8, None, display, eye=(0, 0, 600))
    assert seen.shape == (512, 384, 3)
    with pytest.raises(parallax.Error, match="^" + as_keywords("--pupil: applies to the two-layer")):
        parallax.simulate(made.image, None, display, eye=(0, 0, 600), pupil=3)
    # A render made for another reading of the optics: the CLI's, byte for byte.
    result = cli("render", "--display", path, "--spp", 1, "--lens-spot", 0, "--bundles",
                 "parallel", "-o", tmp_path / "ideal")
    assert result.returncode == 0, result.stderr
    ideal = parallax.render(scene, display, spp=1, lens_spot=0, bundles="parallel")
    assert np.array_equal(ideal.image_srgb8, rgb(read_png(tmp_path / "ideal" / "image.png")))
    assert ideal.record["design"]["optics"]["bundles"] == "parallel"
    assert ideal.record["design"]["optics"]["lens_spot_subpixels"] == 0
    assert not np.array_equal(ideal.image_srgb8, made.image_srgb8)
    # A quilt interlaced for those optics: the CLI's too.
    result = cli("render", "--display", path, "--spp", 1, "--quilt", "4x2", "--size", "96x128",
                 "-o", tmp_path / "q")
    assert result.returncode == 0, result.stderr
    quilt_file = next((tmp_path / "q").glob("quilt_*.png"))
    result = cli("interlace", quilt_file, "--display", path, "--bundles", "parallel", "-o",
                 tmp_path / "qi")
    assert result.returncode == 0, result.stderr
    interlaced = parallax.interlace(quilt=rgb(read_png(quilt_file)), display=display,
                                    quilt_layout=(4, 2), bundles="parallel")
    assert np.array_equal(interlaced.image_srgb8, rgb(read_png(tmp_path / "qi" / "image.png")))
    assert interlaced.record["design"]["optics"]["bundles"] == "parallel"
    with pytest.raises(parallax.Error, match="^" + as_keywords("--lens-spot: applies to lenticular")):
        parallax.render(scene, parallax.load_display(), spp=1, lens_spot=1)


def test_lenticular_framing_is_the_cli_framing(scene, tmp_path):
    # fit, focus and depth_budget on a Looking Glass panel, refused before (docs/lenticular.md,
    # "Depth of field"): design's figures are the CLI's, and a render's framing is the CLI's.
    spheres = SOURCE / "scenes" / "spheres.json"
    portrait = parallax.load_display("lkg:portrait")
    expected = json.loads(cli("design", "lkg:portrait", "--json", "--scene", spheres,
                              "--fit", "depth", "--focus", 5).stdout)
    got = parallax.design(portrait, scene=parallax.load_scene(str(spheres)), fit="depth", focus=5)
    assert got == expected
    assert got["depth_of_field_mm"] == pytest.approx(12.799, abs=1e-3)
    assert got["scene"]["focus_mm"] == 5 and got["scene"]["within_budget"]
    path, display = quarter_portrait(tmp_path)
    made = parallax.render(scene, display, spp=1, fit="depth", depth_budget=8)
    framing = made.record["framing"]
    assert 0 < framing["depth_scale"] < 1
    assert max(framing["shown_near_mm"], -framing["shown_far_mm"]) == pytest.approx(8)
    result = cli("render", "--display", path, "--spp", 1, "--fit", "depth", "--depth-budget", 8,
                 "-o", tmp_path / "out")
    assert result.returncode == 0, result.stderr
    assert np.array_equal(made.image_srgb8, rgb(read_png(tmp_path / "out" / "image.png")))
    assert json.loads((tmp_path / "out" / "render.json").read_text())["framing"] == framing


def cli_error(*args):
    result = cli(*args)
    assert result.returncode == 2 and result.stderr.startswith("error: ")
    return result.stderr.strip()[len("error: "):]


def as_keywords(cli_line):
    """The CLI's error line as Python says it: options become keywords (--filter-width ->
    filter_width, "--spp 16:" -> "spp=16:")."""
    line = re.sub(r"^--([a-z-]+) (\S+):", lambda m: m.group(1).replace("-", "_") + "=" + m.group(2) + ":",
                  cli_line)
    return re.sub(r"--([a-z][a-z-]*)", lambda m: m.group(1).replace("-", "_"), line)


def test_errors_carry_the_cli_lines(scene, small, tmp_path):
    missing = str(tmp_path / "missing.json")
    with pytest.raises(parallax.Error) as caught:
        parallax.load_display(missing)
    assert str(caught.value) == cli_error("design", missing)
    bad = tmp_path / "bad.json"
    bad.write_text('{"image_layer": {"resolution": [320, 180], "pixel_pitch_mm": 0.27}, '
                   '"gap_mm": 0, "view_distance_mm": 600, "views": 9}')
    with pytest.raises(parallax.Error) as caught:
        parallax.load_display(str(bad))
    assert str(caught.value) == cli_error("design", bad)
    assert "gap_mm" in str(caught.value)
    with pytest.raises(parallax.Error) as caught:
        parallax.load_scene(str(tmp_path / "missing.obj"))
    assert str(caught.value) == cli_error("view", tmp_path / "missing.obj")
    with pytest.raises(parallax.Error) as caught:
        parallax.render(scene, small, filter="sideways")
    assert str(caught.value) == as_keywords(
        cli_error("render", "--display", SMALL, "--filter", "sideways"))
    assert str(caught.value).startswith("filter: expected none, view")
    with pytest.raises(parallax.Error) as caught:
        parallax.render(scene, small, fit="sideways")
    assert str(caught.value) == as_keywords(
        cli_error("render", "--display", SMALL, "--fit", "sideways"))
    assert str(caught.value).startswith("fit: expected window, depth")
    assert isinstance(caught.value, ValueError)


def test_bad_arrays_and_keywords_are_refused(layers, small):
    with pytest.raises(ValueError, match=r"^image: expected an H x W x 3 .* got shape \(180, 320, 4\)$"):
        parallax.simulate(np.zeros((180, 320, 4), np.float32), layers.mask, small, eye=EYE)
    with pytest.raises(ValueError, match=r"^mask: expected float32 \(linear\) or uint8 \(sRGB\)"):
        parallax.simulate(layers.image, layers.mask.astype(np.int64), small, eye=EYE)
    with pytest.raises(ValueError, match="^mask: a barrier display needs"):
        parallax.simulate(layers.image, None, small, eye=EYE)
    with pytest.raises(parallax.Error, match="in front"):
        parallax.simulate(layers.image, layers.mask, small, eye=(0, 0, -5))
    with pytest.raises(TypeError):
        parallax.render(spp=1, sample_count=4)
    with pytest.raises(TypeError):
        parallax.simulate(layers.image, layers.mask, small, eye=EYE, pupill=3)


def test_nonsense_layers_and_solver_settings_are_refused(scene, layers, small):
    # Layers no panel shows: NaN, infinite or negative light, a transmittance above 1; each
    # names the argument and the first bad pixel (jobs::checkLayerValues, also the CLI's).
    image = layers.image.copy()
    image[0, 3, 1] = np.nan
    with pytest.raises(parallax.Error, match=r"^image: pixel \(3, 0\) channel 1 is NaN"):
        parallax.simulate(image, layers.mask, small, eye=EYE)
    with pytest.raises(parallax.Error, match=r"^image: .* is infinite"):
        parallax.simulate(np.full_like(layers.image, np.inf), layers.mask, small, eye=EYE)
    with pytest.raises(parallax.Error, match=r"^mask: pixel \(0, 0\) channel 0 is -0.5"):
        parallax.simulate(layers.image, np.full_like(layers.mask, -0.5), small, eye=EYE)
    with pytest.raises(parallax.Error, match=r"^mask: .* is 2: a transmittance is from 0 to 1"):
        parallax.simulate(layers.image, np.full_like(layers.mask, 2.0), small, eye=EYE)
    with pytest.raises(parallax.Error, match=r"^image: .* is -1"):
        parallax.quality(scene, small, -np.ones_like(layers.image), layers.mask, eyes=[EYE])
    # An image layer above 1 (a linear layer's highlights) is taken.
    assert np.isfinite(parallax.simulate(layers.image * 2, layers.mask, small, eye=EYE)).all()
    # 0 iterations is no default; solver settings without a solver are not ignored.
    with pytest.raises(parallax.Error, match="^iterations: must be between 1 and 1000"):
        parallax.render(scene, small, spp=1, layers="nmf", iterations=0)
    with pytest.raises(parallax.Error, match="^iterations: applies to layers optimized-image or nmf"):
        parallax.render(scene, small, spp=1, iterations=5)
    # Keywords the command line's validators check, checked for Python too.
    nan = float("nan")
    with pytest.raises(parallax.Error, match="^eye: must be finite and within 1e6 mm"):
        parallax.simulate(layers.image, layers.mask, small, eye=(nan, 0, 600))
    with pytest.raises(parallax.Error, match="^eye: must be finite and within 1e6 mm"):
        parallax.simulate(layers.image, layers.mask, small, eye=(1e300, 0, 600))
    with pytest.raises(parallax.Error, match=r"^threads=100000: must be 0 \(all cores\) to"):
        parallax.simulate(layers.image, layers.mask, small, eye=EYE, threads=100000)
    with pytest.raises(parallax.Error, match=r"^threads=100000: must be 0 \(all cores\) to"):
        parallax.render(scene, small, spp=1, threads=100000)
    with pytest.raises(parallax.Error, match="^eye: must be three finite numbers"):
        parallax.view(scene, size=(8, 8), spp=1, eye=(nan, 0, 0))
    with pytest.raises(parallax.Error, match="^display_eye: must be three finite numbers"):
        parallax.ideal_view(scene, small, eye=(nan, 0, 600), spp=1, size=(8, 8))
    with pytest.raises(parallax.Error, match="^look_at: the camera would look at its own position"):
        parallax.view(scene, size=(8, 8), spp=1, eye=(0, 0, 5), look_at=(0, 0, 5))
    with pytest.raises(parallax.Error, match="^distance: applies to lenticular displays"):
        parallax.render(scene, small, spp=1, distance=nan)
    with pytest.raises(parallax.Error, match="^adaptive_threshold: must be a number from 0 to 255"):
        parallax.render(scene, small, spp=1, adaptive=True, adaptive_threshold=nan)
    with pytest.raises(parallax.Error, match="^adaptive_threshold: applies with adaptive=True"):
        parallax.render(scene, small, spp=1, adaptive_threshold=3.0)
    with pytest.raises(parallax.Error, match="^seed: must be a whole number from 0 to 2"):
        parallax.render(scene, small, spp=1, seed=-1)


def test_other_threads_run_while_rendering(scene):
    def render_beside_a_counter(spp):
        ticks = []
        stop = threading.Event()

        def count():
            while not stop.is_set():
                ticks.append(time.perf_counter())

        counter = threading.Thread(target=count)
        counter.start()
        try:
            time.sleep(0.05)
            start = time.perf_counter()
            parallax.view(scene, size=(640, 360), spp=spp)
            end = time.perf_counter()
        finally:
            stop.set()
            counter.join()
        # The counter's longest pause inside the call: with the GIL held through the render it
        # could not run until the call returned (a pause as long as the render); released, it
        # pauses only for the argument conversion and the copy into the array.
        inside = [start] + [t for t in ticks if start < t < end] + [end]
        return end - start, max(b - a for a, b in zip(inside, inside[1:]))

    # Long enough to tell the two apart, however fast this machine and its Embree are.
    spp = 64
    duration, longest = render_beside_a_counter(spp)
    while duration < 0.2 and spp < 4096:
        spp *= 4
        duration, longest = render_beside_a_counter(spp)
    assert duration >= 0.2, f"{spp} spp took only {duration:.3f} s"
    assert longest < 0.5 * duration, f"paused {longest:.3f} s of {duration:.3f} s"


def test_two_threads_render_at_once_as_one_alone(scene, small):
    alone = [parallax.view(scene, size=(200, 100), spp=16), parallax.render(scene, small, spp=4).image]
    together = [None, None]

    def first():
        together[0] = parallax.view(scene, size=(200, 100), spp=16)

    def second():
        together[1] = parallax.render(scene, small, spp=4).image

    threads = [threading.Thread(target=first), threading.Thread(target=second)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all(np.array_equal(a, b) for a, b in zip(alone, together))


def test_the_installed_package_imports(tmp_path):
    # `cmake --install BUILD --component python` into a fresh prefix, imported from elsewhere
    # with nothing of the build tree on the path.
    build, cmake = os.environ.get("PARALLAX_BUILD_DIR"), os.environ.get("PARALLAX_CMAKE")
    assert build and cmake, "CTest sets PARALLAX_BUILD_DIR and PARALLAX_CMAKE"
    prefix = tmp_path / "prefix"
    installed = subprocess.run([cmake, "--install", build, "--prefix", prefix, "--component",
                                "python"], capture_output=True, text=True)
    assert installed.returncode == 0, installed.stderr
    site = prefix / os.environ["PARALLAX_PYTHON_INSTALL_DIR"]
    assert (site / "parallax" / "__init__.py").is_file()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(site)
    code = "import parallax; print(parallax.__file__); print(parallax.design()['views'])"
    ran = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                         cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr
    where, views = ran.stdout.split()
    assert Path(where).is_relative_to(site) and float(views) == 9


def test_a_user_prefix_install_imports_without_a_path(tmp_path):
    # docs/install.md's `cmake --install build --prefix ~/.local`: Python's user base, whose
    # site-packages (not the system prefixes' dist-packages) the interpreter reads by itself.
    build, cmake = os.environ.get("PARALLAX_BUILD_DIR"), os.environ.get("PARALLAX_CMAKE")
    assert build and cmake, "CTest sets PARALLAX_BUILD_DIR and PARALLAX_CMAKE"
    user_base = tmp_path / "home-local"
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "DESTDIR")}
    env["PYTHONUSERBASE"] = str(user_base)
    installed = subprocess.run([cmake, "--install", build, "--prefix", user_base, "--component",
                                "python"], capture_output=True, text=True, env=env)
    assert installed.returncode == 0, installed.stderr
    code = "import parallax; print(parallax.__file__)"
    ran = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                         cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr
    assert Path(ran.stdout.strip()).is_relative_to(user_base)
    # Any other prefix is left as it was: no .pth is written outside the user base.
    other = tmp_path / "prefix"
    subprocess.run([cmake, "--install", build, "--prefix", other, "--component", "python"],
                   capture_output=True, text=True, env=env, check=True)
    assert not list(other.rglob("*.pth"))


def test_the_docs_example_runs(tmp_path, monkeypatch):
    text = (SOURCE / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) >= 5
    monkeypatch.chdir(SOURCE)
    namespace = {"__name__": "docs_example"}
    for block in blocks:
        if "matplotlib" in block:  # plotting is optional (not a dependency)
            continue
        exec(compile(block, "docs/python.md", "exec"), namespace)
    assert namespace["layers"].image.shape == (180, 320, 3)
    assert len(namespace["figures"]["eyes"]) == 3


# ---- interlace, calibration, lenticular simulate (jobs/interlace_job.h, jobs/calibrate_job.h)

def quarter_portrait(folder):
    """A Looking Glass calibration on a quarter-size panel (fast): its path and its Display."""
    calibration = json.loads((SOURCE / "displays" / "lenticular" / "portrait-like.json").read_text())
    calibration["screenW"]["value"] /= 4
    calibration["screenH"]["value"] /= 4
    path = Path(folder) / "visual.json"
    path.write_text(json.dumps(calibration))
    return path, parallax.load_display(str(path))


@pytest.fixture(scope="module")
def cli_quilt(tmp_path_factory):
    """A 3x3 quilt of 64x36 views from the CLI: its PNG file."""
    out = tmp_path_factory.mktemp("quilt")
    result = cli("render", "--quilt", "3x3", "--size", "64x36", "--spp", 1, "--display", SMALL,
                 "-o", out)
    assert result.returncode == 0, result.stderr
    return out / "quilt_qs3x3a1.7778.png"


def same_tool_files(mine, theirs):
    """Every file of the CLI's folder is in mine, byte for byte (render.json but its time)."""
    names = sorted(p.name for p in Path(theirs).iterdir())
    assert sorted(p.name for p in Path(mine).iterdir()) == names
    for name in names:
        a, b = (Path(mine) / name).read_bytes(), (Path(theirs) / name).read_bytes()
        if name == "render.json":
            a, b = (re.sub(rb'"created": "[^"]*"', b"", x) for x in (a, b))
        assert a == b, name


def test_interlace_is_the_cli_interlace(small, cli_quilt, tmp_path):
    result = cli("interlace", cli_quilt, "--display", SMALL, "-o", tmp_path / "cli")
    assert result.returncode == 0, result.stderr
    quilt = rgb(read_png(cli_quilt))
    made = parallax.interlace(quilt=quilt, display=small, quilt_layout=(3, 3))
    assert made.image.shape == (180, 320, 3) and made.mask.shape == (180, 320, 3)
    assert np.array_equal(made.image_srgb8, rgb(read_png(tmp_path / "cli" / "image.png")))
    assert np.array_equal(made.mask_srgb8, rgb(read_png(tmp_path / "cli" / "mask.png")))
    record = json.loads((tmp_path / "cli" / "render.json").read_text())
    assert made.record["cameras"] == record["cameras"] and made.record["design"] == record["design"]
    # The same views one by one (tiles from the bottom-left, leftmost camera first).
    tiles = [quilt[36 * (2 - k // 3):36 * (3 - k // 3), 64 * (k % 3):64 * (k % 3 + 1)]
             for k in range(9)]
    assert np.array_equal(parallax.interlace(tiles, small).image, made.image)
    # To files: the CLI's files.
    written = parallax.interlace_files(tmp_path / "py", quilt=cli_quilt, display=SMALL)
    assert written["inputs"] == record["inputs"]
    same_tool_files(tmp_path / "py", tmp_path / "cli")


def test_filter_none_with_spp_says_so_with_keywords(scene, small, capfd):
    """The CLI's note, the keywords where the CLI names its options."""
    parallax.render(scene, small, filter="none", spp=4)
    err = capfd.readouterr().err
    assert "note: filter none casts each film pixel's central ray only" in err
    assert "so spp 4 renders as 1 sample a pixel" in err
    assert "--filter" not in err and "--spp" not in err


def test_interlace_nearest_onto_a_lenticular_panel(cli_quilt, tmp_path):
    """view_resampling="nearest": each subpixel's nearest view, not the blend (as the CLI)."""
    path, display = quarter_portrait(tmp_path)
    quilt = rgb(read_png(cli_quilt))
    linear = parallax.interlace(quilt=quilt, display=display, quilt_layout=(3, 3))
    nearest = parallax.interlace(quilt=quilt, display=display, quilt_layout=(3, 3),
                                 view_resampling="nearest")
    assert not np.array_equal(nearest.image, linear.image)
    assert nearest.record["inputs"]["view_resampling"] == "nearest"
    result = cli("interlace", cli_quilt, "--display", path, "--view-resampling", "nearest",
                 "-o", tmp_path / "cli")
    assert result.returncode == 0, result.stderr
    assert np.array_equal(nearest.image_srgb8, rgb(read_png(tmp_path / "cli" / "image.png")))


def test_interlace_onto_a_lenticular_panel_is_the_cli_interlace(cli_quilt, tmp_path):
    path, display = quarter_portrait(tmp_path)
    result = cli("interlace", cli_quilt, "--display", path, "--linear", "-o", tmp_path / "cli")
    assert result.returncode == 0, result.stderr
    made = parallax.interlace(quilt=rgb(read_png(cli_quilt)), display=display,
                              quilt_layout=(3, 3))
    assert made.mask is None and made.image.shape == (512, 384, 3)
    assert np.array_equal(made.image_srgb8, rgb(read_png(tmp_path / "cli" / "image.png")))
    parallax.interlace_files(tmp_path / "py", quilt=cli_quilt, display=path, linear=True)
    same_tool_files(tmp_path / "py", tmp_path / "cli")


def test_calibration_patterns_are_the_cli_patterns(small, tmp_path):
    result = cli("calibrate", "patterns", "--display", SMALL, "--steps", 3, "--duty", 0.5,
                 "-o", tmp_path / "cli")
    assert result.returncode == 0, result.stderr
    made = parallax.calibration_patterns(small, period_steps=3, duty=0.5)
    assert made.index == json.loads((tmp_path / "cli" / "index.json").read_text())
    assert made.readme == (tmp_path / "cli" / "README.txt").read_text()
    assert [name for name, _ in made.pictures] == [p["file"] for p in made.index["patterns"]]
    assert sum(name.startswith("mask-period-") for name, _ in made.pictures) == 3
    for name, picture in made.pictures:
        assert picture.shape == (180, 320, 3) and picture.dtype == np.float32
        assert np.array_equal(parallax.to_srgb8(picture), rgb(read_png(tmp_path / "cli" / name))), name
    index = parallax.calibration_patterns_files(tmp_path / "py", SMALL, period_steps=3, duty=0.5)
    assert index == made.index
    same_tool_files(tmp_path / "py", tmp_path / "cli")


def test_photo_shots_are_the_cli_shots_and_photos_are_refused_as_the_cli_refuses(tmp_path):
    for display, name in [(None, "barrier"), ("lkg:portrait", "lenticular")]:
        extra = [] if display is None else ["--display", display]
        result = cli("calibrate", "patterns", "--photo", *extra, "-o", tmp_path / f"cli-{name}")
        assert result.returncode == 0, result.stderr
        index = parallax.calibration_photo_patterns(tmp_path / f"py-{name}", display)
        assert index["kind"] == name
        assert index == json.loads((tmp_path / f"cli-{name}" / "index.json").read_text())
        same_tool_files(tmp_path / f"py-{name}", tmp_path / f"cli-{name}")
    # A photo that is not a photo: the same one line as the command line's, nothing written.
    bad = tmp_path / "grid-1.jpg"
    bad.write_text("not a photo")
    result = cli("calibrate", "photo", "--shots", tmp_path / "cli-barrier", bad,
                 "-o", tmp_path / "cli.json")
    assert result.returncode == 2
    with pytest.raises(parallax.Error) as raised:
        parallax.calibrate_photo(tmp_path / "py-barrier", [bad], output=tmp_path / "py.json")
    assert str(raised.value) in result.stderr
    assert "not a JPEG or PNG" in str(raised.value)
    assert not (tmp_path / "py.json").exists() and not (tmp_path / "cli.json").exists()
    # The seat check refuses as the command line does: barrier shots, a photo that is not one.
    lens = tmp_path / "lens-1.jpg"
    lens.write_text("not a photo")
    for shots, photo, text in [("barrier", bad, "holds barrier shots"),
                               ("lenticular", lens, "not a JPEG or PNG")]:
        result = cli("calibrate", "check", "--shots", tmp_path / f"cli-{shots}", photo)
        assert result.returncode == 2
        with pytest.raises(parallax.Error) as raised:
            parallax.calibration_check(tmp_path / f"py-{shots}", [photo])
        assert text in str(raised.value) and text in result.stderr


def test_lenticular_simulate_is_the_cli_simulate(cli_quilt, tmp_path):
    path, display = quarter_portrait(tmp_path)
    assert cli("interlace", cli_quilt, "--display", path, "-o", tmp_path / "set").returncode == 0
    panel = rgb(read_png(tmp_path / "set" / "image.png"))
    for eye, distance, extra in [((30, -5, 900), 0, ["--eye", "30,-5,900"]),
                                 (None, 800, ["--distance", 800])]:
        out = tmp_path / "seen.png"
        result = cli("lenticular", "simulate", tmp_path / "set", *extra, "-o", out)
        assert result.returncode == 0, result.stderr
        seen = parallax.lenticular_simulate(panel, display, eye=eye, distance=distance)
        assert seen.shape == (512, 384, 3)
        assert np.array_equal(parallax.to_srgb8(seen), rgb(read_png(out)))
    # The lens optics' readings (docs/lenticular.md, "The optics"): the same keywords as the
    # options, the same pictures, and a reading other than the display's sees another picture.
    readings = {}
    for spot, bundles in [(0, "parallel"), (3, "converging")]:
        out = tmp_path / f"seen-{spot}.png"
        result = cli("lenticular", "simulate", tmp_path / "set", "--lens-spot", spot,
                     "--bundles", bundles, "-o", out)
        assert result.returncode == 0, result.stderr
        seen = parallax.lenticular_simulate(panel, display, lens_spot=spot, bundles=bundles)
        assert np.array_equal(parallax.to_srgb8(seen), rgb(read_png(out)))
        readings[spot] = seen
        pictures = parallax.simulate(panel, None, display, eye=(0, 0, 1374), lens_spot=spot,
                                     bundles=bundles)
        assert pictures.shape == (512, 384, 3)
    assert not np.array_equal(readings[0], readings[3])
    with pytest.raises(parallax.Error, match=r"^bundles.*expected parallel or converging"):
        parallax.lenticular_simulate(panel, display, bundles="sideways")
    with pytest.raises(parallax.Error, match="^lens_spot: "):
        parallax.simulate(panel, None, display, eye=(0, 0, 900), lens_spot=20)


def test_tool_errors_name_their_keywords(small, cli_quilt, tmp_path):
    with pytest.raises(parallax.Error) as caught:
        parallax.interlace(quilt=rgb(read_png(cli_quilt)), display=small, quilt_layout=(3, 3),
                           view_resampling="cubic")
    assert str(caught.value) == as_keywords(
        cli_error("interlace", cli_quilt, "--display", SMALL, "--view-resampling", "cubic",
                  "-o", tmp_path / "x"))
    assert str(caught.value).startswith("view_resampling: expected nearest or linear")
    with pytest.raises(parallax.Error) as caught:
        parallax.calibration_patterns(small, from_px=8.8, to_px=9.1)
    line = cli_error("calibrate", "patterns", "--display", SMALL, "--from", 8.8, "--to", 9.1,
                     "-o", tmp_path / "y")
    assert str(caught.value) == line.replace("--from", "from_px")
    assert str(caught.value).startswith("from_px: G1 needs")
    path, display = quarter_portrait(tmp_path)
    with pytest.raises(parallax.Error, match=r"^eye: the eye must be in front"):
        parallax.lenticular_simulate(np.zeros((512, 384, 3), np.float32), display, eye=(0, 0, -5))
    with pytest.raises(parallax.Error, match="^quilt_layout: "):
        parallax.interlace(quilt=np.zeros((36, 64, 3), np.float32), display=small)
    with pytest.raises(TypeError):
        parallax.calibration_patterns(small, steps=3)


def test_splats_are_the_cli_splats_and_render(tmp_path):
    """make_splats writes the command's file byte for byte; a splat file loads as a scene whose
    Gaussians show over the background in view, and render takes it as any scene."""
    made = parallax.make_splats(tmp_path / "py.ply", "mesh", count=2000, seed=3)
    assert made["gaussians"] == 2000 and made["sh_degree"] == 0
    cli("splats", "from-mesh", "--count", "2000", "--seed", "3", "-o", str(tmp_path / "cli.ply"))
    assert (tmp_path / "py.ply").read_bytes() == (tmp_path / "cli.ply").read_bytes()
    scene = parallax.load_scene(str(tmp_path / "py.ply"))
    picture = parallax.view(scene, size=(64, 36), spp=1)
    background = parallax.view(parallax.load_scene(str(tmp_path / "py.ply")), size=(64, 36),
                               spp=1, eye=(0.0, 0.0, -1e4))  # looking away: the background
    covered = (np.abs(picture - background).max(axis=2) > 0.01).mean()
    assert covered > 0.03  # the built-in scene's box and floor, as splats (7.5 %)
    with pytest.raises(parallax.Error, match="source"):
        parallax.make_splats(tmp_path / "bad.ply", "video")
