"""The carrier-less noncircular planetary's kinematics (gearcad.trains.nc_planetary): the makers'
table (issue 38) reproduced by two computations that share only the curve, the circular set by the
method of stopping, and the exact closure of the two example sets."""

import math

import numpy as np
import pytest

from gearcad.errors import DesignError
from gearcad.mechanisms import nc_planetary
from gearcad.trains.carrier import solve_train
from gearcad.trains.nc_planetary import (
    Lobed,
    by_arc_length,
    by_sun_angle,
    close_ring,
    convex_limit,
    matched_sun,
    poses,
)
from gearcad.trains.nc_set import phasing, planet_gap, planetary_set

# The published table: (n, e, natural ring lobe count, orbit-radius change in %).
PUBLISHED = [
    (4, 0.03, 12.007, 0.1),
    (4, 0.06, 12.021, 0.35),
    (4, 0.09, 12.070, 0.75),
    (3, 0.03, 9.002, 0.1),
    (3, 0.06, 9.015, 0.35),
    (3, 0.09, 9.039, 0.75),
]


@pytest.mark.parametrize(("n", "e", "n_r", "change"), PUBLISHED)
def test_the_makers_table_two_ways(n, e, n_r, change):
    """n_r within ±0.005 of the published figure, the orbit-radius change rounding to it (the
    table's changes are multiples of 0.05 %), the two computations agreeing to 1e-6."""
    curve = Lobed(1.0, n, e)
    kennedy = by_sun_angle(curve, steps=200)
    rolled = by_arc_length(curve)
    assert kennedy.natural_lobes == pytest.approx(rolled.natural_lobes, abs=1e-6)
    assert kennedy.orbit_change == pytest.approx(rolled.orbit_change, abs=1e-6)
    assert abs(rolled.natural_lobes - n_r) <= 0.005
    assert round(rolled.orbit_change * 100 / 0.05) * 0.05 == pytest.approx(change)


def test_the_orbit_change_is_e_squared_to_leading_order():
    """Perturbation of the rolling: ψ ≈ θ + π/n + (2e/n)·sin nθ makes |C| ≈ 2R(1 + e²·sin² nθ/…),
    a change of e² (to O(e³)) whatever n — an independent closed form for small e."""
    for n in (3, 4, 5):
        change = by_arc_length(Lobed(1.0, n, 0.005)).orbit_change
        assert change == pytest.approx(0.005**2, rel=0.05)


@pytest.mark.parametrize("n", [3, 4])
def test_circles_are_the_circular_planetary_by_the_method_of_stopping(n):
    """e = 0: sun, planet radius R, ring 3R; the sun held and the carrier turning at 1 rad/s
    counter-clockwise (the seed's −1), the ring turns at 1 + 1/3 (carrier.solve_train)."""
    train = solve_train(
        (1.0, 1.0, 3.0), ("external", "internal"), omega1=0.0, epsilon1=0.0, carrier=-1.0, carrier_eps=0.0
    )
    lobe = 2 * math.pi / n
    for data in (by_arc_length(Lobed(1.0, n, 0.0)), by_sun_angle(Lobed(1.0, n, 0.0), steps=20)):
        assert data.ring_turn / lobe == pytest.approx(train.omega[2], abs=1e-12)
        assert data.natural_lobes == pytest.approx(3 * n, abs=1e-12)
        assert data.orbit_min == pytest.approx(2.0, abs=1e-12)
        assert data.orbit_max == pytest.approx(2.0, abs=1e-12)


def test_poses_roll_without_slip_and_touch_tangentially():
    """The pose itself: the planet's point ψ lands on the sun's point θ with opposite tangents,
    and the arc rolled on each is the same (checked by trapezoid sums, not the Fourier series)."""
    curve = Lobed(1.0, 4, 0.05)
    theta = np.linspace(0.0, 0.6, 7)
    pose = poses(curve, curve, theta)
    q = curve.point(pose.psi)
    cb, sb = np.cos(pose.beta), np.sin(pose.beta)
    landed = pose.centre + np.stack([cb * q[:, 0] - sb * q[:, 1], sb * q[:, 0] + cb * q[:, 1]], -1)
    assert np.max(np.abs(landed - curve.point(theta))) < 1e-12
    turn = curve.tangent_angle(pose.psi) + pose.beta - curve.tangent_angle(theta)
    assert np.max(np.abs(np.mod(turn - np.pi + np.pi, 2 * np.pi) - np.pi)) < 1e-12
    for t, psi in zip(theta[1:], pose.psi[1:]):
        x = np.linspace(0.0, t, 20001)
        y = np.linspace(psi, math.pi / 4, 20001)
        assert np.trapezoid(curve.speed(x), x) == pytest.approx(np.trapezoid(curve.speed(y), y), abs=1e-8)


