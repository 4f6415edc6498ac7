#!/usr/bin/env python3
"""Writes scenes/dem/naples_synthetic_utm33n.tif, campo's bundled example DEM.

SYNTHETIC relief, not survey data: a few smooth hills, a ridge and a valley
(analytic functions, plus small ripples whose phases come from a seeded
generator), placed near Naples (40.85 N, 14.27 E) in WGS 84 / UTM zone 33N
(EPSG:32633). 256 x 256 cells of 10 m (2.56 km square), heights in metres
stored as Int16 decimetres (band scale 0.1), DEFLATE-compressed, with a small
void of nodata cells (-32768) as real elevation models have (radar shadow,
water), so the bundled scene shows "nodata": "fill".

Reproducible: pure Python (no third-party module) writes an ASCII grid, and
GDAL's gdal_translate (Debian gdal-bin) turns it into the GeoTIFF. Run from
the repository's root:  python3 tools/make_example_dem.py
"""
import math
import os
import random
import subprocess
import sys
import tempfile

COLS = ROWS = 256
CELL_M = 10.0
# Lower-left corner of the raster in UTM 33N: the raster's centre is at
# easting 438000 m, northing 4522000 m (40.8467 N, 14.2646 E).
X_LL = 438000.0 - COLS * CELL_M / 2
Y_LL = 4522000.0 - ROWS * CELL_M / 2
NODATA = -32768
OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "dem", "naples_synthetic_utm33n.tif")


def height_m(x, y, ripples):
    """Height at (x, y) metres from the raster's centre (x east, y north)."""
    h = 40.0 + 0.012 * x + 0.008 * y  # a plain rising gently to the north-east
    h += 140.0 * math.exp(-((x - 500.0) ** 2 + (y - 400.0) ** 2) / (2 * 380.0 ** 2))  # the main hill
    h += 60.0 * math.exp(-((x + 650.0) ** 2 + (y + 500.0) ** 2) / (2 * 250.0 ** 2))   # a lower hill
    # A ridge running north-west from the main hill, and a valley south of it.
    along, across = (x + y) / math.sqrt(2), (y - x) / math.sqrt(2)
    h += 35.0 * math.exp(-(across - 300.0) ** 2 / (2 * 120.0 ** 2)) * (1 / (1 + math.exp(-along / 200.0)))
    h -= 25.0 * math.exp(-(y + 150.0) ** 2 / (2 * 90.0 ** 2))
    for amplitude, wavelength, direction, phase in ripples:
        h += amplitude * math.sin(2 * math.pi * (x * math.cos(direction) + y * math.sin(direction)) / wavelength + phase)
    return h


def main():
    generator = random.Random(35)  # issue 35
    ripples = [(generator.uniform(0.5, 2.0), generator.uniform(80.0, 300.0), generator.uniform(0, math.pi),
                generator.uniform(0, 2 * math.pi)) for _ in range(6)]
    lines = [f"ncols {COLS}", f"nrows {ROWS}", f"xllcorner {X_LL:.1f}", f"yllcorner {Y_LL:.1f}",
             f"cellsize {CELL_M:.1f}", f"NODATA_value {NODATA}"]
    for row in range(ROWS):  # the first line is the northern row
        y = (ROWS - 1 - row + 0.5) * CELL_M - ROWS * CELL_M / 2
        values = []
        for col in range(COLS):
            x = (col + 0.5) * CELL_M - COLS * CELL_M / 2
            # The void: an ellipse of about 60 x 40 m on the western slope.
            if ((x + 420.0) / 30.0) ** 2 + ((y - 260.0) / 20.0) ** 2 <= 1.0:
                values.append(str(NODATA))
            else:
                values.append(str(round(height_m(x, y, ripples) * 10)))
        lines.append(" ".join(values))
    with tempfile.TemporaryDirectory() as work:
        grid = os.path.join(work, "dem.asc")
        with open(grid, "w") as f:
            f.write("\n".join(lines) + "\n")
        subprocess.run(["gdal_translate", "-q", "-of", "GTiff", "-ot", "Int16", "-a_srs", "EPSG:32633",
                        "-a_nodata", str(NODATA), "-a_scale", "0.1", "-co", "COMPRESS=DEFLATE", "-co", "PREDICTOR=2",
                        "-co", "ZLEVEL=9", "-mo", "AREA_OR_POINT=Area",
                        "-mo", "TIFFTAG_IMAGEDESCRIPTION=campo example DEM: SYNTHETIC relief near Naples, not survey "
                        "data (tools/make_example_dem.py)", grid, OUT], check=True)
    print(f"wrote {os.path.normpath(OUT)} ({os.path.getsize(OUT)} bytes)", file=sys.stderr)


if __name__ == "__main__":
    main()
