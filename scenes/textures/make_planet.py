"""Writes planet.png beside this file: the pixmap of the demo's textured
sphere, 256 x 128 in longitude and latitude (u across, v up), an ocean
with continents, ice caps and a graticule every 30 degrees (so the sphere's
(u, v) can be seen). Made from sines, the same every run.

    python scenes/textures/make_planet.py   (needs the hitray package)
"""

import pathlib

import numpy as np

import hitray

W, H = 256, 128
u = (np.arange(W) + 0.5) / W
v = 1.0 - (np.arange(H) + 0.5) / H
lon, lat = np.meshgrid(2 * np.pi * u, np.pi * (v - 0.5))

land = (np.sin(2 * lon + 1.3) * np.cos(3 * lat) + 0.6 * np.sin(5 * lon - 2 * lat + 0.7)
        + 0.35 * np.sin(11 * lon + 7 * lat)) > 0.45
ocean = np.stack([0.02 + 0.04 * np.cos(lat), 0.08 + 0.1 * np.cos(lat), 0.35 + 0.2 * np.cos(lat)], -1)
green = np.stack([0.12 + 0.25 * (1 - np.cos(lat)), 0.32 - 0.1 * (1 - np.cos(lat)), np.full_like(lat, 0.06)], -1)
image = np.where(land[..., None], green, ocean)
ice = np.abs(lat) > np.radians(68)
image[ice] = (0.85, 0.88, 0.92)
grid = (np.abs(((np.degrees(lon) + 15) % 30) - 15) < 0.8) | (np.abs(((np.degrees(lat) + 15) % 30) - 15) < 0.8)
image[grid] = (0.9, 0.75, 0.2)

hitray.Image(image.astype(np.float32)).save(pathlib.Path(__file__).with_name("planet.png"))
