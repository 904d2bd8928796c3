#!/usr/bin/env python3
"""Writes sunny_sky_1k.hdr: a synthetic clear-sky environment (1024 x 512, equirectangular, linear
Radiance RGBE) with a visible sun, for trying image-based lighting and the environment's
extracted lights outdoors. Made here from formulas, not from a photograph:
  - sky: blue at the zenith, paler and brighter towards the horizon (a gradient in the elevation),
    brighter around the sun (a forward-scattering glow falling off with the angle to the sun);
  - sun: a disc of 1 degree radius (twice the real sun's, so that a 1024-texel map resolves it)
    whose irradiance is about five times the sky's, as on a clear day;
  - ground: a dull green-brown below the horizon, lit by sun and sky.
Directions follow <preskin/Environment.h>: column u is the longitude 2 pi (u - 0.5) from +X
towards +Z, row v the polar angle pi v from +Y.
Usage: python3 make_sunny_sky.py [out.hdr]   (needs numpy and OpenImageIO's Python module)"""
import sys

import numpy as np
import OpenImageIO as oiio

W, H = 1024, 512
SUN_ELEVATION = np.radians(35.0)
SUN_AZIMUTH = np.radians(60.0)  # longitude from +X towards +Z
SUN_RADIUS = np.radians(1.0)


def main(out):
    u = (np.arange(W) + 0.5) / W
    v = (np.arange(H) + 0.5) / H
    phi = 2.0 * np.pi * (u[None, :] - 0.5)
    theta = np.pi * v[:, None]
    d = np.stack([np.sin(theta) * np.cos(phi), np.cos(theta) * np.ones_like(phi), np.sin(theta) * np.sin(phi)], -1)
    sun = np.array([np.cos(SUN_ELEVATION) * np.cos(SUN_AZIMUTH), np.sin(SUN_ELEVATION),
                    np.cos(SUN_ELEVATION) * np.sin(SUN_AZIMUTH)])
    up = np.clip(d[..., 1], 0.0, 1.0)
    cos_sun = np.clip(d @ sun, -1.0, 1.0)
    zenith = np.array([0.25, 0.45, 0.95])
    horizon = np.array([0.85, 0.9, 1.0])
    t = np.power(1.0 - up, 3.0)[..., None]
    sky = zenith * (1.0 - t) + horizon * t
    glow = (0.6 * np.exp((cos_sun - 1.0) * 12.0) + 0.15 * (1.0 + cos_sun) ** 2)[..., None] * np.array([1.0, 0.92, 0.8])
    sky = sky * 1.2 + glow
    ground = np.array([0.18, 0.16, 0.11]) * 1.3
    # A soft horizon (half a degree) so the image has no aliased edge.
    blend = np.clip(d[..., 1] / np.radians(0.5) + 0.5, 0.0, 1.0)[..., None]
    rgb = ground * (1.0 - blend) + sky * blend
    # The sun: its disc's coverage of each texel from 4 x 4 samples, radiance from its irradiance.
    sky_irradiance = np.pi * 1.2 * 0.6
    sun_irradiance = 5.0 * sky_irradiance
    sun_radiance = sun_irradiance / (2.0 * np.pi * (1.0 - np.cos(SUN_RADIUS)))
    coverage = np.zeros((H, W))
    near = np.argwhere(cos_sun > np.cos(SUN_RADIUS + np.radians(1.0)))
    for y, x in near:
        hits = 0
        for sy in range(4):
            for sx in range(4):
                pu = (x + (sx + 0.5) / 4) / W
                pv = (y + (sy + 0.5) / 4) / H
                p, th = 2.0 * np.pi * (pu - 0.5), np.pi * pv
                dd = np.array([np.sin(th) * np.cos(p), np.cos(th), np.sin(th) * np.sin(p)])
                hits += dd @ sun >= np.cos(SUN_RADIUS)
        coverage[y, x] = hits / 16.0
    rgb = rgb + coverage[..., None] * sun_radiance * np.array([1.0, 0.95, 0.88])
    spec = oiio.ImageSpec(W, H, 3, oiio.FLOAT)
    image = oiio.ImageOutput.create(out)
    if not image or not image.open(out, spec):
        sys.exit(f"cannot write {out}: {oiio.geterror()}")
    image.write_image(rgb.astype(np.float32))
    image.close()


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "sunny_sky_1k.hdr")
