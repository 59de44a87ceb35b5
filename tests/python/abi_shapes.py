"""Python shape classes the hitray.abi tests register."""

import math


class Ball:
    """sphere of a given radius at the origin, in Python"""

    closed = True
    # The stable root pair below gives t to a few ulps for rays that cross
    # well inside; 1e-12 leaves room for grazing ones.
    hit_relative_error = 1e-12

    def __init__(self, radius=1.0):
        if radius <= 0:
            raise ValueError(f"radius must be positive, not {radius}")
        self.radius = radius

    def bounds(self):
        r = self.radius
        return ((-r, -r, -r), (r, r, r))

    def hit(self, origin, direction, tmin, tmax):
        ox, oy, oz = origin
        dx, dy, dz = direction
        a = dx * dx + dy * dy + dz * dz
        b = ox * dx + oy * dy + oz * dz
        c = ox * ox + oy * oy + oz * oz - self.radius * self.radius
        disc = b * b - a * c
        if disc < 0.0:
            return []
        # No cancellation between -b and the root: q has the sign of -b.
        q = -(b + math.copysign(math.sqrt(disc), b))
        if q == 0.0:
            return []
        t0, t1 = sorted((q / a, c / q))
        hits = []
        for t, entering in ((t0, True), (t1, False)):
            if tmin < t < tmax:
                hits.append((t, (ox + t * dx, oy + t * dy, oz + t * dz), entering))
        return hits


class Floor:
    """the plane y = 0, unbounded, normal +y"""

    def bounds(self):
        return None

    def hit(self, origin, direction, tmin, tmax):
        if direction[1] == 0.0:
            return []
        t = -origin[1] / direction[1]
        return [(t, (0.0, 1.0, 0.0), direction[1] < 0.0)] if tmin < t < tmax else []


class Slabs:
    """`count` parallel planes z = 0, 1, ..., count-1 inside a box: more hits
    than the host's first allocation holds"""

    params = {"count": 20}

    def __init__(self, count):
        self.count = count

    def bounds(self):
        return ((-1.0, -1.0, 0.0), (1.0, 1.0, self.count - 1.0))

    def hit(self, origin, direction, tmin, tmax):
        if direction[2] == 0.0:
            return []
        ts = sorted((k - origin[2]) / direction[2] for k in range(self.count))
        return [(t, (0.0, 0.0, 1.0), False) for t in ts if tmin < t < tmax]
