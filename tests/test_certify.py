"""The proven certificate of the least play (gearcad/fitting/prove.py, ``output.certificate =
"theorem"``; docs/fit.md "How the least play is certified") on a pair built here: two eight-tooth
wheels with straight-sided teeth, rolling at k = 1, one of gear 1's flanks carrying a narrow bump
that takes play over a stretch of driver angle far narrower than the first positions' spacing.
The true least play comes from the oracle's exact vertex-against-edge turns (tests/fit_oracle.py),
not from gearcad's band code."""

from __future__ import annotations

import math

import numpy as np
import shapely

from gearcad.fitting.band import pair_band
from gearcad.fitting.pair_geometry import follower_speed
from gearcad.fitting.play import PairGeometry
from gearcad.fitting.prove import prove_lazily, prove_play
from tests.fit_oracle import free_turns

N, R, A, E = 8, 10.0, 1.0, 20.3
PITCH = 2 * math.pi / N
MODULE = 2 * R / N


def _wheel(base: float, tip: float, phase: float, bump: bool = False) -> np.ndarray:
    """A wheel of N straight-sided teeth (half-angles ``base`` at the root, ``tip`` at the tip,
    fractions of the pitch), the first centred at ``phase``; ``bump``: a 0.25 mm bump half way up
    the first tooth's leading flank."""
    pts = []
    for i in range(N):
        c = phase + i * PITCH
        corners = [(R - 1.25 * A, c - 0.5 * PITCH), (R - A, c - base * PITCH)]
        if bump and i == 0:
            lo, hi = np.array([R - A, c - base * PITCH]), np.array([R + A, c - tip * PITCH])
            for f, out in ((0.47, 0.0), (0.5, 0.25), (0.53, 0.0)):
                r, a = lo + f * (hi - lo)
                corners.append((r, a - out / r))
        corners += [(R + A, c - tip * PITCH), (R + A, c + tip * PITCH), (R - A, c + base * PITCH)]
        pts += [(r * math.cos(a), r * math.sin(a)) for r, a in corners]
    return np.array(pts)


RINGS = (_wheel(0.3, 0.2, 0.0, bump=True), _wheel(0.28, 0.17, math.pi + PITCH / 2))
SLOPE = np.ones_like


def _pair(phi1: np.ndarray) -> PairGeometry:
    return PairGeometry(
        rings=RINGS,
        center_distance=E,
        phi1=phi1,
        phi2=phi1.copy(),
        r1=np.full(len(phi1), E / 2),
        module=MODULE,
        pressure_angle=math.radians(20),
        teeth=np.zeros(len(phi1), dtype=int),
        at=_pair,
        ratio=RATIO,
        slope=SLOPE,
    )


RATIO = follower_speed(SLOPE, 2 * math.pi, samples=256)


def _oracle_play(phi: float) -> float:
    """Gear 2's free turn each way at driver angle φ, exact (the oracle), times its arm."""
    c, s = math.cos(-phi), math.sin(-phi)
    g1 = shapely.Polygon(RINGS[0] @ np.array([[c, s], [-s, c]]))
    c2, s2 = math.cos(phi), math.sin(phi)
    g2 = shapely.Polygon(RINGS[1] @ np.array([[c2, s2], [-s2, c2]]) + [E, 0.0])
    up, down = free_turns(g1, g2, np.array([E, 0.0]), np.array([E / 2, 0.0]), 3 * MODULE, 0.3)
    return (up + down) * (E / 2)


def test_a_tight_spot_between_the_first_positions_is_found_and_bounded_below():
    g = _pair(np.linspace(0.0, 2 * math.pi, 2 * N, endpoint=False))
    first = np.array([_oracle_play(p) for p in g.phi1])
    dense = np.linspace(-0.6, 0.0, 31)  # the bump meets gear 2's tip about φ = −0.4
    plays = np.array([_oracle_play(p) for p in dense])
    j = int(np.argmin(plays))
    lo, hi = dense[max(j - 1, 0)], dense[min(j + 1, len(dense) - 1)]
    for _ in range(16):  # golden section on the oracle's play about the least
        a, b = hi - 0.618 * (hi - lo), lo + 0.618 * (hi - lo)
        if _oracle_play(a) <= _oracle_play(b):
            hi = b
        else:
            lo = a
    true_min = min(_oracle_play(0.5 * (lo + hi)), float(plays.min()))
    assert first.min() > true_min + 0.005  # the first positions miss it: it lies between them
    margin = 0.25 * true_min  # a margin the pair keeps: the certificate must prove it
    geo, play, cert = prove_play(g, (0.0, 0.0), 0.0, 1e-3, reach=3.0, margin=margin)
    assert cert.proven
    assert margin <= cert.lower <= true_min
    assert cert.positions > len(g.phi1)  # refined where the bound was weak
    # a margin between the true least and the first positions' least: sampled, it would fit;
    # the certificate must find the spot (a measured jam) or say it could not close, never fit
    margin = true_min + 0.004
    geo, play, cert = prove_play(g, (0.0, 0.0), 0.0, 1e-3, reach=3.0, margin=margin, budget=64)
    assert not (cert.proven and cert.lower >= margin)