def test_the_convexity_limit_is_where_the_valley_flattens():
    for n in (3, 4):
        limit = convex_limit(n)
        valley = math.pi / n
        assert Lobed(1.0, n, limit * (1 - 1e-9)).curvature(valley) > 0
        assert Lobed(1.0, n, limit * (1 + 1e-9)).curvature(valley) < 0


@pytest.mark.parametrize(("n", "e", "ring"), [(4, 0.05, 12), (3, 0.08, 9)])
def test_the_example_sets_close_exactly(n, e, ring):
    """The sun's e solved so the ring has exactly 3n lobes: closure ≤ 1e-9 rad by the solver's
    method and again by the Kennedy integration; the sun's lobe as long as the planet's."""
    planet = Lobed(1.0, n, e)
    sun, residual = close_ring(planet, ring)
    assert residual <= 1e-9
    check = by_sun_angle(sun, planet, steps=200)
    assert abs(ring * abs(check.sweep) - 2 * math.pi) <= 1e-6  # RK4 at 200 steps: ~1e-8
    assert 0 < sun.e < convex_limit(n)
    x = np.linspace(0.0, 2 * math.pi / n, 40001)
    assert np.trapezoid(sun.speed(x), x) == pytest.approx(np.trapezoid(planet.speed(x), x), rel=1e-10)


def test_a_ring_that_cannot_close_is_refused_naming_the_key():
    with pytest.raises(DesignError, match=r"^e = [0-9.]+: no sun eccentricity .* closes the ring at 15 lobes"):
        close_ring(Lobed(1.0, 4, 0.05), 15)


def test_a_matched_sun_of_the_planets_own_e_is_the_planet():
    planet = Lobed(1.0, 3, 0.08)
    assert matched_sun(planet, 0.08).radius == pytest.approx(1.0, abs=1e-14)


@pytest.fixture(scope="module")
def square():
    planet = Lobed(1.0, 4, 0.05)
    sun, _ = close_ring(planet, 12)
    return planetary_set(sun, planet, 4, 12)


def test_the_ring_closes_lobe_after_lobe_and_turns_as_rolled(square):
    """γ advances by exactly −2π/12 per sun lobe (the ring closes after 12 of its lobes), the
    ring's radius repeats with its period, and φ_r at a lobe's end is the rolled sweep's."""
    lobe = square.lobe
    assert square.ring_angle(lobe) == pytest.approx(-2 * math.pi / 12, abs=1e-12)
    gamma = np.linspace(0.0, 2 * math.pi / 12, 7)
    assert np.max(np.abs(square.ring_radius_at(gamma) - square.ring_radius_at(gamma + 5 * 2 * math.pi / 12))) < 1e-12
    assert square.ring_turn(3 * lobe) == pytest.approx(3 * square.data.ring_turn, abs=1e-12)
    # the ring's rate by the Kennedy integration, at a lobe's end
    assert square.ring_turn(lobe) == pytest.approx(
        by_sun_angle(square.sun, square.planet, steps=100).ring_turn, abs=1e-6
    )


def test_the_ring_held_moves_every_planet_as_the_first(square):
    """Ring held: each planet's centre at the same distance from O, evenly spaced, and the sun
    turned back by φ_r; the planets' orbit (carrier) angle is γ."""
    state = square.ring_held(0.37)
    radii = np.hypot(state["centres"][:, 0], state["centres"][:, 1])
    assert np.ptp(radii) < 1e-12
    angles = np.unwrap(np.arctan2(state["centres"][:, 1], state["centres"][:, 0]))
    assert np.allclose(np.diff(angles), 2 * math.pi / 4, atol=1e-12)
    assert state["sun"] == pytest.approx(-float(square.ring_turn(0.37)), abs=1e-15)


