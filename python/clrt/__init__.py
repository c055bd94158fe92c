"""clrt: the OpenCL Whitted ray tracer of Computer Graphics from Scratch, and its double-precision reference.

    import clrt
    scene = clrt.Scene.load("scenes/cgfs-demo.json")
    r = clrt.Renderer(scene, 600, 600)       # builds (or loads) the program, uploads the scene
    img = r.render(depth=3)                  # clrt.Image: float32 (600, 600, 3), 1.0 = the book's 255
    img.to_uint8()                           # the 8-bit image `clrt render -o x.png` writes
    clrt.compare(scene, 200, 200)            # the dict of `clrt compare --json`

The guide: docs/guide/python.md. Errors are clrt.Error (a RuntimeError) with the command line's message;
bad input is clrt.UsageError (also a ValueError), a bad scene clrt.SceneError, a failing OpenCL runtime
clrt.DeviceError. Ctrl-C stops a render between bands and raises KeyboardInterrupt.
"""

import numpy as _np

from ._clrt import (
    DeviceError,
    Error,
    Scene,
    SceneError,
    UsageError,
    Warning,
    __version__,
    accuracy,
    compare,
    devices,
    sweep,
    to_uint8,
)
from . import _clrt

__all__ = [
    "DeviceError", "Error", "Image", "Renderer", "Scene", "SceneError", "UsageError", "Warning", "__version__",
    "accuracy", "compare", "devices", "reference", "sweep", "to_uint8",
]


class Image(_np.ndarray):
    """A rendered frame: a numpy float32 array (height, width, 3) on the float image files' scale
    (value / 255: 1.0 is the book's 255, as clrt's EXR and PFM files hold it), unclamped.

    ``info`` is a dict of how it was made (scene, depth, device, kernel_ms, frame_ms, ...). ``aovs`` holds
    the AOV layers a Renderer(aovs=...) was asked for, by name: "depth" (height, width) float32 (distance
    to the first hit, +inf on a miss), "normal" and "albedo" (height, width, 3) float32, "id" (height, width)
    int32 (-1 on a miss); of the ray through each pixel's centre (docs/guide/images.md, "Layers"). In Jupyter it
    shows as a PNG (``_repr_png_``); ``to_uint8()`` gives the 8-bit image clrt's PNG/PPM files hold.
    Arithmetic on it gives plain-looking Images too; ``numpy.asarray(img)`` is the bare array.
    """

    def __new__(cls, array, info=None, aovs=None):
        obj = _np.asarray(array, dtype=_np.float32).view(cls)
        obj.info = dict(info or {})
        obj.aovs = dict(aovs or {})
        return obj

    def __array_finalize__(self, obj):
        self.info = getattr(obj, "info", {})
        self.aovs = getattr(obj, "aovs", {})

    def __array_wrap__(self, obj, context=None):
        if obj.shape == ():  # a reduction (img.mean()): a plain numpy scalar, not a 0-d Image
            return obj[()]
        return super().__array_wrap__(obj, context)

    def to_uint8(self):
        """The 8-bit values by the canvas rule (clamp to [0, 255], round half to even, NaN to 0)."""
        return to_uint8(_np.asarray(self))

    def to_png(self):
        """PNG bytes, encoded by clrt's imaging module as `clrt render -o x.png` writes them."""
        return _clrt._encode(_np.asarray(self), "png")

    def save(self, path, format=""):
        """Writes the image as clrt does: the extension (or ``format``) picks png, ppm, exr, pfm, ..."""
        _clrt._save(_np.asarray(self), str(path), format)

    def _repr_png_(self):
        if self.ndim != 3 or self.shape[2] != 3 or self.shape[0] < 1 or self.shape[1] < 1:
            return None
        return self.to_png()


class Renderer(_clrt._Renderer):
    """One scene at one size, on one device or several: its compiled program and device buffers are kept
    between frames, so every render() after the first is a warm frame.

    Renderer(scene, width=600, height=600, *, device=None, precision="robust", spp=1, adaptive=None,
             subsample=None, aspect=None, depth=None, lanes=None, accel="auto", specialize=True, ftz=True,
             cache=True, verbose=False, kernel_dir=None, cl_options=None, local=None, band_rows=0,
             max_launch_ms=None, aovs=None)

    ``scene``: a clrt.Scene or a path. The options are `clrt render`'s (docs/guide/commands.md), with the
    same defaults, checks and messages; ``depth`` is the default of render(depth=None) (None: the scene's).
    ``aovs``: layers to render beside the colour, `clrt render --aov`'s ("depth,normal,albedo,id" or a list
    of those names), in each Image's ``aovs`` dict.
    """

    def render(self, depth=None):
        """The frame at ``depth`` (None: the Renderer's, else the scene's recursion_depth) as an Image."""
        array, info, aovs = self._render(depth)
        return Image(array, info, aovs)

    def __repr__(self):
        return "<clrt.Renderer %r %dx%d on %s>" % (self.scene.name, self.width, self.height, self.device)


def reference(scene, width=600, height=600, **options):
    """The double-precision reference's image (the oracle), as an Image.

    reference(scene, width=600, height=600, *, depth=None, spp=1, adaptive=None, subsample=None, aspect=None)
    """
    array, info = _clrt._reference(scene, width, height, **options)
    return Image(array, info)
