#!/usr/bin/python3
"""Makes the bathymetry grids of tests/data/bathymetry (written by the sonarloop project,
Apache-2.0 like the rest of it; no survey data is in them).

  forth_2m.asc/.prj  a 320 m x 320 m site at 2 m cells in WGS 84 / UTM zone 30N (EPSG:32630)
                     around the default scenario's origin (55.9 N, 3.2 W, off Edinburgh):
                     depths of 23-29 m on a gentle slope, a meandering channel 2 m deep, a
                     rock mound, sand waves and a few centimetres of multibeam noise; its
                     north-east corner beyond the swath has no data (-9999)
  realism_iver2_dive.asc
                     the seabed under the real Iver2 recording's dive (docs/realism.md) for a
                     vehicle holding 18.8 m depth: depth = 18.8 + the file's altitude, along the
                     track (north, Y) at the file's mean speed, constant across it; 1 m cells,
                     100 x 100, X and Y from -50 to 50 m, no CRS (origin_xy_m: [0, 0]); the
                     track starts at Y = -27 m
  plane_4m.xyz       an XYZ grid without a CRS (X east, Y north, depth), 4 m cells, 100 x 100
                     cells: the plane depth = 25 + 0.01 X + 0.02 Y (X, Y from the grid's
                     centre), to test placement: an interpolated plane is exact

Run from this folder: /usr/bin/python3 make_grids.py
"""
import os
import sys

import numpy as np

UTM30N_WKT = (
    'PROJCS["WGS 84 / UTM zone 30N",GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",'
    '6378137,298.257223563,AUTHORITY["EPSG","7030"]],AUTHORITY["EPSG","6326"]],PRIMEM['
    '"Greenwich",0,AUTHORITY["EPSG","8901"]],UNIT["degree",0.0174532925199433,AUTHORITY['
    '"EPSG","9122"]],AUTHORITY["EPSG","4326"]],PROJECTION["Transverse_Mercator"],PARAMETER['
    '"latitude_of_origin",0],PARAMETER["central_meridian",-3],PARAMETER["scale_factor",0.9996],'
    'PARAMETER["false_easting",500000],PARAMETER["false_northing",0],UNIT["metre",1,AUTHORITY['
    '"EPSG","9001"]],AXIS["Easting",EAST],AXIS["Northing",NORTH],AUTHORITY["EPSG","32630"]]')


def forth():
    n, cell = 160, 2.0
    xll, yll = 487334.0, 6194808.0  # the origin (55.9 N, 3.2 W) is at (487494.26, 6194968.02)
    rng = np.random.default_rng(7)
    e = xll + (np.arange(n) + 0.5) * cell          # cell centres, west to east
    nn = yll + (np.arange(n)[::-1] + 0.5) * cell   # rows north to south
    E, N = np.meshgrid(e - 487494.0, nn - 6194968.0)
    depth = 26.0 + 0.006 * E - 0.004 * N           # the slope
    centre = 25.0 * np.sin(N / 60.0)               # a meandering channel running north
    depth += 2.0 * np.exp(-((E - centre) / 18.0) ** 2)
    depth -= 2.5 * np.exp(-((E + 70.0) ** 2 + (N - 40.0) ** 2) / (2 * 15.0 ** 2))  # a mound
    depth += 0.3 * np.sin(2 * np.pi * (0.8 * E + 0.6 * N) / 24.0)  # sand waves, 24 m
    depth += rng.normal(0.0, 0.03, depth.shape)    # multibeam noise
    depth = np.round(depth, 3)
    depth[(E > 120.0) & (N > 120.0)] = -9999.0     # no data beyond the swath
    with open("forth_2m.asc", "w") as f:
        f.write(f"ncols {n}\nnrows {n}\nxllcorner {xll}\nyllcorner {yll}\ncellsize {cell}\n"
                "NODATA_value -9999\n")
        for row in depth:
            f.write(" ".join(f"{v:.3f}" for v in row) + "\n")
    with open("forth_2m.prj", "w") as f:
        f.write(UTM30N_WKT + "\n")


def plane():
    n, cell = 100, 4.0
    with open("plane_4m.xyz", "w") as f:
        for r in range(n):  # rows north to south, as GDAL's XYZ driver reads them
            y = (n / 2 - r - 0.5) * cell
            for c in range(n):
                x = (c - n / 2 + 0.5) * cell
                f.write(f"{x:.1f} {y:.1f} {25.0 + 0.01 * x + 0.02 * y:.3f}\n")


def dive():
    here = os.path.dirname(os.path.abspath(__file__))
    sys.path.insert(0, os.path.join(here, "..", "..", "..", "tools"))
    from xtf_stats import read_xtf
    pings = read_xtf(os.path.join(here, "..", "xtf", "scotsman-iver2.xtf"))["pings"]
    ok = pings["altitude_m"] > 0.0                 # the first ping has no altitude
    t = pings["time_s"][ok] - pings["time_s"][0]
    speed = np.mean(pings["speed_kn"]) * 0.514444  # 1.04 m/s
    along = -27.0 + t * speed                      # the scenario's track starts at -27 m
    # a running median over 1 s of pings: the altimeter's single-ping jumps out
    alt = pings["altitude_m"][ok]
    alt = np.array([np.median(alt[max(0, i - 4):i + 5]) for i in range(len(alt))])
    n, cell = 100, 1.0
    y = (n / 2 - np.arange(n) - 0.5) * cell        # rows north to south
    depth = 18.8 + np.interp(y, along, alt)        # held beyond the file's ends
    with open("realism_iver2_dive.asc", "w") as f:
        f.write(f"ncols {n}\nnrows {n}\nxllcorner {-n / 2 * cell}\nyllcorner {-n / 2 * cell}\n"
                f"cellsize {cell}\nNODATA_value -9999\n")
        for v in depth:
            f.write(" ".join([f"{v:.3f}"] * n) + "\n")


forth()
plane()
dive()
