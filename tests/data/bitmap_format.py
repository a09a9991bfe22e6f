"""Writes the images of tests/tests/bitmap_format.rs (bitmap_format_8.png, bitmap_format_16.png,
bitmap_format.exr: tiny, with values chosen to show each storage precision) and bitmap_format.json:
Mitsuba 3.9.1's `bitmap` texture (scalar_rgb, nearest lookups at each texel's centre, row 0 at v
near 0) for each file under each `format`, with and without `raw`.
Run: python bitmap_format.py (with mitsuba installed)."""
import json
import os
import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")
here = os.path.dirname(os.path.abspath(__file__))

img8 = np.array([[[0, 128, 255], [10, 188, 64], [3, 77, 200]],
                 [[255, 0, 1], [90, 90, 90], [250, 5, 130]]], dtype=np.uint8)
img16 = np.array([[[1000, 30000, 65535], [12345, 54321, 7], [128, 32768, 65000]],
                  [[0, 257, 40000], [65535, 1, 33333], [500, 20000, 60000]]], dtype=np.uint16)
imgf = np.array([[[0.1, 2.0, 0.3], [0.7, 0.0001, 5.0], [1000.0, 0.5, 1e-6]],
                 [[0.25, 0.75, 1.0], [3.14159, 0.33333, 0.66667], [0.004, 0.996, 1.5]]], dtype=np.float32)
files = {"bitmap_format_8.png": img8, "bitmap_format_16.png": img16, "bitmap_format.exr": imgf}
for name, data in files.items():
    mi.Bitmap(data).write(os.path.join(here, name))

cases = []
for name in files:
    for fmt in ["auto", "variant", "float16", "fp16", "uint8"]:
        for raw in [False, True]:
            texture = mi.load_dict({"type": "bitmap", "filename": os.path.join(here, name),
                                    "format": fmt, "raw": raw, "filter_type": "nearest"})
            h, w = files[name].shape[:2]
            texels = []
            for y in range(h):
                for x in range(w):
                    si = mi.SurfaceInteraction3f()
                    si.uv = mi.Point2f((x + 0.5) / w, (y + 0.5) / h)
                    texels.append([float(c) for c in texture.eval(si)])
            cases.append({"file": name, "format": fmt, "raw": raw, "texels": texels})
with open(os.path.join(here, "bitmap_format.json"), "w") as f:
    json.dump({"mitsuba": mi.__version__, "cases": cases}, f, indent=1)