def test_the_band_takes_the_certificate_output_certificate_names():
    """pair_band bounds the play by the slope estimate unless told "theorem" (the profile's
    ``output.certificate``), and the report says which; the theorem's bound proves this pair's
    exact-parts margin, no more than the least play it measured."""
    g = _pair(np.linspace(0.0, 2 * math.pi, 2 * N, endpoint=False))
    kw = {"edge": (0.0, 0.0, 0.0), "spread": 0.0, "tol": 1e-3, "backlash": 0.0}
    assert pair_band(g, **kw).as_dict()["certificate"] == "estimate"
    proven = pair_band(g, **kw, certificate="theorem").as_dict()
    assert proven["certificate"] == "theorem" and proven["proven"] and proven["verdict"] == "fits"
    assert proven["certified_min"] <= proven["min"]


def test_the_assembly_says_its_depth_is_proven_only_where_every_band_is(built):
    """report.json's ``assembly.depth_proven``: true where every mesh's band is proven to fit
    (the example gear pairs, the trains whose meshes repeat by a tooth, the noncircular internal
    pair and planetary sets), false where any band is sampled or estimated, or there is none (the
    rolling wheel); and the check's assembly line says so only then."""
    import json

    from tests.conftest import EXAMPLES

    seen = set()
    for path in sorted(EXAMPLES.glob("*.toml")):
        report = json.loads((built / path.stem / "report.json").read_text(encoding="utf-8"))
        bands = report.get("bands", [])
        every = bool(bands) and all(
            b.get("certificate") == "theorem" and b.get("proven") and b["verdict"] == "fits" for b in bands
        )
        assert report["assembly"].get("depth_proven", False) == (every and report["assembly"]["max_depth"] is not None)
        seen.add(report["assembly"].get("depth_proven", False))
    for name in ("spur_pair", "elliptic_focus", "walker"):
        assert json.loads((built / name / "report.json").read_text(encoding="utf-8"))["assembly"]["depth_proven"]
    assert seen == {True, False}


def test_a_lazy_proof_settles_the_same_verdict_first_and_finishes_as_the_whole_proof():
    """What a backlash search reads of each cut (:func:`prove_lazily`'s first answer) is the
    verdict of the whole proof, proven, its bound no higher than the finished one's; finished,
    it is the whole proof, position for position."""
    g = _pair(np.linspace(0.0, 2 * math.pi, 2 * N, endpoint=False))
    margin = 0.01
    whole = prove_play(g, (0.0, 0.0), 0.0, 1e-3, reach=3.0, margin=margin)
    (geo, play, cert), finish = prove_lazily(g, (0.0, 0.0), 0.0, 1e-3, reach=3.0, margin=margin)
    assert cert.proven and whole[2].proven and cert.lower >= margin
    assert cert.lower <= whole[2].lower and cert.positions < whole[2].positions
    done = finish()
    assert done[2] == whole[2] and np.array_equal(done[1], whole[1])
    assert finish() is done  # carried on once


def test_a_lazy_proof_of_a_jam_answers_at_the_first_positions_and_finishes_as_the_whole_proof():
    """A cut that jams settles its verdict at the first position measured under the margin: a
    backlash search reads that (the first positions' least); finished — what a design reports —
    the intervals about the least are halved as :func:`prove_play` halves them."""
    g = _pair(np.linspace(0.0, 2 * math.pi, 2 * N, endpoint=False))
    grown, margin = (0.1, 0.1), 0.01  # both wheels 0.1 mm fatter: the bumped flank bites
    whole = prove_play(g, grown, 0.0, 1e-3, reach=3.0, margin=margin)
    (geo, play, cert), finish = prove_lazily(g, grown, 0.0, 1e-3, reach=3.0, margin=margin)
    assert cert.proven and cert.lower < margin and cert.lower == float(np.min(play))
    assert cert.positions == 2 * N < whole[2].positions  # not yet halved
    done = finish()
    assert done[2] == whole[2] and np.array_equal(done[1], whole[1])
    assert finish() is done


