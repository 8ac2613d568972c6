"""The gap between placed outlines measured on runs of their edges is shapely's distance to the
bit: for lobed polygons apart, overlapping, nested, with holes, in parts, empty and mixed with a
line, all at once and for a few of them."""

import numpy as np
import shapely

from gearcad.geometry.gap import distances, runs


def _lobed(rng, centre, n=60):
    t = np.sort(rng.uniform(0, 2 * np.pi, n))
    r = 0.6 + 0.4 * rng.uniform(size=n)
    return shapely.Polygon(np.column_stack([centre[0] + r * np.cos(t), centre[1] + r * np.sin(t)]))


def _pairs(count=120):
    rng = np.random.default_rng(1)
    first, second = [], []
    for k in range(count):
        a, b = _lobed(rng, (0, 0)), _lobed(rng, (rng.uniform(0.5, 2.5), rng.uniform(-1, 1)))
        if k % 7 == 0:
            a = shapely.MultiPolygon([a, _lobed(rng, (5, 5))])
        if k % 11 == 0:
            b = b.difference(b.centroid.buffer(0.05))  # a hole
        if k % 13 == 0:
            b = shapely.GeometryCollection([b, shapely.LineString([(0, 0), (3, 3)])])
        if k % 17 == 0:
            b = shapely.Polygon()
        if k % 19 == 0:
            b = shapely.box(-0.1, -0.1, 0.1, 0.1)  # inside the first: 0 though the edges are apart
        first.append(a)
        second.append(b)
    return np.array(first, dtype=object), np.array(second, dtype=object)


def test_distances_are_shapelys_to_the_bit():
    first, second = _pairs()
    near = np.tile([1.0, 0.0], (len(first), 1))
    expected = shapely.distance(first, second)
    assert (expected == 0).sum() > 30 and (expected > 0).sum() > 30 and np.isnan(expected).any()
    for edges in (3, 16):
        lines1 = runs(first, near, edges=edges).lines(shapely.get_coordinates(first))
        cut = runs(second, near, edges=edges)
        found = distances(first, second, lines1, cut.lines(shapely.get_coordinates(second)))
        np.testing.assert_array_equal(found, expected)
        few = np.array([0, 5, 13, 19, 40, 77])
        found = distances(first[few], second[few], lines1[few], cut.lines(shapely.get_coordinates(second[few]), few))
        np.testing.assert_array_equal(found, expected[few])