def test_the_planets_gap_bounds_the_circles_gap():
    """e = 0: planets of radius 1 on an orbit of 2, N = 4: the gap is 4·sin(π/4) − 2 exactly; the
    certified bound lies at most the tolerance under it and never over."""
    circle = Lobed(1.0, 4, 0.0)
    bound, least, _ = planet_gap(planetary_set(circle, circle, 4, 12))
    exact = 4 * math.sin(math.pi / 4) - 2
    assert bound <= exact + 1e-9
    assert bound >= exact - 6e-3
    assert least == pytest.approx(exact, abs=1e-4)


def test_the_phasing_rule():
    assert phasing(4, 12, 4) is None
    assert phasing(3, 9, 3) is None
    assert "use 3 or 6 planets" in phasing(6, 18, 4)
    assert "at least 3" in phasing(4, 12, 2)


# ----------------------------------------------------------------------------- the mechanism


@pytest.fixture(scope="module")
def square_draft():
    from .conftest import drafted

    return drafted("nc_square", nc_planetary.design)[1]


def test_the_square_set_is_closed_proved_and_phased(square_draft):
    """The example square set: closed to round-off and again by the Kennedy integration, both
    meshes without overlap at every position of a sun lobe, biting when nudged, with a play of
    most of the 0.2 mm backlash; sun, planets, ring carry 16, 16, 48 teeth of one module."""
    data = square_draft.data
    assert data["set"]["closure_residual"] <= 1e-9
    assert data["set"]["closure_by_sun_angle"] <= 1e-9
    teeth = data["teeth"]
    assert (teeth["sun"], teeth["planet"], teeth["ring"]) == (16, 16, 48)
    # the module from the planets' perimeter, by a trapezoid sum (independent of the arc frames)
    x = np.linspace(0.0, 2 * math.pi, 200001)
    perimeter = np.trapezoid(Lobed(20.0, 4, 0.05).speed(x), x)
    assert teeth["module"] == pytest.approx(perimeter / (math.pi * 16), rel=1e-9)
    for mesh in data["meshes"]:
        assert mesh["max_overlap"] <= mesh["allowed_overlap"]
        assert mesh["max_depth"] <= 2 * 0.01
        assert mesh["nudged_min_overlap"] > mesh["allowed_overlap"]
        assert 0.1 < mesh["least_play"] <= 0.2 + 4 * 0.01
    assert not square_draft.findings


def test_the_planets_sit_on_their_orbit_evenly(square_draft):
    """Four planet placements, centres at the orbit radius of θ = 0 (the sun's lobe on a planet's
    valley: the least, by symmetry, 2R(1 + …) within the orbit's range), a quarter turn apart."""
    planets = [pl for pl in square_draft.placements if pl.part == "planet"]
    centres = np.array([pl.offset for pl in planets])
    radii = np.hypot(centres[:, 0], centres[:, 1])
    data = square_draft.data["set"]
    assert np.ptp(radii) < 1e-9
    assert data["orbit_min"] - 1e-9 <= radii[0] <= data["orbit_max"] + 1e-9
    angles = np.unwrap(np.arctan2(centres[:, 1], centres[:, 0]))
    assert np.allclose(np.diff(angles), math.pi / 2, atol=1e-12)
    assert np.allclose(np.diff([pl.angle for pl in planets]), math.pi / 2, atol=1e-12)


def test_bad_sets_are_refused_in_one_line():
    from gearcad.errors import ProfileError
    from gearcad.profiles import validated
    from gearcad.profiles.nc_planetary import NcPlanetaryParams

    def params(**s):
        base = {"lobes": 4, "e": 0.05, "radius": 20.0, "planets": 4}
        return validated(NcPlanetaryParams, set={**base, **s}, teeth={"count": 24})

    with pytest.raises(ProfileError, match=r"^set.e = 0.06: must be below 1/\(n² \+ 1\) = 0.05882"):
        params(e=0.06)
    with pytest.raises(ProfileError, match=r"^set.planets = 3: must divide gcd\(set.lobes, ring lobes\)"):
        params(planets=3)
    with pytest.raises(ProfileError, match=r"^teeth.count = 26: must be a multiple of set.lobes = 4"):
        validated(NcPlanetaryParams, set={"lobes": 4, "e": 0.05, "radius": 20.0, "planets": 4}, teeth={"count": 26})


# ------------------------------------------------------------------ two stacked bands (retention)


