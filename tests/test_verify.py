"""The distances of geometry.verify against brute force: each point's least GEOS distance to
every segment of a ring, and GEOS's R-tree's nearest vertex, bit for bit, on the rings that
break a k-d tree of samples (zero-length segments, a huge spread of lengths, a far point, a few
vertices, ulp near-ties) and on random rings; and the work bounded: the adversarial cases run
within a memory limit."""

import subprocess
import sys
import textwrap

import numpy as np
import pytest
import shapely

from gearcad.geometry.verify import distances, max_distance, nearest


def _least(points: np.ndarray, rings) -> np.ndarray:
    """Brute force: each point's least GEOS distance to every segment of ``rings``."""
    a = np.concatenate(rings)
    b = np.concatenate([np.roll(r, -1, axis=0) for r in rings])
    segments = shapely.linestrings(np.stack([a, b], axis=1))
    return shapely.distance(shapely.points(points)[:, None], segments[None, :]).min(axis=1)


def _rtree_nearest(points: np.ndarray, vertices: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """What nearest() always gave: GEOS's R-tree's pick."""
    tree = shapely.STRtree(shapely.points(vertices))
    (i, j), d = tree.query_nearest(shapely.points(points), return_distance=True, all_matches=False)
    index, distance = np.empty(len(points), dtype=int), np.empty(len(points))
    index[i], distance[i] = j, d
    return index, distance


def _spread() -> np.ndarray:
    """2000 segments of 5e-7 mm, two of about 50 mm."""
    return np.vstack([np.linspace(0, 1, 2001)[:, None] * [1e-3, 0], [[0.5, 50.0]]])


def _wavy(n: int) -> np.ndarray:
    """A circle of fine teeth, n vertices, radius 10 mm ± 0.05."""
    phi = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return (10 + 0.05 * np.sin(400 * phi))[:, None] * np.column_stack([np.cos(phi), np.sin(phi)])


def _around(ring: np.ndarray, rng, n: int = 200) -> np.ndarray:
    """Points near, on and far from ``ring``."""
    lo, hi = ring.min(axis=0), ring.max(axis=0)
    span = max(float((hi - lo).max()), 1e-9)
    return np.vstack([rng.uniform(lo - span, hi + span, (n, 2)), ring[: n // 4], ring.mean(axis=0)[None]])


_ULP_TIE = "0.02 0.02 0.02 0 -0.02 0.04 0.02 -0.03 -0.02 0 0.01 0.03 0.02 0 0.03 0.02 0.04 -0.01 0.04 0.04 -0.04 0.03"
"""A ring whose nearest segment to (0.04, -0.03) GEOS's R-tree missed by an ulp."""

ADVERSARIAL = {
    "zero-length": np.array([[0, 0], [0, 0], [0, 0], [10, 0], [10, 0], [10, 0], [5, 5]], float),
    "spread": _spread(),
    "wavy": _wavy(4000),
    "one vertex": np.array([[1.0, 2.0]]),
    "two vertices": np.array([[0.0, 0.0], [3.0, 4.0]]),
    "triangle far off": np.array([[1e6, 1e6], [1e6 + 1e-3, 1e6], [1e6, 1e6 + 1e-3]]),
    "ulp tie": np.array(_ULP_TIE.split(), dtype=float).reshape(-1, 2),
}


@pytest.mark.parametrize("name", ADVERSARIAL)
def test_distances_are_the_least(name):
    ring = ADVERSARIAL[name]
    points = _around(ring, np.random.default_rng(len(ring)))
    points = np.vstack([points, [[3.0, 1.0], [0.04, -0.03], ring.mean(axis=0) + [60.0, 0.0]]])
    least = _least(points, [ring])
    np.testing.assert_array_equal(distances(points, [ring]), least)
    assert max_distance(points, ring) == least.max()


def test_a_point_far_beyond_the_samples():
    """One point 60 samples off a fine ring, the rest on it: each its own reach."""
    ring = _wavy(10000)
    h = 2 * np.median(np.hypot(*np.diff(ring, axis=0).T))
    points = np.vstack([ring[::97] * 1.001, [[10 + 60 * h + 0.05, 0.0]]])
    np.testing.assert_array_equal(distances(points, [ring]), _least(points, [ring]))


def test_on_a_decimal_grid():
    """Rings and points on a grid, where segments tie to an ulp (GEOS's R-tree could return one an
    ulp farther than the least)."""
    rng = np.random.default_rng(11)
    for _ in range(400):
        scale = 10.0 ** rng.integers(-3, 3)
        ring = rng.integers(-4, 5, size=(int(rng.integers(2, 40)), 2)) * scale
        points = rng.integers(-8, 9, size=(30, 2)) / 2 * scale
        np.testing.assert_array_equal(distances(points, [ring]), _least(points, [ring]))
    assert distances([[0.04, -0.03]], [ADVERSARIAL["ulp tie"]])[0] == 0.019999999999999997


def test_random_rings():
    rng = np.random.default_rng(7)
    for _ in range(60):
        n = int(rng.integers(3, 300))
        phi = np.sort(rng.uniform(0, 2 * np.pi, n))
        radius = rng.uniform(0.2, 1, n) * 10.0 ** rng.integers(-2, 3)
        offset = rng.choice([0.0, 100.0, 1e5])
        rings = [np.column_stack([np.cos(phi), np.sin(phi)]) * radius[:, None] + offset]
        if rng.random() < 0.5:  # a hole, some vertices repeated
            rings.append(np.repeat(rings[0][::3] * 0.3 + offset * 0.7, rng.integers(1, 3, len(rings[0][::3])), axis=0))
        points = _around(rings[0], rng, 100)
        np.testing.assert_array_equal(distances(points, rings), _least(points, rings))


NEAR_TIES = [  # the R-tree picks the vertex an ulp farther: so must nearest()
    ([0.0002, 0.0], [[0.0002, -5.000000000000001e-05], [0.00015000000000000001, 0.0]]),
    ([-5e-05, -5e-05], [[-5.000000000000001e-05, -0.00015000000000000001], [5e-05, -5.000000000000001e-05]]),
    ([5e-05, 0.00025], [[0.0001, 0.00025], [5e-05, 0.0002]]),
    ([-0.15000000000000002, -0.2], [[0.0, -0.30000000000000004], [0.0, -0.1]]),
]


@pytest.mark.parametrize(("point", "vertices"), NEAR_TIES)
def test_nearest_picks_as_the_rtree(point, vertices):
    for order in (vertices, vertices[::-1]):
        got, before = nearest(np.array([point]), np.array(order)), _rtree_nearest(np.array([point]), np.array(order))
        np.testing.assert_array_equal(got[0], before[0])
        np.testing.assert_array_equal(got[1], before[1])


def test_nearest_on_grids():
    rng = np.random.default_rng(5)
    for _ in range(400):  # the R-tree's own picks between near ties: NEAR_TIES above
        scale = 10.0 ** rng.integers(-3, 3)
        vertices = (rng.integers(-6, 7, size=(int(rng.integers(1, 30)), 2)) * 0.05 + rng.choice([0, 0.1, 0.3])) * scale
        points = rng.integers(-12, 13, size=(40, 2)) * 0.05 * scale
        (index, distance), (before, measured) = nearest(points, vertices), _rtree_nearest(points, vertices)
        np.testing.assert_array_equal(index, before)
        np.testing.assert_array_equal(distance, measured)
        least = shapely.distance(shapely.points(points)[:, None], shapely.points(vertices)[None, :]).min(axis=1)
        assert np.all(np.abs(distance - least) <= 4e-15 * least)


BOUNDED = """
import resource, numpy as np
from gearcad.geometry.verify import distances
size = int(open("/proc/self/statm").read().split()[0]) * resource.getpagesize()
resource.setrlimit(resource.RLIMIT_AS, (size + 400 * 2**20, resource.RLIM_INFINITY))
ring = np.array([[0, 0], [0, 0], [0, 0], [10, 0], [10, 0], [10, 0], [5, 5]], float)
assert distances([[3.0, 1.0]], [ring])[0] == 1.0
spread = np.vstack([np.linspace(0, 1, 2001)[:, None] * [1e-3, 0], [[0.5, 50.0]]])
distances([[3.0, 1.0], [1e-4, 1e-4]], [spread])
phi = np.linspace(0, 2 * np.pi, 40000, endpoint=False)
unit = np.column_stack([np.cos(phi), np.sin(phi)])
wavy = (10 + 0.05 * np.sin(400 * phi))[:, None] * unit
h = 2 * np.median(np.hypot(*np.diff(wavy, axis=0).T))
distances(np.vstack([10 * unit, [[10 + 60 * h + 0.05, 0]], [[0.0, 0.0]] * 100]), [wavy])
cluster = np.vstack([wavy[:-1] * 1e-7, [[50.0, 0.0], [0.0, 50.0]]])  # 40000 vertices within 2e-6 mm
distances(cluster[:39999:4] * 1.01, [cluster])
print("bounded")
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="/proc and RLIMIT_AS")
def test_work_is_bounded():
    """Zero-length segments, a huge spread of lengths, a far point among many near ones, a cluster
    of tiny segments: each within 400 MB more than the imports and a minute."""
    run = subprocess.run([sys.executable, "-c", textwrap.dedent(BOUNDED)], capture_output=True, text=True, timeout=120)
    assert run.stdout.strip() == "bounded", run.stderr[-2000:]
