"""parallax: ray tracing for glasses-free 3-D displays, from Python (docs/python.md).

Pictures are numpy arrays of shape (H, W, 3): float32 linear RGB out of every function
(row 0 at the top); in, float32/float64 linear RGB or uint8 sRGB codes (as in the PNG files).
Bad input raises parallax.Error (a ValueError) with the command line's one-line message.
The GIL is released while rays are traced and eyes simulated.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from typing import Optional, Sequence, Tuple

import numpy as np

from . import _parallax
from ._parallax import (Display, Error, Scene, __version__, load_display, load_scene, set_limits,
                        version)

__all__ = [
    "Display", "Error", "Scene", "RenderResult", "QuiltResult", "load_scene", "load_display",
    "design", "render", "render_files", "view", "ideal_view", "quilt", "simulate", "sweep_eyes", "sweep",
    "quality", "to_srgb8", "version", "__version__", "set_limits", "estimate_memory", "interlace", "interlace_files", "CalibrationPatterns", "calibration_patterns", "calibration_patterns_files", "calibration_photo_patterns", "calibrate_photo", "calibration_check", "lenticular_simulate",
]

Eye = Tuple[float, float, float]


def estimate_memory(function, *args, **kwargs) -> int:
    """What `function(*args, **kwargs)` would need: its estimated peak resident memory in bytes
    (this process's, as `parallax --estimate` prints the command's), checked against
    set_limits(max_memory=...) as the call itself would be. The call stops at its estimate,
    before its work allocates; nothing is written. For render, render_files, view, quilt,
    simulate and sweep (docs/inputs.md, "Memory")."""
    _parallax._set_estimate_only(True)
    try:
        function(*args, **kwargs)
    except _parallax._Estimated as stop:
        return int(stop.args[0])
    finally:
        _parallax._set_estimate_only(False)
    raise Error(f"{getattr(function, '__name__', function)}: makes no memory estimate")


def _display(display: Optional[Display]) -> Display:
    return load_display() if display is None else display


def _framing(fit: Optional[str], focus, depth_budget) -> dict:
    # The CLI's --fit/--focus/--depth-budget texts: "" is the scene's own choice.
    text = lambda value: "" if value is None else str(value)
    return {"fit": text(fit), "focus": text(focus), "depth_budget": text(depth_budget)}


def to_srgb8(linear: np.ndarray) -> np.ndarray:
    """Linear float RGB -> uint8 sRGB codes, exactly as the PNG writer converts them."""
    return _parallax._to_srgb8(np.ascontiguousarray(linear, dtype=np.float32))


def design(display: Optional[Display] = None, *, depth: float = 0.0,
           scene: Optional[Scene] = None, fit: Optional[str] = None, focus=None,
           depth_budget=None) -> dict:
    """The derived design, as `parallax design --json [--depth MM] [--scene S]` prints it."""
    return json.loads(_parallax._design_json(_display(display), depth=depth, scene=scene,
                                             **_framing(fit, focus, depth_budget)))


@dataclass
class RenderResult:
    """The display's layers (float32 linear, H x W x 3) and render.json's record.

    A lenticular panel has one layer: its interlaced picture is `image`, `mask` is None.
    Time-multiplexed layers (layers="nmf", rank > 1) are `frames`, (image, mask) pairs shown in
    turn; `image` and `mask` are the first.
    """
    image: np.ndarray
    mask: Optional[np.ndarray]
    record: dict = field(repr=False)
    frames: list = field(default_factory=list, repr=False)

    @property
    def image_srgb8(self) -> np.ndarray:
        return to_srgb8(self.image)

    @property
    def mask_srgb8(self) -> Optional[np.ndarray]:
        return None if self.mask is None else to_srgb8(self.mask)


@dataclass
class QuiltResult:
    """The quilt (float32 linear, tiles from the bottom-left) and its record (/quilt)."""
    quilt: np.ndarray
    record: dict = field(repr=False)


def _given(**keywords) -> dict:
    """The keywords the caller gave (None: the request's default)."""
    return {key: value for key, value in keywords.items() if value is not None}


def render(scene: Optional[Scene] = None, display: Optional[Display] = None, *,
           spp: int = 16, seed: int = 0, threads: int = 0, jitter: str = "auto",
           bounces: int = 0, adaptive: bool = False, adaptive_threshold: Optional[float] = None,
           filter: str = "view", filter_width: Optional[float] = None, subpixels: bool = False,
           direct_mapping: bool = False, layers: str = "slits", rank: int = 1,
           iterations: Optional[int] = None, brightness: float = 0.0, train_eyes: int = 2,
           train_distances: Optional[str] = None, train_spp: Optional[int] = None,
           layer_error: Optional[str] = None, distance: float = 0.0,
           lens_spot: Optional[float] = None, bundles: Optional[str] = None,
           fit: Optional[str] = None, focus=None, depth_budget=None,
           diffuser: Optional[float] = None, color_filters: bool = False,
           pupil: float = 0.0, pupil_samples: int = 16) -> RenderResult:
    """`parallax render`: the image and mask layers of a barrier display (the slits', direct
    mapping's, or content-adaptive layers solved for eyes across the view zone), or a lenticular
    panel's interlaced picture (`lenticular render`), made for the lens optics lens_spot and
    bundles (`--lens-spot`, `--bundles`; default: the display's own)."""
    frames, _, record = _parallax._render(
        scene if scene is not None else load_scene(), _display(display),
        **_given(spp=spp, seed=seed, threads=threads, jitter=jitter, bounces=bounces,
                 adaptive=adaptive, adaptive_threshold=adaptive_threshold, filter=filter,
                 filter_width=filter_width, subpixels=subpixels, direct_mapping=direct_mapping,
                 layers=layers, rank=rank, iterations=iterations, brightness=brightness,
                 train_eyes=train_eyes, train_distances=train_distances, train_spp=train_spp,
                 layer_error=layer_error, distance=distance,
                 lens_spot=lens_spot, bundles=bundles, diffuser=diffuser,
                 color_filters=color_filters, pupil=pupil, pupil_samples=pupil_samples),
        **_framing(fit, focus, depth_budget))
    image, mask = frames[0]
    return RenderResult(image, mask, json.loads(record), frames)


def render_files(output: str, scene: Optional[str] = None, display: Optional[str] = None, *,
                 camera: str = "", exposure: Optional[float] = None,
                 view_transform: Optional[str] = None, focus_on: str = "",
                 **keywords) -> dict:
    """`parallax render SCENE --display DISPLAY -o OUTPUT ...`: the same files, byte for byte:
    layers, quilts (quilt="auto" or (columns, rows), size=(w, h), linear=True), sequences
    (frames="A:B", turntable=DEGREES, duration, fps, chunk="K/N") and their video (video=FILE,
    video_codec, video_quality). `scene` and `display` are paths (None: the built-in ones);
    every keyword of render() is taken. Returns the record (OUTPUT/render.json) of one picture
    set, or {} for a sequence."""
    _parallax._render_files(str(output), None if scene is None else str(scene),
                            None if display is None else str(display), camera=camera,
                            exposure=exposure, view_transform=view_transform,
                            focus_on=focus_on, **_given(**keywords))
    record = os.path.join(str(output), "render.json")
    return json.load(open(record)) if os.path.exists(record) else {}


def view(scene: Optional[Scene] = None, *, eye: Optional[Sequence[float]] = None,
         look_at: Optional[Sequence[float]] = None, up: Optional[Sequence[float]] = None,
         fov: Optional[float] = None, size: Tuple[int, int] = (960, 540), spp: int = 16,
         seed: int = 0, threads: int = 0, jitter: str = "auto", bounces: int = 0,
         adaptive: bool = False) -> np.ndarray:
    """`parallax view`: an ordinary pinhole picture (scene units), float32 linear."""
    return _parallax._view(scene if scene is not None else load_scene(), eye=eye,
                           look_at=look_at, up=up, fov=fov, size=size, spp=spp, seed=seed,
                           threads=threads, jitter=jitter, bounces=bounces, adaptive=adaptive)


def ideal_view(scene: Optional[Scene] = None, display: Optional[Display] = None, *,
               eye: Sequence[float], size: Optional[Tuple[int, int]] = None, spp: int = 16,
               seed: int = 0, threads: int = 0, jitter: str = "auto", bounces: int = 0,
               adaptive: bool = False, fit: Optional[str] = None, focus=None,
               depth_budget=None) -> np.ndarray:
    """`parallax view --display-eye X,Y,Z`: the ideal picture through the display's window."""
    return _parallax._view(
        scene if scene is not None else load_scene(), display=_display(display),
        display_eye=tuple(eye), size=size, spp=spp, seed=seed, threads=threads, jitter=jitter,
        bounces=bounces, adaptive=adaptive, **_framing(fit, focus, depth_budget))


def quilt(scene: Optional[Scene] = None, display: Optional[Display] = None, *,
          layout: Optional[Tuple[int, int]] = None, size: Optional[Tuple[int, int]] = None,
          spp: int = 16, seed: int = 0, threads: int = 0, jitter: str = "auto",
          bounces: int = 0, adaptive: bool = False, fit: Optional[str] = None, focus=None,
          depth_budget=None) -> QuiltResult:
    """`parallax render --quilt CxR|auto [--size WxH]`: layout None is auto."""
    _, array, record = _parallax._render(
        scene if scene is not None else load_scene(), _display(display),
        quilt="auto" if layout is None else tuple(layout),
        **_given(size=None if size is None else tuple(size), spp=spp, seed=seed, threads=threads,
                 jitter=jitter, bounces=bounces, adaptive=adaptive),
        **_framing(fit, focus, depth_budget))
    return QuiltResult(array, json.loads(record))


def simulate(image: np.ndarray, mask: Optional[np.ndarray] = None,
             display: Optional[Display] = None, *, eye: Optional[Sequence[float]] = None,
             eyes: Optional[Sequence[Sequence[float]]] = None, **options) -> np.ndarray:
    """`parallax simulate --eye X,Y,Z`: what one eye (or each of `eyes`) sees, float32 linear.

    One eye gives an (H, W, 3) array, `eyes` an (N, H, W, 3) stack. Options: size, spp,
    pupil, pupil_samples, diffuser, color_filters, raw, raw_pixels, threads; on a lenticular
    panel lens_spot (the focal spot in subpixels, 0: an ideal lens) and bundles ("parallel" or
    "converging"), the optics it is read under (default: the display's).
    """
    if (eye is None) == (eyes is None):
        raise ValueError("simulate: give either eye=(x, y, z) or eyes=[...]")
    display = _display(display)
    if display.kind == "barrier" and mask is None:
        raise ValueError("mask: a barrier display needs the mask layer's array")
    pictures = _parallax._simulate(image, mask, display, eyes=[tuple(eye)] if eye is not None else [tuple(e) for e in eyes],
                                   **options)
    return pictures[0] if eye is not None else pictures


def sweep_eyes(display: Optional[Display] = None, count: int = 9, *, sweep_range: float = 1.0,
               distance: float = 0.0) -> list:
    """The eyes of `simulate --sweep N [--sweep-range F] [--sweep-distance MM]`, left first."""
    return [tuple(e) for e in _parallax._sweep_eyes(_display(display), count=count,
                                                   sweep_range=sweep_range, distance=distance)]


def sweep(image: np.ndarray, mask: Optional[np.ndarray] = None,
          display: Optional[Display] = None, count: int = 9, *, sweep_range: float = 1.0,
          distance: float = 0.0, **options) -> Tuple[list, np.ndarray]:
    """The eye moved across the view zone: (eyes, an (N, H, W, 3) stack of what each sees)."""
    eyes = sweep_eyes(display, count, sweep_range=sweep_range, distance=distance)
    return eyes, simulate(image, mask, display, eyes=eyes, **options)


def quality(scene: Optional[Scene], display: Optional[Display], image: np.ndarray,
            mask: Optional[np.ndarray] = None, *, eyes: Sequence[Sequence[float]],
            reference_spp: int = 4, fit: Optional[str] = None, focus=None,
            depth_budget=None, **options) -> dict:
    """`parallax simulate --reference --eye ... --json`: PSNR, SSIM, brightness, cross-talk."""
    return json.loads(_parallax._quality(
        scene if scene is not None else load_scene(), _display(display), image, mask,
        eyes=[tuple(e) for e in eyes], reference_spp=reference_spp,
        **_framing(fit, focus, depth_budget), **options))


# ---- interlace, calibration (jobs/interlace_job.h, jobs/calibrate_job.h)

def _layout(quilt_layout) -> Optional[Tuple[int, int]]:
    return None if quilt_layout is None else tuple(quilt_layout)


def interlace(views: Optional[Sequence[np.ndarray]] = None, display: Optional[Display] = None, *,
              quilt: Optional[np.ndarray] = None, quilt_layout: Optional[Tuple[int, int]] = None,
              subpixels: bool = False, view_resampling: str = "linear",
              lens_spot: Optional[float] = None, bundles: str = "") -> RenderResult:
    """`parallax interlace VIEW... | QUILT`: camera views (leftmost camera first, all of one
    size) or one quilt array (tiles from the bottom-left, cut by quilt_layout=(columns, rows))
    mapped onto the display: a barrier's image layer by direct mapping, with its mask, or a
    lenticular panel's picture (mask None), for the lens optics lens_spot and bundles (default:
    the display's)."""
    image, mask, record = _parallax._interlace(
        None if views is None else list(views), quilt, _display(display),
        quilt_layout=_layout(quilt_layout), subpixels=subpixels, view_resampling=view_resampling,
        lens_spot=lens_spot, bundles=bundles)
    return RenderResult(image, mask, json.loads(record), [(image, mask)])


def make_splats(output: str, source: str = "capture-like", *, scene: Optional[str] = None,
                count: int = 0, seed: int = 1) -> dict:
    """`parallax splats capture-like|from-mesh -o OUTPUT`: the same file, byte for byte
    (docs/splats.md). source "mesh" covers `scene`'s surfaces (None: the built-in scene);
    count 0 is the command's default. Returns the Gaussians' count, degree and the file's
    bytes."""
    return _parallax._make_splats(str(output), source, None if scene is None else str(scene),
                                  count, seed)


def interlace_files(output: str, views: Optional[Sequence[str]] = None,
                    display: Optional[str] = None, *, quilt: Optional[str] = None,
                    quilt_layout: Optional[Tuple[int, int]] = None, subpixels: bool = False,
                    view_resampling: str = "linear", linear: bool = False,
                    lens_spot: Optional[float] = None, bundles: str = "") -> dict:
    """`parallax interlace VIEW... | QUILT --display DISPLAY -o OUTPUT`: the same files, byte for
    byte. `views` are image files, `quilt` one quilt file (its layout from its name unless
    quilt_layout is given), `display` a path (None: the built-in). Returns OUTPUT/render.json."""
    _parallax._interlace_files(str(output), [str(v) for v in views or []],
                               "" if quilt is None else str(quilt),
                               "" if display is None else str(display),
                               quilt_layout=_layout(quilt_layout), subpixels=subpixels,
                               view_resampling=view_resampling, linear=linear,
                               lens_spot=lens_spot, bundles=bundles)
    return json.load(open(os.path.join(str(output), "render.json")))


@dataclass
class CalibrationPatterns:
    """The calibration patterns: (file name, float32 linear picture) pairs in index order, each
    at its layer's resolution, and what index.json and README.txt say of them."""
    pictures: list
    index: dict = field(repr=False)
    readme: str = field(repr=False)


def calibration_patterns(display: Optional[Display] = None, *, screen_period_px: int = 0,
                         slit_period_px: float = 0.0, phase_px: float = 0.0, from_px: float = 0.0,
                         to_px: float = 0.0, period_steps: int = 9, phase_step_px: float = 0.0,
                         duty: float = 0.0, label_scale: int = 0) -> CalibrationPatterns:
    """`parallax calibrate patterns`: the slit patterns for a barrier display's two layers (0: the
    setting's default, as the CLI's options)."""
    pictures, index, readme = _parallax._calibration_patterns(
        _display(display), screen_period_px=screen_period_px, slit_period_px=slit_period_px,
        phase_px=phase_px, from_px=from_px, to_px=to_px, period_steps=period_steps,
        phase_step_px=phase_step_px, duty=duty, label_scale=label_scale)
    return CalibrationPatterns(list(pictures), json.loads(index), readme)


def calibration_patterns_files(output: str = "calibration", display: Optional[str] = None,
                               **settings) -> dict:
    """`parallax calibrate patterns --display DISPLAY -o OUTPUT`: the same files (the PNGs,
    index.json, README.txt), byte for byte; calibration_patterns' keywords. Returns the index."""
    _parallax._calibration_patterns_files(str(output), "" if display is None else str(display),
                                          **settings)
    return json.load(open(os.path.join(str(output), "index.json")))


def calibration_photo_patterns(output: str = "shots", display: Optional[str] = None) -> dict:
    """`parallax calibrate patterns --photo [--display DISPLAY] -o OUTPUT`: the shots to show on
    the panels and photograph with a phone (any display kind: a barrier file, a lenticular
    calibration or lkg:NAME; docs/calibration.md, "From photos"). Returns index.json."""
    _parallax._calibration_photo_patterns(str(output), "" if display is None else str(display))
    return json.load(open(os.path.join(str(output), "index.json")))


def calibrate_photo(shots: str, photos: Sequence[str], output: Optional[str] = None,
                    display: Optional[str] = None) -> dict:
    """`parallax calibrate photo [--display NOMINAL] --shots SHOTS PHOTO... -o OUTPUT --json`: the
    display measured from the photos (each named after its shot: grid-1.jpg). Returns the
    report (`--json`'s object: each estimate with its sigma); with `output`, the measured display
    file is written there, else the report's "measured" key holds its text."""
    report, measured = _parallax._calibrate_photo(
        str(shots), [str(p) for p in photos], "" if output is None else str(output),
        "" if display is None else str(display))
    result = json.loads(report)
    if output is None:
        result["measured"] = measured
    return result


def calibration_check(shots: str, photos: Sequence[str], display: Optional[str] = None) -> dict:
    """`parallax calibrate check [--display FILE] --shots SHOTS PHOTO... --json`: what each seat
    sees of a lenticular panel showing the lens shot drawn with the calibration to check (the
    view at the panel's centre and across it, the one a right calibration shows there, the
    crosstalk; docs/calibration.md, "Checking a calibration"). Returns the report."""
    return json.loads(_parallax._calibration_check(
        str(shots), [str(p) for p in photos], "" if display is None else str(display)))


def lenticular_simulate(image: np.ndarray, display: Display, *,
                        eye: Optional[Sequence[float]] = None,
                        distance: float = 0.0, lens_spot: Optional[float] = None,
                        bundles: str = "") -> np.ndarray:
    """`parallax lenticular simulate --image FILE CALIBRATION [--eye X,Y,Z] [--distance MM]
    [--lens-spot W] [--bundles parallel|converging]`: the panel picture seen from the eye through
    the lenses (default eye: the centre of the view cone at the design distance; default optics:
    the display's), float32 linear."""
    return _parallax._lenticular_simulate(image, display,
                                          eye=None if eye is None else tuple(eye),
                                          distance=distance, lens_spot=lens_spot,
                                          bundles=bundles)