def _turned_over(ring: np.ndarray, line: float) -> np.ndarray:
    """``ring`` mirrored about the line through the origin at angle ``line``: z → e^{2iu}·z̄
    (complex numbers, not the code's matrix)."""
    z = (ring[:, 0] - 1j * ring[:, 1]) * np.exp(2j * line)
    return np.column_stack([z.real, z.imag])


def _band_polygons(draft, upper: bool) -> dict:
    """Each part's band as a shapely polygon in its own frame: the drawn outline, or (``upper``)
    the outline turned over about its line from ``draft.bands``."""
    import shapely

    out = {}
    for spec in draft.parts:
        line = draft.bands[spec.name]
        rings = [spec.outer] if spec.hole is None else [spec.outer, spec.hole]
        if upper:
            rings = [_turned_over(r, line) for r in rings]
        out[spec.name] = shapely.Polygon(rings[0], rings[1:])
    return out


def _placed(polygon, angle: float, pivot) -> object:
    import shapely

    return shapely.affinity.translate(shapely.affinity.rotate(polygon, angle, origin=(0, 0), use_radians=True), *pivot)


def test_the_upper_bands_mesh_and_hold_the_planets(square_draft):
    """Retention by two stacked bands: each part's upper band is its lower band turned over about
    its line (sun and ring: the x axis; the planet: the line through its centre toward O).

    Held, not sliding out: at the assembly a planet's upper band stands in the sun's and the
    ring's lower bands' teeth (and its lower band in their upper bands'), by a good part of a
    tooth's area — with one band (or bands half a pitch apart but the same) that area is 0.
    Meshing: at 16 frames of the animation's cycle (sampled, independently of the proof, which
    covers the lower bands) the upper bands overlap no more than the allowance, as the lower do."""
    import shapely

    draft = square_draft
    assert set(draft.bands) == {"sun", "planet", "ring"}
    lower, upper = _band_polygons(draft, False), _band_polygons(draft, True)
    module = draft.data["teeth"]["module"]
    allowed = draft.data["meshes"][0]["allowed_overlap"]
    sun_pl, planet_pl, ring_pl = draft.placements[0], draft.placements[1], draft.placements[-1]
    placed = {
        (name, band): _placed(polys[name], pl.angle, pl.offset)
        for name, pl in (("sun", sun_pl), ("planet", planet_pl), ("ring", ring_pl))
        for band, polys in (("lower", lower), ("upper", upper))
    }
    # a tooth's area is about m·(π m/2)·… : the blocking overlaps are each over 0.5 m²
    for other in ("sun", "ring"):
        assert placed["planet", "lower"].intersection(placed[other, "lower"]).area <= allowed
        assert placed["planet", "upper"].intersection(placed[other, "upper"]).area <= allowed
        assert placed["planet", "upper"].intersection(placed[other, "lower"]).area > 0.5 * module**2
        assert placed["planet", "lower"].intersection(placed[other, "upper"]).area > 0.5 * module**2
    motion = draft.motion
    names = motion.parts
    frames = range(0, len(motion.angles), max(1, len(motion.angles) // 16))
    worst = {"lower": 0.0, "upper": 0.0}
    for k in frames:
        for band, polys in (("lower", lower), ("upper", upper)):
            at = [
                _placed(polys[name], pl.angle + motion.angles[k, j], motion.pivots[k, j])
                for j, (name, pl) in enumerate(zip(names, draft.placements))
            ]
            sun, planets, ring = at[0], at[1:-1], at[-1]
            for planet in planets:
                worst[band] = max(worst[band], planet.intersection(sun).area, planet.intersection(ring).area)
            assert shapely.union_all(planets).area == pytest.approx(len(planets) * planets[0].area, rel=1e-9)
    assert worst["lower"] <= allowed and worst["upper"] <= allowed, worst


@pytest.mark.parametrize("chamfer", [0.0, 0.4])
def test_a_stacked_solid_is_one_watertight_body_of_two_bands(square_draft, chamfer):
    """The planet's solid (export.mesh.stacked): one closed surface — every edge used twice, once
    each way, and V − E + F = 2 (one shell of genus 0: two loose bands would give 4) — whose
    volume by the divergence theorem is the band's area × thickness less, with a chamfer, a 45°
    chamfer's c²/2 per mm of edge at the bottom and at the top (perimeter × c² in all); its first
    chamfered level (z = c) lies on the lower outline, its last (z = h − c) on the outline turned
    over (z = 0 and h without a chamfer), and a second call gives the same arrays (the chamfered)."""
    import shapely

    from gearcad.export.mesh import stacked
    from gearcad.geometry.outline import Outline

    spec = draft_part(square_draft, "planet")
    line = square_draft.bands["planet"]
    lower, upper = Outline((spec.outer,)), Outline((_turned_over(spec.outer, line)[::-1],))
    h = 5.0
    solid = stacked(lower, upper, h, name="planet", chamfer=chamfer)
    v, t = solid.vertices, solid.triangles
    directed = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    ahead, back = np.sort(directed[:, 0] * len(v) + directed[:, 1]), np.sort(directed[:, 1] * len(v) + directed[:, 0])
    assert np.all(np.diff(ahead) > 0) and np.array_equal(ahead, back)  # no edge twice the same way, each once back
    assert len(np.unique(t)) - len(directed) // 2 + len(t) == 2
    volume = np.einsum("ij,ij->i", v[t[:, 0]], np.cross(v[t[:, 1]], v[t[:, 2]])).sum() / 6
    polygon = shapely.Polygon(spec.outer)
    expected = polygon.area * h - polygon.exterior.length * chamfer**2
    assert volume == pytest.approx(expected, rel=1e-4 if chamfer else 1e-9)
    assert solid.volume == pytest.approx(volume, rel=1e-9)
    for z, ring in ((chamfer, spec.outer), (h - chamfer, upper.outer)):  # the outlines' own levels
        level = v[np.isclose(v[:, 2], z, atol=1e-9), :2]
        assert len(level) >= len(ring) // 2
        assert max(shapely.LinearRing(ring).distance(shapely.Point(p)) for p in level[::7]) < 1e-9
    if chamfer:
        again = stacked(lower, upper, h, name="planet", chamfer=chamfer)
        assert np.array_equal(again.vertices, v) and np.array_equal(again.triangles, t)


def draft_part(draft, name: str):
    return next(spec for spec in draft.parts if spec.name == name)


def test_the_plate_holds_the_set_assembled_in_the_middle_of_the_bed(square_draft):
    """Stacked bands cannot be put together loose: the plate is the assembly as placed (every
    placement moved by one vector), the ring's centre on the bed's centre (its rim a circle about
    its pivot, within the rim's chords); a bed too small for the ring with its margins holds no
    plate and a ``bed`` finding says so."""
    import dataclasses

    from gearcad.mechanisms.finish import finish

    out = square_draft.params.output
    params = square_draft.params.model_copy(update={"output": out.model_copy(update={"formats": ("3mf",)})})
    design = finish(dataclasses.replace(square_draft, params=params))
    (plate,) = design.plates
    moves = np.array([np.subtract(a.offset, b.offset) for a, b in zip(plate, square_draft.placements)])
    assert np.ptp(moves, axis=0) == pytest.approx([0, 0], abs=1e-9)
    assert [pl.angle for pl in plate] == [pl.angle for pl in square_draft.placements]
    assert plate[-1].offset == pytest.approx(np.divide(out.bed, 2), abs=0.01)
    small = params.model_copy(update={"output": params.output.model_copy(update={"bed": (120.0, 120.0)})})
    refused = finish(dataclasses.replace(square_draft, params=small))
    assert refused.plates == () and [f.code for f in refused.findings] == ["bed"]


def test_a_stacked_step_solid_is_one_valid_solid_of_both_bands():
    """The STEP side (export.step_brep): a ring of three lines and a half circle turned over keeps
    its area 8 + π/2 (a sign slip of the bulge gives 8 − π/2) and its arc on the mirrored chord;
    the two bands fused are one valid solid of volume h·(8 + π/2), as OpenCASCADE measures it."""
    pytest.importorskip("OCP")
    from OCP.BRepCheck import BRepCheck_Analyzer
    from OCP.TopAbs import TopAbs_SOLID
    from OCP.TopExp import TopExp_Explorer

    from gearcad.export.step_brep import ring_area, volume
    from gearcad.export.step_stacked import mirrored_ring, stacked_solid
    from gearcad.geometry.arcfit import ArcRing

    ring = ArcRing(np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [0.0, 2.0]]), np.array([0.0, 1.0, 0.0, 0.0]))
    line = 0.3
    turned = mirrored_ring(ring, line)
    assert ring_area(turned) == pytest.approx(8 + math.pi / 2, rel=1e-12)
    (j,) = np.nonzero(turned.bulges)[0]
    chord = _turned_over(np.array([[4.0, 2.0], [4.0, 0.0]]), line)
    assert np.allclose(turned.vertices[[j, (j + 1) % 4]], chord, atol=1e-12)
    solid = stacked_solid([ring], [turned], 3.0, name="d")
    solids = TopExp_Explorer(solid.shape, TopAbs_SOLID)
    count = 0
    while solids.More():
        count, _ = count + 1, solids.Next()
    assert count == 1 and BRepCheck_Analyzer(solid.shape).IsValid()
    assert volume(solid.shape) == pytest.approx(3.0 * (8 + math.pi / 2), rel=1e-7)
    assert solid.volume == pytest.approx(3.0 * (8 + math.pi / 2), rel=1e-12)