def test_a_proof_whose_budget_runs_out_says_so_also_where_nothing_pins_the_least():
    """A proof left open by its work budget is an answer (not proven, the interval named), also
    under measures that pin nothing down (a general motion's: ``tighten`` 0), and a jam with no
    halvings to carry on is its own whole proof (a review found both raising StopIteration)."""
    from gearcad.fitting import prove

    class Pinless(prove.Measures):
        tighten = 0.0

    g = _pair(np.linspace(0.0, 2 * math.pi, 2 * N, endpoint=False))
    geo, play, cert = prove_play(g, (0.0, 0.0), 0.0, 1e-3, reach=3.0, margin=0.0, budget=2 * N + 1, measures=Pinless())
    assert not cert.proven and cert.lower == -1e-3 and cert.open[0] < cert.open[1]
    lazy, finish = prove_lazily(g, (0.1, 0.1), 0.0, 1e-3, reach=3.0, margin=0.01, measures=Pinless())
    assert finish()[2] == prove_play(g, (0.1, 0.1), 0.0, 1e-3, reach=3.0, margin=0.01)[2]


def test_a_pairs_first_bounds_are_taken_over_half_intervals():
    """Where the first positions show no jam, a gear pair's proof measures their midpoints before
    it takes any bound (``Measures.first_split``, docs/fit.md "The first bounds over half
    intervals"): every midpoint is among the positions of its first answer, where without the
    split the refining measures only some; a budget under the split's positions is kept."""
    from gearcad.fitting import prove

    class Unsplit(prove.Measures):
        first_split = 1

    g = _pair(np.linspace(0.0, 2 * math.pi, 2 * N, endpoint=False))
    mids = (g.phi1 + PITCH / 4) % (2 * math.pi)  # two first positions a tooth: half a pitch apart

    def measured(geo) -> np.ndarray:
        gaps = np.abs((geo.phi1[None, :] - mids[:, None] + math.pi) % (2 * math.pi) - math.pi)
        return np.min(gaps, axis=1) < 1e-12

    (geo, _, cert), _ = prove_lazily(g, (0.0, 0.0), 0.0, 1e-3, reach=3.0, margin=0.01)
    assert cert.proven and measured(geo).all()
    (geo, _, cert), _ = prove_lazily(g, (0.0, 0.0), 0.0, 1e-3, reach=3.0, margin=0.01, measures=Unsplit())
    assert cert.proven and not measured(geo).all()
    geo, _, cert = prove_play(g, (0.0, 0.0), 0.0, 1e-3, reach=3.0, margin=0.01, budget=3 * N)
    assert cert.positions <= 3 * N and len(geo.phi1) <= 3 * N


def test_a_lone_first_position_bounds_the_whole_cycle():
    """A proof started from one position covers the whole turn from it (its gap to the next is
    the cycle, not 0: a review found a zero-width interval "proven" at 0.78 mm on this pair,
    whose play falls to about 0.4 mm): whatever it proves lies under the least the oracle's exact
    turns give anywhere on a grid."""
    grid = np.linspace(0.0, 2 * math.pi, 64, endpoint=False)
    least = min(_oracle_play(p) for p in grid)
    geo, play, cert = prove_play(_pair(np.array([0.3])), (0.0, 0.0), 0.0, 1e-3, reach=3.0, margin=0.01)
    assert cert.positions > 1 and len(geo.phi1) == len(play) == cert.positions
    assert cert.lower <= least + 1e-9


def test_the_bound_looks_only_at_vertices_where_a_mate_can_first_touch():
    """Two parts coming together first touch with a vertex of one on an edge of the other, and not
    at a reflex vertex (the part fills more than a half-disc there): the bound's vertices
    (``corners.corners``) are a window's convex and straight vertices, each once — here a square
    notched at (2, 2) and holed by a square, given clockwise: its four outer corners and the
    straight vertex at (4, 2); the notch's reflex vertex and the hole's four corners (reflex seen
    from the part) left out — and the normal at each is the unit normal to the chord between its
    neighbours."""
    from gearcad.fitting.corners import corners

    outer = [(0, 0), (0, 4), (2, 2), (4, 4), (4, 2), (4, 0)]  # clockwise
    hole = [(0.5, 0.5), (1.5, 0.5), (1.5, 1.5), (0.5, 1.5)]
    xy, normal, window = corners(np.array([shapely.Polygon(outer, [hole])]))
    assert not window.any()
    assert sorted(map(tuple, xy.tolist())) == [(0, 0), (0, 4), (4, 0), (4, 2), (4, 4)]
    chords = {(0, 0): (-4, 4), (0, 4): (2, 2), (4, 4): (2, 0), (4, 2): (0, 4), (4, 0): (4, 2)}
    for (x, y), n in zip(xy.tolist(), normal):
        cx, cy = chords[(x, y)]  # from the vertex before to the one after, round either way
        assert abs(np.hypot(*n) - 1) < 1e-12 and abs(n @ np.array([cx, cy])) < 1e-12, ((x, y), n)
