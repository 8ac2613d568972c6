"""Parts as written: every cut path simple and within the tolerance of the exact outline, after
arc fitting and kerf; what would destroy teeth or spaces is refused with the largest allowed."""

import numpy as np
import pytest
import shapely

from gearcad.errors import DesignError
from gearcad.fitting import design
from gearcad.geometry.arcfit import arc_points
from gearcad.geometry.verify import is_simple, max_distance
from gearcad.profiles import load_profile

from .conftest import QUICK, ROOT, drawn


def _design(profile: str, **overrides):
    return design(load_profile(ROOT / "profiles" / f"{profile}.toml", {**QUICK, **overrides}))


@pytest.mark.parametrize(
    "profile,overrides,bites",
    [
        ("walker", {"output.tolerance": 0.01}, False),  # the README's laser setting: the arcs once crossed
        # the centre ellipse at e = 0.95 with 40 teeth is made, and its teeth bite 236 µm deep:
        # reported as interference, not trimmed away (the tip relief takes at most 0.02 m)
        ("elliptic_centre", {"gear1.eccentricity": 0.95, "teeth.count": 40, "output.tolerance": 0.01}, True),
        ("spur_pair", {"output.kerf": 0.2, "output.tolerance": 0.01}, False),
    ],
    ids=["walker-0.01", "centre-e0.95", "spur-kerf"],
)
def test_cut_paths_are_simple_and_within_tolerance(profile, overrides, bites):
    """The check is independent of the fitting: the arcs are flattened finely and measured
    against the part's outline offset by half the kerf with shapely.  The parts as drawn
    (:func:`~.conftest.drawn`: the assembly's interference proof is the finishing line's, the
    fit's band adds nothing here; it was two thirds of the walker's CPU)."""
    d = drawn(load_profile(ROOT / "profiles" / f"{profile}.toml", {**QUICK, **overrides}))
    assert ("interference" in {f.code for f in d.failures()}) is bites
    assert (d.assembly.depth > d.assembly.allowed_depth) is bites
    tol, kerf = d.params.output.tolerance, d.params.output.kerf
    for part in d.parts():
        # the fine cut lies within a quarter of the tolerance of the exact outline
        exact = shapely.Polygon(part.fine.rings[0], part.fine.rings[1:]).buffer(kerf / 2, quad_segs=64)
        for ring in part.cut:
            points = arc_points(ring, tol / 100)
            assert is_simple(points), part.name
            band = shapely.buffer(exact.boundary, 0.75 * tol * 1.001, quad_segs=16)
            if not band.covers(shapely.LineString(points)):  # measured only to say by how much
                miss = shapely.distance(shapely.points(points), exact.boundary).max()
                raise AssertionError((part.name, miss))


def test_max_distance_is_exact_where_it_matters():
    """Against shapely's point-to-line distance on a ring with long and short segments."""
    t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    ring = np.column_stack([np.cos(t) * 10, np.sin(t) * 4])
    ring = np.vstack([ring[:100], ring[300:]])  # one long chord across the middle
    pts = np.random.default_rng(1).uniform(-12, 12, (500, 2))
    exact = shapely.distance(shapely.points(pts), shapely.LinearRing(ring))
    assert max_distance(pts, ring, limit=0.0) == pytest.approx(exact.max(), rel=1e-12)
    assert max_distance(pts, ring, limit=1e9) >= exact.max() - 1e-12  # an upper bound


@pytest.mark.parametrize(
    "key,value,largest",
    [
        ("teeth.clearance", 5.0, r"largest clearance these teeth take is 0\.[0-9]+ mm"),
        ("teeth.backlash", 5.0, r"largest backlash module 2 takes is 3\.142 mm"),
    ],
)
def test_offsets_that_destroy_teeth_are_refused_with_the_largest_allowed(key, value, largest):
    with pytest.raises(DesignError, match=largest) as exc:
        _design("spur_pair", **{key: value})
    assert str(exc.value).startswith(f"{key} = {value:g}:")


def test_largest_kerf_is_accepted_and_keeps_the_spaces():
    """A kerf that destroys teeth is refused with the largest every part takes; just under the
    reported largest kerf the build goes through and every tooth space is
    still cut: the cut path comes back to within the kerf of the root."""
    coarse = {"output.tolerance": 0.01}
    with pytest.raises(DesignError, match=r"largest kerf every part takes is [0-9]\.[0-9]+ mm") as exc:
        _design("spur_pair", **{"output.kerf": 1.9}, **coarse)
    assert str(exc.value).startswith("output.kerf = 1.9:")
    largest = float(str(exc.value).split("every part takes is ")[1].split(" mm")[0])
    d = _design("spur_pair", **{"output.kerf": 0.98 * largest}, **coarse)
    assert all(is_simple(arc_points(r, 1e-3)) for p in d.parts() for r in p.cut)