def test_the_square_sets_least_plays_are_proven_under_an_independent_sweep(built, square_draft):
    """report.json's two bands of the square set (no process: the parts as drawn) are proven by the
    theorem, and each certified least play lies under the least play an independent sweep measures
    at 120 even sun angles over the cycle (a sun lobe; 10 times the positions the proof starts
    from): the set placed as its animation places it, the ring held (``ring_held_frames``), gear 2
    turned each way about its pivot by bisection on whether it meets gear 1 (shapely, whole parts
    cut only where they cannot reach), times its pitch radius at the contact (the sun's pitch point
    from the planet's centre; the ring's ρ(θ)).  At the band's tightest place the sweep's measure
    is the band's own least to 1 µm; the bound keeps the margin (the parts may bite 4·tol/cos α)."""
    import json

    import shapely

    from .fit_oracle import _turn, turns_free

    bands = {b["mesh"]: b for b in json.loads((built / "nc_square" / "report.json").read_text())["bands"]}
    ps, draft = square_draft.detail, square_draft
    sun, planet, ring = (shapely.Polygon(p.outer, None if p.hole is None else [p.hole]) for p in draft.parts)
    radius = lambda g: np.hypot(*shapely.get_coordinates(g).T)  # noqa: E731

    def sweep(theta):
        s, centres, turns = ps.ring_held_frames(theta)  # the sun's turn, the planets' places
        c, b = centres[:, 0], turns[:, 0]  # the first planet in the ring's frame
        pc, pb = _turn(c, -s), b - s  # the planet in the sun's frame
        pitch = ps.sun.point(theta)
        # sun/planet: the planet turned about its centre; farther from O than the sun's tips and
        # what 0.03 rad moves it, it cannot touch the sun
        near = shapely.buffer(shapely.points(_turn(-pc, -pb)), radius(sun).max() + 0.03 * radius(planet).max() + 0.01)
        pieces = shapely.intersection(planet, near)
        up, down = turns_free(sun, pieces, lambda k, xy, t: _turn(xy, pb[k] + t) + pc[k], 0.03)
        sun_planet = (up + down) * np.hypot(*(pitch - pc).T)
        # planet/ring: the ring turned about O is the planet turned back about O, in the ring's
        # frame; within the ring's least radius nothing of the planet can touch it
        inside = shapely.buffer(shapely.points(_turn(-c, -b)), radius(ring.interiors[0]).min() - 0.01)
        pieces = shapely.difference(planet, inside)
        up, down = turns_free(ring, pieces, lambda k, xy, t: _turn(_turn(xy, b[k]) + c[k], t), 0.01)
        return {"sun/planet": sun_planet, "planet/ring": (up + down) * ps.rho(theta)}

    dense = sweep(np.arange(120) * ps.lobe / 120)
    tightest = sweep(np.array([bands[name]["worst_phi"] for name in dense]))
    margin = -4 * 0.01 / math.cos(math.radians(20))
    for k, (name, plays) in enumerate(dense.items()):
        b = bands[name]
        assert b["certificate"] == "theorem" and b["proven"] and b["verdict"] == "fits"
        assert margin <= b["certified_min"] <= float(plays.min()) + 1e-6, (name, b["certified_min"], plays.min())
        assert b["certified_min"] <= b["min"] and tightest[name][k] == pytest.approx(b["min"], abs=1e-3)
