"""Fuzz test of the check path: any profile dict ends in a design or one gearcad error, in budget.

Profiles are generated as dicts (the TOML's tables) for every mechanism: the gear pair with
every curve, the roller body (harmonic and series), the rolling wheel and the carrier train
(external and internal meshes, and a compound ring).  Half of them are built from valid values only, chosen so the
design is small and quick (coarse tolerance); the other half also draw, for every key, edge
values — 0, negatives, huge and tiny numbers, NaN and infinity, strings, booleans, None,
400-digit integers, empty and long lists, tables where a value belongs — unknown keys, and
whole tables replaced by a value.

``gearcad.check(data)`` must then, within a time and memory budget, either return a
:class:`~gearcad.mechanisms.Design` whose parts have finite outlines, simple cut paths (as
drawn: arcs flattened) and a report that is strict JSON, or raise a
:class:`~gearcad.errors.GearcadError` of short lines, each :class:`~gearcad.errors.ProfileError`
line naming a dotted key.  Anything else — another exception, a ``MemoryError``, running
over the budget — fails.

The CI run is small and fixed (``derandomize=True``).  A long campaign::

    GEARCAD_FUZZ_EXAMPLES=300 GEARCAD_FUZZ_WIDE=1 GEARCAD_FUZZ_SEED=1 \\
    GEARCAD_FUZZ_LOG=/tmp/fuzz.jsonl python -m pytest tests/test_fuzz.py

draws ``GEARCAD_FUZZ_EXAMPLES`` profiles per kind from a random seed, includes the regions
of known, not yet fixed findings (``GEARCAD_FUZZ_WIDE``: see ``_UNBOUNDED``), and with
``GEARCAD_FUZZ_LOG`` records every failure as a JSON line and goes on instead of stopping.
"""

from __future__ import annotations

import base64
import json
import logging
import math
import os
import pickle
import re
import resource
import select
import signal
import stat
import traceback
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any, get_args

import numpy as np
import pytest
from hypothesis import HealthCheck, given, seed, settings
from hypothesis import strategies as st
from pydantic import BaseModel

import gearcad
from gearcad.errors import GearcadError, ProfileError
from gearcad.geometry.arcfit import arc_points
from gearcad.geometry.verify import is_simple
from gearcad.mechanisms import MECHANISMS
from gearcad.profiles import CarrierTrainParams, GearPairParams, RollerBodyParams, RollingWheelParams

EXAMPLES = int(os.environ.get("GEARCAD_FUZZ_EXAMPLES", "4"))
"""Profiles per kind (13 kinds)."""
WIDE = os.environ.get("GEARCAD_FUZZ_WIDE", "") == "1"
LOG = os.environ.get("GEARCAD_FUZZ_LOG", "")
SEED = os.environ.get("GEARCAD_FUZZ_SEED", "")
SECONDS = float(os.environ.get("GEARCAD_FUZZ_SECONDS", "10"))
"""Time budget of one check, CPU seconds (not wall: the suite must pass on a loaded machine)."""
SLOWER = {"nc-internal": 2.0, "roller-body": 2.0}
"""Kinds whose check takes longer by design, and by how much: an internal noncircular mesh's band
is certified over a window of up to seven modules (a ring's tight spot can lie ten modules from
the pitch point) at four positions a tooth; a badly jammed one (a lobed oval pinion of module 6
at no backlash) took 9.5 CPU-s (docs/fit.md). A toothed body's roller is proven over every body
tooth at three to six positions each: 24-tooth rollers of radius 0.05 on a body of scale 150 (457
body teeth, 1371 positions) took 15.3 CPU-s at tolerance 0.01."""
MEMORY = int(float(os.environ.get("GEARCAD_FUZZ_MEMORY_GIB", "2")) * (1 << 30))
"""Memory budget of one check: address space it may add to the process, bytes."""

OMIT = object()
"""A key left out of its table."""

_UNBOUNDED: dict[str, str] = {}
"""Keys whose huge or tiny values are accepted but lead to unbounded work (findings not yet
fixed): the CI run draws no size extremes for them; ``GEARCAD_FUZZ_WIDE=1`` does."""

# ---------------------------------------------------------------------------------------------
# values


def _floats(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False)


_WRONG = st.sampled_from(
    [
        -1,
        -0.5,
        0,
        0.0,
        -0.0,
        float("nan"),
        float("inf"),
        float("-inf"),
        True,
        False,
        None,
        10**400,
        -(10**400),
        2**63,
        "",
        "1",
        "nan",
        "inf",
        "solve",
        "x" * 300,
        "é\n\x00",
        [],
        [1],
        [1.0] * 300,
        [[3, 0.1, 0.0]],
        {},
        {"a": 1},
    ]
)
"""Values of the wrong kind or sign, which no key should take as a large amount of work."""
_SIZES = st.sampled_from([1e-300, 5e-324, 1e-12, 1e-6, 1e6, 1e12, 1e300, 10**18])
"""Size extremes: accepted by some keys (a length > 0 has no upper bound)."""
_ANY = st.one_of(
    st.floats(),
    st.integers(),
    st.text(max_size=12),
    st.lists(st.floats(allow_nan=False), max_size=4),
)


_EXTREME_FLOATS = st.one_of(
    st.floats(-12.0, 12.0).map(lambda e: 10.0**e),
    st.floats(-12.0, 12.0).map(lambda e: -(10.0**e)),
    _SIZES,
)
"""Accepted or not, numbers far from a key's usual range: 1e-12 … 1e12, either sign."""
_EXTREME_INTS = st.sampled_from([-1, 0, 1, 2, 3, 5, 6, 7, 8, 24, 25, 60, 64, 200, 2000, 2001, 100_000])
MODES = ("valid", "wild", "extreme")
"""How a profile is drawn: valid values only; now and then a value of the wrong kind instead
(wild); now and then a number far out of the usual range instead (extreme)."""


class Gen:
    """Draws one profile's values in one of :data:`MODES`."""

    def __init__(self, draw: Callable, mode: str):
        self.draw, self.mode = draw, mode

    @property
    def wild(self) -> bool:
        return self.mode == "wild"

    def key(
        self, name: str, valid: st.SearchStrategy, *, optional: bool = True, edges: tuple = (), known: tuple = ()
    ) -> Any:
        """A value for ``name``: valid, left out (when optional), or an edge value.

        ``known`` are edge values that meet a known finding not yet fixed, and the keys in
        :data:`_UNBOUNDED` get no size extremes: both only when WIDE.
        """
        roll = self.draw(st.integers(0, 19))
        sizes = WIDE or name not in _UNBOUNDED
        if self.mode == "wild" and roll >= 18:
            pools = [_WRONG, _ANY]
            if sizes:
                pools.append(_SIZES)
            edges = edges + known if WIDE else edges
            if edges:
                pools.append(st.sampled_from(edges))
            return self.draw(st.one_of(pools))
        if self.mode == "extreme":
            value = self.draw(valid)
            if roll >= 15 and sizes and not isinstance(value, bool):
                if isinstance(value, float):
                    return self.draw(_EXTREME_FLOATS)
                if isinstance(value, int):
                    return self.draw(_EXTREME_INTS)
            return value
        if optional and roll >= 15:
            return OMIT
        return self.draw(valid)

    def table(self, name: str, entries: dict[str, Any], *, optional: bool = False) -> Any:
        """The table of the given entries (OMIT ones left out); when wild, sometimes an unknown
        key too, or the whole table replaced by a value."""
        if optional and self.draw(st.integers(0, 9)) >= 8:
            return OMIT
        table = {k: v for k, v in entries.items() if v is not OMIT}
        if self.wild:
            roll = self.draw(st.integers(0, 39))
            if roll == 0:
                return self.draw(_WRONG)
            if roll == 1:
                table[self.draw(st.sampled_from(["bogus", "A-1", "x.y", "a b", ""]))] = 1
        return table


def _profile(gen: Gen, mechanism: str | None, tables: dict[str, Any]) -> dict:
    data: dict[str, Any] = {}
    if mechanism is not None:
        data["mechanism"] = gen.key("mechanism", st.just(mechanism), optional=False, edges=("gear-pair", "gear pair"))
    elif gen.wild and gen.draw(st.integers(0, 19)) == 0:
        data["mechanism"] = "gear-pair"
    name = gen.key("name", st.sampled_from(["p", "pair-1", "A_b.c"]), edges=("../x", "/tmp/x", "a/b", "assembly", ".h"))
    if name is not OMIT:
        data["name"] = name
    title = gen.key("title", st.text(max_size=20))
    if title is not OMIT:
        data["title"] = title
    data.update({k: v for k, v in tables.items() if v is not OMIT})
    if gen.wild and gen.draw(st.integers(0, 19)) == 0:
        data[gen.draw(st.sampled_from(["extra", "gear3", "Output"]))] = {}
    return data


def _output(gen: Gen) -> Any:
    """``[output]`` for a small, quick design: a coarse tolerance, no charts or animation."""
    thickness = gen.draw(_floats(2.0, 10.0))
    return gen.table(
        "output",
        {
            "tolerance": gen.key(
                "output.tolerance", _floats(0.01, 0.1), optional=False, edges=(1e-4, 0.5, 0.50001, 9.99e-5)
            ),
            "charts": gen.key("output.charts", st.just(False), optional=False),
            "animation": gen.key("output.animation", st.just(False), optional=False),
            "formats": gen.key(
                "output.formats",
                st.lists(st.sampled_from(["dxf", "svg", "stl", "3mf"]), unique=True),
                edges=(["dwg"], ["dxf", "dxf"]),
            ),
            "dxf": gen.key("output.dxf", st.sampled_from(["polyline", "lines-arcs", "polyline-flat"])),
            "thickness": gen.key("output.thickness", st.just(thickness), edges=(1000, 1000.1)),
            "chamfer": gen.key("output.chamfer", st.sampled_from([0.0, 0.2, 0.5]), edges=(thickness / 2,)),
            "kerf": gen.key("output.kerf", st.sampled_from([0.0, 0.05, 0.1]), edges=(2, 2.01, 1.5)),
            "cut_layer": gen.key("output.cut_layer", st.sampled_from(["CUT", "cut_1"]), edges=("MARK", "a b")),
            "mark_layer": gen.key("output.mark_layer", st.sampled_from(["MARK", "$ENGRAVE"]), edges=("CUT",)),
            "sheet": gen.key("output.sheet", st.tuples(_floats(400, 3000), _floats(400, 3000)).map(list)),
            "gap": gen.key("output.gap", _floats(0.0, 10.0)),
            "bed": gen.key("output.bed", st.tuples(_floats(200, 3000), _floats(200, 3000)).map(list)),
        },
    )


def _bore(gen: Gen) -> Any:
    diameter = gen.draw(st.sampled_from([0.0, 3.0, 5.0]))
    shape = gen.draw(st.sampled_from(["round", "keyway", "flat"])) if diameter else "round"
    width = 1.0 if shape == "keyway" else 0.0
    flat = 0.35 * diameter if shape == "flat" else 0.0
    return gen.table(
        "bore",
        {
            "diameter": gen.key("bore.diameter", st.just(diameter), optional=not diameter, edges=(1e4,)),
            "keyway_width": gen.key("bore.keyway_width", st.just(width), optional=not width),
            "keyway_depth": gen.key("bore.keyway_depth", st.just(width), optional=not width, edges=(50.0,)),
            "flat": gen.key("bore.flat", st.just(flat), optional=not flat),
        },
        optional=True,
    )


# ---------------------------------------------------------------------------------------------
# gear pairs


def _curve(gen: Gen, curve: str) -> tuple[dict, int]:
    """``[gear1]`` entries for one curve kind, and its lobes."""
    entries: dict[str, Any] = {
        "name": gen.key("gear1.name", st.sampled_from(["driver", "g1"]), edges=("gear2", "DRIVER", "sheet")),
    }
    tag = "ellipse" if curve.startswith("ellipse") else curve
    entries["curve"] = gen.key("gear1.curve", st.just(tag), optional=False, edges=("Ellipse", "spline"))
    a = gen.draw(_floats(10.0, 60.0))
    shape = gen.draw(_floats(0.6, 1.0))  # b / a
    lobes = 1
    if curve.startswith("ellipse"):
        pivot = "focus" if curve == "ellipse-focus" else "centre"
        lobes = 1 if pivot == "focus" else 2
        entries["a"] = gen.key("gear1.a", st.just(a), optional=False)
        if gen.draw(st.booleans()):
            entries["b"] = gen.key("gear1.b", st.just(a * shape), optional=False, edges=(2 * a,))
        else:
            entries["eccentricity"] = gen.key(
                "gear1.eccentricity", _floats(0.0, 0.8), optional=False, edges=(1.0, 0.999999)
            )
        entries["pivot"] = gen.key("gear1.pivot", st.just(pivot), optional=pivot == "focus", edges=("center",))
    elif curve == "oval":
        lobes = 2
        entries["a"] = gen.key("gear1.a", st.just(a), optional=False)
        entries["b"] = gen.key("gear1.b", st.just(a * shape), optional=False, edges=(2 * a,))
    elif curve == "circle":
        entries["radius"] = gen.key("gear1.radius", _floats(5.0, 50.0), optional=False)
    elif curve == "ratio":
        lobes = gen.draw(st.integers(1, 3))
        entries["lobes"] = gen.key("gear1.lobes", st.just(lobes), optional=lobes == 1, edges=(25, 24))
        count = gen.draw(st.integers(0, 3))
        orders = gen.draw(st.lists(st.integers(1, 4), min_size=count, max_size=count))
        size = gen.draw(_floats(0.0, 0.3)) / max(count, 1)
        terms = [
            [k * lobes, gen.draw(_floats(-size, size)), gen.draw(_floats(-size, size))] for k in orders
        ]  # scaled by the mean below
        entries["harmonics"] = (terms, lobes)  # finished once gear 2's lobes are known
    elif curve == "walker":
        lobes = 4
        entries["a"] = gen.key("gear1.a", _floats(95.0, 105.0), optional=False)
        entries["b"] = gen.key("gear1.b", _floats(47.0, 53.0), optional=False, edges=(200.0,))
        entries["c"] = gen.key("gear1.c", _floats(310.0, 330.0), optional=False)
        entries["blend_width_deg"] = gen.key("gear1.blend_width_deg", _floats(0.0, 20.0), edges=(45, 44.999))
    elif curve == "samples":
        lobes = gen.draw(st.integers(1, 2))
        n = gen.draw(st.integers(8 * lobes, 48))
        mean, amplitude, phase = gen.draw(_floats(15.0, 40.0)), gen.draw(_floats(0.0, 0.15)), gen.draw(_floats(0, 6.3))
        radii = [mean * (1 + amplitude * math.cos(2 * math.pi * lobes * j / n + phase)) for j in range(n)]
        entries["radii"] = gen.key(
            "gear1.radii", st.just(radii), optional=False, edges=([1.0] * 7, [1.0] * 100_001, radii[:-1] + [-1.0])
        )
        entries["lobes"] = gen.key("gear1.lobes", st.just(lobes), optional=lobes == 1, edges=(0, 25))
    return entries, lobes


def _teeth(gen: Gen, curve: str) -> Any:
    by_count = gen.draw(st.booleans())
    module = (1.2, 3.0) if curve == "walker" else (0.8, 3.0)
    addendum = gen.draw(_floats(0.7, 1.0))
    return gen.table(
        "teeth",
        {
            "module": gen.key("teeth.module", _floats(*module), optional=False, edges=(1e-3, 100.0))
            if not by_count
            else OMIT,
            "count": gen.key("teeth.count", st.integers(12, 60), optional=False, edges=(5, 6, 2001, 2000))
            if by_count
            else OMIT,
            "pressure_angle_deg": gen.key("teeth.pressure_angle_deg", _floats(14.5, 30.0), edges=(9.99, 35, 35.01)),
            "addendum": gen.key("teeth.addendum", st.just(addendum), edges=(2.0, 2.01)),
            "dedendum": gen.key("teeth.dedendum", _floats(1.25, 1.5), edges=(3.0, 0.5)),
            "tip_radius": gen.key("teeth.tip_radius", _floats(0.0, 0.38), edges=(0.6,)),
            "profile_shift": gen.key("teeth.profile_shift", _floats(-0.4, 0.4), edges=(0.8, -0.8)),
            "backlash": gen.key("teeth.backlash", st.sampled_from([0.0, 0.05, 0.1]), edges=(5.0, 1.0)),
            "clearance": gen.key("teeth.clearance", st.sampled_from([0.0, 0.02, 0.05]), edges=(5.0, 0.5)),
        },
        optional=True,
    )


@st.composite
def gear_pairs(draw: Callable, curve: str) -> dict:
    """A gear-pair profile whose driver is ``curve`` (ellipse-focus, ellipse-centre, oval,
    circle, ratio, walker, samples)."""
    gen = Gen(draw, draw(st.sampled_from(MODES)))
    gear1, lobes1 = _curve(gen, curve)
    lobes2 = draw(st.integers(1, 3)) if curve in ("ratio", "samples", "circle") else 1 if curve == "walker" else lobes1
    if curve == "ratio":
        terms, lobes = gear1.pop("harmonics")
        mean = lobes / lobes2
        gear1["harmonics"] = gen.key(
            "gear1.harmonics",
            st.just([[k, c * mean, s * mean] for k, c, s in terms]),
            edges=([[1, 2.0, 0.0]], [[65, 0.1, 0.1]], [[lobes, 0.1, 0.1]] * 17, [[1, float("nan"), 0]]),
        )
        gear1["mean"] = gen.key("gear1.mean", st.just(mean), edges=(mean * 1.01,)) if draw(st.booleans()) else OMIT
    name2 = gen.key("gear2.name", st.sampled_from(["follower", "g2"]), edges=("driver",))
    gear2 = gen.table(
        "gear2",
        {
            "name": name2,
            "lobes": gen.key(
                "gear2.lobes",
                st.just(lobes2),
                optional=lobes2 == lobes1,
                edges=(25, 24, 0),
                known=(4, 2) if curve == "walker" else (),
            ),
        },
    )
    if lobes2 == lobes1 and draw(st.booleans()):
        gear2 = OMIT
    given_names = [gear1["name"], gear2.get("name") if isinstance(gear2, dict) else OMIT]
    names = [n if isinstance(n, str) else f"gear{k + 1}" for k, n in enumerate(given_names)]
    if curve in ("ratio", "walker"):
        distance = _floats(70.0, 80.0) if curve == "walker" else _floats(30.0, 100.0)
    else:
        distance = st.one_of(st.just("solve"), st.just("solve"), _floats(20.0, 150.0))
    pair = gen.table(
        "pair",
        {
            "center_distance": gen.key("pair.center_distance", distance, optional=curve not in ("ratio", "walker")),
            "driver": gen.key("pair.driver", st.sampled_from(names), edges=("nobody",)),
            "driver_rpm": gen.key("pair.driver_rpm", _floats(1.0, 600.0)),
        },
    )
    claim = gen.table(
        "claim",
        {
            "center_distance": gen.key("claim.center_distance", _floats(20.0, 120.0), optional=False),
            "source": gen.key("claim.source", st.text(max_size=20)),
        },
        optional=True,
    )
    if draw(st.integers(0, 2)) or lobes2 != lobes1:
        claim = OMIT
    tables = {
        "gear1": gen.table("gear1", gear1),
        "gear2": gear2,
        "pair": pair,
        "claim": claim,
        "teeth": _teeth(gen, curve),
        "bore": _bore(gen),
        "output": _output(gen),
    }
    return _profile(gen, draw(st.sampled_from([None, "gear-pair"])), tables)


# ---------------------------------------------------------------------------------------------
# the other mechanisms

_ROLLER_AMPLITUDE = {3: 0.18, 6: 0.06, 9: 0.03}
"""A little over the paper's by-eye limits: some bodies are refused as not simple."""


def _series(gen: Gen, name: str) -> Any:
    count = gen.draw(st.integers(0, 3))
    terms = [
        [gen.draw(st.sampled_from([3, 6, 9])), gen.draw(_floats(-0.01, 0.01)), gen.draw(_floats(-0.01, 0.01))]
        for _ in range(count)
    ]
    return gen.key(
        name,
        st.just(terms),
        edges=([[4, 0.1, 0.0]], [[3, float("nan"), 0.0]], [[63, 0.01, 0.0]], [[60, 0.01, 0.0]], [[3, 0.1, 0]] * 17),
    )


@st.composite
def roller_bodies(draw: Callable, series: bool) -> dict:
    """A roller-body profile, harmonic (horizontal or vertical) or by a series."""
    gen = Gen(draw, draw(st.sampled_from(MODES)))
    m = draw(st.sampled_from([3, 6, 9]))
    direction = "series" if series else draw(st.sampled_from(["horizontal", "vertical"]))
    body = {
        "scale": gen.key("body.scale", _floats(50.0, 150.0)),
        "roller_radius": gen.key("body.roller_radius", _floats(0.05, 0.2), edges=(0.005, 0.0049, 0.999)),
        "direction": gen.key("body.direction", st.just(direction), optional=not series, edges=("diagonal",)),
    }
    if series:
        body["f"] = _series(gen, "body.f")
        body["g"] = _series(gen, "body.g")
    else:
        body["amplitude"] = gen.key("body.amplitude", _floats(0.0, _ROLLER_AMPLITUDE[m]), edges=(10.0,))
        body["m"] = gen.key("body.m", st.just(m), edges=(18, 30, 33, 4, 2))
    tables = {
        "body": gen.table("body", body),
        "kinematics": gen.table("kinematics", {"rpm": gen.key("kinematics.rpm", _floats(1.0, 600.0))}, optional=True),
        "teeth": gen.table(
            "teeth",
            {
                "roller_count": gen.key("teeth.roller_count", st.integers(8, 24), optional=False, edges=(7, 200, 201)),
                "pressure_angle_deg": gen.key("teeth.pressure_angle_deg", _floats(14.5, 30.0)),
            },
            optional=True,
        ),
        "bore": _bore(gen),
        "output": _output(gen),
    }
    if draw(st.booleans()):
        tables["teeth"] = OMIT
    return _profile(gen, "roller-body", tables)


@st.composite
def rolling_wheels(draw: Callable) -> dict:
    """A rolling-wheel profile, sometimes with a horizontal rack (H = R − r)."""
    gen = Gen(draw, draw(st.sampled_from(MODES)))
    r, big = draw(_floats(5.0, 50.0)), draw(_floats(10.0, 100.0))
    length = draw(_floats(100.0, 500.0))
    low = max(0.0, big - r)
    height = low if draw(st.integers(0, 4)) == 0 else draw(_floats(low, low + 300.0))
    drive = {
        "r": gen.key("drive.r", st.just(r), optional=False),
        "R": gen.key("drive.R", st.just(big), optional=False, edges=(1e5, 100000.1)),
        "L": gen.key("drive.L", st.just(length), optional=False),
        "H": gen.key("drive.H", st.just(height), optional=False, edges=(1e5,)),
        "driver_rpm": gen.key("drive.driver_rpm", _floats(1.0, 600.0)),
        "travel": gen.key("drive.travel", _floats(1.0, 0.8 * length), edges=(length,)),
    }
    return _profile(gen, "rolling-wheel", {"drive": gen.table("drive", drive), "output": _output(gen)})


@st.composite
def carrier_trains(draw: Callable, internal: bool) -> dict:
    """A carrier-train profile: external meshes only, or a sun, planet and ring."""
    gen = Gen(draw, draw(st.sampled_from(MODES)))
    if internal:
        sun, planet = draw(st.integers(10, 30)), draw(st.integers(8, 30))
        teeth = [sun, planet, draw(st.sampled_from([sun + 2 * planet, planet + 12, planet + 40]))]
        meshes = ["external", "internal"]
    else:
        teeth = draw(st.lists(st.integers(8, 60), min_size=2, max_size=4))
        meshes = ["external"] * (len(teeth) - 1)
    names = [f"gear{k}" for k in range(len(teeth))]
    train = {
        "module": gen.key("train.module", _floats(0.5, 2.0), optional=False, edges=(50.0, 50.01)),
        "teeth": gen.key("train.teeth", st.just(teeth), optional=False, edges=([8], [2000, 8], [7, 20])),
        "meshes": gen.key(
            "train.meshes", st.just(meshes), optional=not internal, edges=(["internal"] * (len(teeth) - 1),)
        ),
        "names": gen.key("train.names", st.just(names), edges=(["a", "A"] + names[2:], names[:1])),
        "gear1_rpm": gen.key("train.gear1_rpm", _floats(-600.0, 600.0)),
        "carrier_rpm": gen.key("train.carrier_rpm", _floats(-600.0, 600.0)),
        "gear1_eps": gen.key("train.gear1_eps", _floats(-10.0, 10.0)),
        "carrier_eps": gen.key("train.carrier_eps", _floats(-10.0, 10.0)),
        "pressure_angle_deg": gen.key("train.pressure_angle_deg", _floats(14.5, 30.0)),
    }
    tables = {"train": gen.table("train", train), "bore": _bore(gen), "output": _output(gen)}
    return _profile(gen, "carrier-train", tables)


@st.composite
def compound_trains(draw: Callable) -> dict:
    """A carrier train whose middle gear is a compound ring (seed 001's second scheme): external
    teeth to gear 1, internal teeth (of their own module) round gear 3."""
    gen = Gen(draw, draw(st.sampled_from(MODES)))
    module, inner_module = draw(_floats(0.5, 2.0)), draw(st.sampled_from([None, 0.5, 1.0, 2.0]))
    m_in = module if inner_module is None else inner_module
    inside = draw(st.integers(8, 30))
    inner_teeth = draw(st.integers(inside + 12, inside + 30))
    # the wall (r_out − 1.25·m) − (r_in + 1.25·m_in) ≥ 2·max(m, m_in), with a tooth to spare
    least = math.ceil((m_in * inner_teeth / 2 + 1.25 * (module + m_in) + 2 * max(module, m_in)) * 2 / module) + 1
    teeth = [draw(st.integers(8, 40)), draw(st.integers(least, least + 20)), inside]
    names = gen.key("train.names", st.just(["gear1", "ring", "gear3"]))
    ring = st.sampled_from(["ring", 2]) if names is not OMIT else st.just(2)
    compound = {
        "gear": gen.key("train.compound.gear", ring, optional=False, edges=("gear1", 3, 0)),
        "inner_teeth": gen.key(
            "train.compound.inner_teeth", st.just(inner_teeth), optional=False, edges=(teeth[1], inside + 11)
        ),
        "inner_module": gen.key(
            "train.compound.inner_module", st.just(inner_module) if inner_module else st.just(OMIT), edges=(50.0,)
        ),
    }
    train = {
        "module": gen.key("train.module", st.just(module), optional=False, edges=(50.0,)),
        "teeth": gen.key("train.teeth", st.just(teeth), optional=False, edges=([8, 8, 8], [20, 2000, 14])),
        "meshes": gen.key("train.meshes", st.just(["external", "internal"]), optional=False),
        "names": names,
        "gear1_rpm": gen.key("train.gear1_rpm", _floats(-600.0, 600.0)),
        "carrier_rpm": gen.key("train.carrier_rpm", _floats(-600.0, 600.0)),
        "compound": gen.table("train.compound", compound),
    }
    tables = {"train": gen.table("train", train), "bore": _bore(gen), "output": _output(gen)}
    return _profile(gen, "carrier-train", tables)


@st.composite
def nc_internals(draw: Callable) -> dict:
    """A noncircular internal pair: an oval pinion (two lobes) in a ring of 3 or 4 lobes.  The
    values a draw shrinks to (its first example) are the mildest: the roundest oval (b = 0.95 a)
    at the most backlash (0.3 mm); the worst — b = 0.8 a jammed at no backlash, 10 to 14 CPU-s
    of fit search, most of this file's time — is left to the campaigns' random draws."""
    gen = Gen(draw, draw(st.sampled_from(MODES)))
    a = draw(_floats(20.0, 35.0))
    lobes = draw(st.sampled_from([3, 4]))
    pinion = {
        "curve": gen.key("pinion.curve", st.just("oval"), optional=False, edges=("spiral",)),
        "a": gen.key("pinion.a", st.just(a), optional=False, edges=(-1.0, 1e6)),
        "b": gen.key(
            "pinion.b", _floats(0.8 * a, 0.95 * a).map(lambda b: 1.75 * a - b), optional=False, edges=(a * 1.5, 0.0)
        ),
    }
    teeth = {
        "count": gen.key("teeth.count", st.sampled_from([20, 30, 40]), optional=False, edges=(7, 401, 31)),
        "backlash": gen.key("teeth.backlash", _floats(0.0, 0.3).map(lambda b: 0.3 - b), edges=(-0.1, 50.0)),
    }
    tables = {
        "pinion": gen.table("pinion", pinion),
        "ring": gen.table("ring", {"lobes": gen.key("ring.lobes", st.just(lobes), optional=False, edges=(1, 2, 0))}),
        "teeth": gen.table("teeth", teeth),
        "bore": _bore(gen),
        "output": _output(gen),
    }
    return _profile(gen, "nc-internal", tables)


@st.composite
def nc_planetaries(draw: Callable) -> dict:
    """A carrier-less noncircular planetary: the square or the triangle set, e inside convexity."""
    gen = Gen(draw, draw(st.sampled_from(MODES)))
    lobes = draw(st.sampled_from([3, 4]))
    limit = 1 / (lobes**2 + 1)
    sets = {
        "lobes": gen.key("set.lobes", st.just(lobes), optional=False, edges=(1, 13)),
        "e": gen.key("set.e", _floats(0.0, 0.9 * limit), optional=False, edges=(limit * 1.5, 0.6, -0.01)),
        "radius": gen.key("set.radius", _floats(15.0, 25.0), optional=False, edges=(0.0, 1e6)),
        "planets": gen.key("set.planets", st.just(lobes), optional=False, edges=(2, 5, 13)),
    }
    teeth = {
        "count": gen.key("teeth.count", st.just(4 * lobes), optional=False, edges=(7, 4 * lobes + 1)),
        "backlash": gen.key("teeth.backlash", _floats(0.1, 0.3), edges=(-0.1,)),
    }
    tables = {
        "set": gen.table("set", sets),
        "teeth": gen.table("teeth", teeth),
        "bore": _bore(gen),
        "output": _output(gen),
    }
    return _profile(gen, "nc-planetary", tables)


_OF_MECHANISM: dict[str, dict[str, st.SearchStrategy[dict]]] = {
    "gear-pair": {
        c: gear_pairs(c) for c in ("ellipse-focus", "ellipse-centre", "oval", "circle", "ratio", "walker", "samples")
    },
    "roller-body": {"harmonic": roller_bodies(False), "series": roller_bodies(True)},
    "rolling-wheel": {"": rolling_wheels()},
    "carrier-train": {
        "external": carrier_trains(False),
        "internal": carrier_trains(True),
        "compound": compound_trains(),
    },
    "nc-internal": {"": nc_internals()},
    "nc-planetary": {"": nc_planetaries()},
}
KINDS: dict[str, st.SearchStrategy[dict]] = {
    f"{name}/{kind}" if kind else name: strategy
    for name in MECHANISMS  # the registry's: a mechanism with no strategies here fails at import
    for kind, strategy in _OF_MECHANISM[name].items()
}

# ---------------------------------------------------------------------------------------------
# the check and its budget


class OverBudget(BaseException):  # noqa: N818 - not an error of the code under test: the budget's
    """The check ran past its time budget (a BaseException, so no ``except Exception`` hides it)."""


def _address_space() -> int:
    with open("/proc/self/status", encoding="ascii") as status:
        for line in status:
            if line.startswith("VmSize:"):
                return int(line.split()[1]) * 1024
    return 0  # pragma: no cover


@contextmanager
def budget(seconds: float, memory: int) -> Iterator[None]:
    """Raise :class:`OverBudget` after ``seconds`` of this process's CPU time (ITIMER_PROF: a
    loaded machine's scheduler does not spend it) and ``MemoryError`` beyond ``memory`` more
    bytes of address space (RLIMIT_AS), restoring both afterwards."""

    def alarm(signum, frame):
        raise OverBudget(f"over the time budget of {seconds:g} CPU seconds")

    previous = signal.signal(signal.SIGPROF, alarm)
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    limit = _address_space() + memory
    if hard != resource.RLIM_INFINITY:
        limit = min(limit, hard)
    resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    signal.setitimer(signal.ITIMER_PROF, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, previous)
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


_NAME = r'(?:[A-Za-z0-9_-]+|"(?:[^"\\]|\\.)*")(?:\[\d+\])*'
_KEY = rf"{_NAME}(?:\.{_NAME})*"
_PROFILE_LINE = re.compile(
    rf"(?:\[(?P<table>{_KEY})\] is missing: .+"
    rf"|(?P<key>{_KEY}|the profile)(?: = .+?: .+|: .+| is missing: .+)"
    r"|the profile must be a table)"
)
_MAX_LINE = 1000
"""Characters: a message shows values shortened, never a whole long list."""


def profile_keys(model: Any, prefix: str = "") -> set[str]:
    """Every dotted key a profile of ``model`` (a params class or union of them) may write."""
    keys: set[str] = set()
    for cls in _models(model):
        for name, field in cls.model_fields.items():
            key = f"{prefix}{name}"
            keys.add(key)
            keys |= profile_keys(field.annotation, f"{key}.")
    return keys


def _models(annotation: Any) -> list[type[BaseModel]]:
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return [annotation]
    return [m for arg in get_args(annotation) for m in _models(arg)]


_KEYS = {
    cls.model_fields["mechanism"].default: profile_keys(cls)
    for cls in (GearPairParams, RollerBodyParams, RollingWheelParams, CarrierTrainParams)
}
_TABLES = sorted({key.split(".")[0] for keys in _KEYS.values() for key in keys if "." in key})
_MENTION = re.compile(rf"\b(?:{'|'.join(_TABLES)})\.[a-z_0-9]+")


def check_error(exc: GearcadError, mechanism: str | None = None) -> None:
    """One short line per problem; a ProfileError's lines each start with the dotted key; a
    DesignError names only keys that the ``mechanism``'s profiles have."""
    text = str(exc)
    lines = text.split("\n")
    assert text.strip(), f"{type(exc).__name__} without a message"
    assert "Traceback" not in text, text
    for line in lines:
        assert line.strip() and line == line.strip(), f"blank or padded line in {text!r}"
        assert len(line) <= _MAX_LINE, f"line of {len(line)} characters: {line[:200]}…"
    if isinstance(exc, ProfileError):
        for line in lines:
            assert _PROFILE_LINE.fullmatch(line), f"ProfileError line names no dotted key: {line!r}"
        return
    assert len(lines) == 1, f"{type(exc).__name__} of {len(lines)} lines: {text!r}"
    if mechanism in _KEYS:
        for key in _MENTION.findall(text):
            assert key in _KEYS[mechanism], f"the message names {key}, which a {mechanism} profile has not: {text}"


def _non_finite(value: Any, where: str = "") -> Iterator[str]:
    if isinstance(value, float | np.floating) and math.isnan(value):
        yield where
    elif isinstance(value, dict):
        for k, v in value.items():
            yield from _non_finite(v, f"{where}.{k}" if where else str(k))
    elif isinstance(value, list | tuple):
        for k, v in enumerate(value):
            yield from _non_finite(v, f"{where}[{k}]")


def check_design(design: gearcad.Design) -> None:
    """Finite outlines, cut paths simple as drawn, the report strict JSON without NaN."""
    tolerance = design.params.output.tolerance
    assert design.parts(), "a design without parts"
    for part in design.parts():
        for ring in part.outline.rings:
            assert len(ring) >= 3 and np.all(np.isfinite(ring)), f"{part.name}: outline ring not finite"
        assert part.outline.area > 0, f"{part.name}: outline area {part.outline.area}"
        assert part.cut, f"{part.name}: no cut path"
        for k, ring in enumerate(part.cut):
            drawn = arc_points(ring, tolerance / 4)
            assert np.all(np.isfinite(drawn)), f"{part.name}: cut ring {k} not finite"
            assert is_simple(drawn), f"{part.name}: cut ring {k} crosses itself as drawn"
    json.dumps(design.report(), allow_nan=False)
    nan = list(_non_finite(design.data))
    assert not nan, f"NaN in the report (written as null): {', '.join(nan[:5])}"


def run_check(data: dict) -> str:
    """The check path on ``data`` within the budget: "design", or the error's class and message."""
    kind = data.get("mechanism") if isinstance(data, dict) else None
    with budget(SECONDS * SLOWER.get(kind, 1.0) if isinstance(kind, str) else SECONDS, MEMORY):
        try:
            design = gearcad.check(data)
        except GearcadError as exc:
            outcome: Any = exc
        else:
            outcome = design
    if isinstance(outcome, GearcadError):
        mechanism = data.get("mechanism", "gear-pair") if isinstance(data, dict) else None
        check_error(outcome, mechanism if isinstance(mechanism, str) else None)
        return f"{type(outcome).__name__}: {outcome}"
    check_design(outcome)
    return "design"


def _where(exc: BaseException) -> str:
    """The deepest gearcad frame of the traceback (else the deepest frame)."""
    frames = traceback.extract_tb(exc.__traceback__)
    ours = [f for f in frames if "/gearcad/" in f.filename.replace(os.sep, "/")] or frames
    if not ours:
        return "?"
    f = ours[-1]
    return f"{f.filename.split('/gearcad/')[-1]}:{f.lineno} in {f.name}"


def _isolated(data: dict) -> dict:
    """``run_check(data)`` in a forked child (the campaign): a check that the alarm cannot stop —
    stuck in C code, or waiting for worker threads — is killed at ten times the budget of wall
    time (a generous multiple: the campaign may run on a loaded machine)."""
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # pragma: no cover - the child
        os.close(read)
        try:
            result = {"outcome": run_check(data)}
        except BaseException as exc:  # noqa: BLE001 - every failure is the finding
            result = {
                "type": type(exc).__name__,
                "message": str(exc)[:2000],
                "where": _where(exc),
                "traceback": "".join(traceback.format_exception(exc))[-4000:],
            }
        with os.fdopen(write, "w", encoding="utf-8") as pipe:
            pipe.write(json.dumps(result, ensure_ascii=False))
        os._exit(0)
    os.close(write)
    with os.fdopen(read, encoding="utf-8") as pipe:
        ready, _, _ = select.select([pipe], [], [], 10 * SECONDS)
        if ready:
            text = pipe.read()
        else:
            os.kill(pid, signal.SIGKILL)
            text = json.dumps({"type": "Hang", "message": f"killed after {10 * SECONDS:g} s", "where": "?"})
    os.waitpid(pid, 0)
    return json.loads(text) if text else {"type": "Crash", "message": "the child died", "where": "?"}


def _campaign(kind: str, data: dict) -> None:
    """Run one check of the campaign and log its outcome, and any failure with its profile."""
    result = _isolated(data)
    if "outcome" not in result:
        entry = {
            "kind": kind,
            **result,
            "data": repr(data)[:20000],
            "pickle": base64.b64encode(pickle.dumps(data)).decode("ascii"),
        }
        with open(LOG, "a", encoding="utf-8") as log:
            log.write(json.dumps(entry, ensure_ascii=False) + "\n")
    outcome = result.get("outcome", "FAILED")
    with open(LOG + ".outcomes", "a", encoding="utf-8") as outcomes:
        outcomes.write(json.dumps({"kind": kind, "outcome": outcome[:300]}, ensure_ascii=False) + "\n")


def _settings(test):
    test = settings(
        max_examples=EXAMPLES,
        deadline=None,
        derandomize=not SEED,
        database=None,
        print_blob=True,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much],
    )(test)
    return seed(int(SEED))(test) if SEED else test


@pytest.fixture(autouse=True)
def _quiet_findings():
    # design warnings are logged; thousands of them would only slow the run down
    logger = logging.getLogger("gearcad")
    level, logger.level = logger.level, logging.CRITICAL
    yield
    logger.setLevel(level)


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_check_path_never_fails_out_of_bounds(kind):
    """Any profile of any mechanism ends in a checked design or one short gearcad error, in budget."""

    @_settings
    @given(data=KINDS[kind])
    def run(data):
        if LOG:
            _campaign(kind, data)
            return
        run_check(data)

    run()


def test_budget_catches_a_slow_check():
    """The budget itself can fail: a loop past the time limit is stopped."""
    with pytest.raises(OverBudget), budget(0.05, MEMORY):
        while True:
            pass


def test_budget_catches_a_large_allocation():
    with pytest.raises(MemoryError), budget(5, 1 << 28):
        np.ones(1 << 27)  # 1 GiB against a budget of 256 MiB


@pytest.mark.parametrize(
    "data",
    [
        {"gear1": {"curve": "circle", "radius": -3}},
        {"gear1": {"curve": "circle", "radius": 20, "bogus": 1}},
        {"mechanism": "rolling-wheel", "drive": {"r": 10, "R": 20, "L": 100, "H": float("nan")}},
        {"gear1": 3},
    ],
)
def test_profile_errors_name_a_key(data):
    """The message check accepts what validation writes: every line starts with the key."""
    with pytest.raises(ProfileError) as caught:
        gearcad.check(data)
    check_error(caught.value)


# ---------------------------------------------------------------------------------------------
# the build's files: what lies around --out, and builds side by side (issue 23)
#
# The design is stubbed (a report the index reads): what is under test is where files go.


def _stub_build(job):
    from gearcad import batch
    from gearcad.mechanisms.base import SCHEMA_VERSION

    params, folder, _ = job
    (folder / "report.json").write_text(json.dumps({"schema": SCHEMA_VERSION, "name": params.name, "files": {}}))
    return batch.BuildResult(params.name, "stub", (), {}, 0.0)


class _Named:
    def __init__(self, name: str) -> None:
        self.name = name


_PLANTS = (
    "index-link",  # OUT/index.html a link to the user's file
    "old-temp-link",  # the old fixed temp name, a link to the user's file
    "old-temp-folder",  # ... a folder
    "profile-link",  # OUT/<profile> a link to a folder outside
    "fifo-report",  # OUT/x/report.json a FIFO
    "foreign-report",  # OUT/y/report.json not gearcad's
    "staging-leftover",  # a killed build's staging folder
    "file-at-out",  # OUT itself a file
    "dangling-out",  # OUT a link to nothing
    "loop-out",  # OUT a link to itself
    "out-via-link-dotdot",  # OUT spelt A/link/../out
)


@st.composite
def filesystems(draw: Callable) -> dict:
    """A state of the folders around --out: whether it exists, how deep its missing parents go,
    and a few of :data:`_PLANTS`."""
    return {
        "exists": draw(st.booleans()),
        "depth": draw(st.integers(0, 2)),
        "plants": draw(st.lists(st.sampled_from(_PLANTS), max_size=4, unique=True)),
        "names": draw(st.lists(st.sampled_from(["p", "q", "index", "r.s"]), min_size=1, max_size=3, unique=True)),
    }


def _snapshot(root, skip) -> dict:
    """Every path under ``root`` outside ``skip`` with its kind and (files) content."""
    seen = {}
    for dirpath, dirnames, filenames in os.walk(root):
        if os.path.realpath(dirpath).startswith(os.path.realpath(skip)):
            continue
        for name in dirnames + filenames:
            path = os.path.join(dirpath, name)
            if os.path.realpath(path) == os.path.realpath(skip):
                continue
            info = os.lstat(path)
            content = None
            if stat.S_ISREG(info.st_mode):
                with open(path, "rb") as fh:
                    content = fh.read()
            seen[os.path.relpath(path, root)] = (stat.S_IFMT(info.st_mode), content)
    return seen


def _plant(root, state) -> tuple[str, Any]:
    """Make the state under ``root``; the --out to give."""
    from pathlib import Path

    root = Path(root)
    victim = root / "victim.txt"
    victim.write_text("the user's file")
    (root / "elsewhere").mkdir()
    base = root.joinpath(*["m"] * state["depth"]) if state["depth"] else root
    out = base / "out"
    plants = state["plants"]
    if state["exists"] or {"index-link", "old-temp-link", "old-temp-folder", "fifo-report", "foreign-report"} & set(
        plants
    ):
        out.mkdir(parents=True, exist_ok=True)
        if "index-link" in plants:
            (out / "index.html").symlink_to(victim)
        if "old-temp-link" in plants:
            (out / ".index.html.tmp").symlink_to(victim)
        if "old-temp-folder" in plants and "old-temp-link" not in plants:
            (out / ".index.html.tmp").mkdir()
        if "fifo-report" in plants:
            (out / "x").mkdir()
            os.mkfifo(out / "x" / "report.json")
        if "foreign-report" in plants:
            (out / "y").mkdir()
            (out / "y" / "report.json").write_text('{"schema": 2, "name": "z"}')
        if "profile-link" in plants:
            (out / state["names"][0]).symlink_to(root / "elsewhere")
        if "staging-leftover" in plants:
            (out / ".gearcad-staging-abcdefgh").mkdir()
    if "file-at-out" in plants and not out.exists():
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text("a file")
    if "dangling-out" in plants and not os.path.lexists(out):
        out.parent.mkdir(parents=True, exist_ok=True)
        out.symlink_to(root / "nowhere")
    if "loop-out" in plants and not os.path.lexists(out):
        out.parent.mkdir(parents=True, exist_ok=True)
        out.symlink_to(out)
    given = str(out)
    if "out-via-link-dotdot" in plants and out.parent.is_dir():
        (root / "A").mkdir()
        (root / "A" / "link").symlink_to(out.parent / "sub", target_is_directory=True)
        (out.parent / "sub").mkdir(exist_ok=True)
        given = f"{root}/A/link/../out"
    return given, out


@_settings
@given(state=filesystems())
def test_a_build_writes_only_inside_out_whatever_lies_around_it(state):
    """Any planted state: the build publishes its folders and a page, or refuses in one
    GearcadError line; nothing outside --out changes, nothing is followed out of it, and no
    staging or temp file is left."""
    import tempfile
    from pathlib import Path
    from unittest import mock

    from gearcad import batch

    with tempfile.TemporaryDirectory() as root, mock.patch.object(batch, "_build_one", _stub_build):
        given, out = _plant(root, state)
        real = Path(os.path.realpath(given))
        before = _snapshot(root, real)
        try:
            batch.build([_Named(n) for n in state["names"]], given, workers=1)
        except GearcadError as exc:
            assert "\n" not in str(exc), str(exc)
            ok = False
        else:
            ok = True
        after = _snapshot(root, real)
        made = {os.path.relpath(p, root) for p in real.parents if str(p).startswith(root + os.sep)} - set(before)
        assert {k: v for k, v in after.items() if k not in made} == before, "something outside --out changed"
        assert Path(root, "victim.txt").read_text() == "the user's file"
        if ok:
            assert real.is_dir() and (real / "index.html").is_file() and not (real / "index.html").is_symlink()
            for name in state["names"]:
                assert (real / name / "report.json").is_file() and not (real / name).is_symlink()
            left = [n for n in os.listdir(real) if n.startswith(".gearcad-")]
            assert left == [], left
        leftovers = [p for p in Path(root).rglob(".gearcad-staging-*") if p.name != ".gearcad-staging-abcdefgh"]
        assert leftovers == [] or not ok


def _concurrent(job) -> str:
    from gearcad import batch

    names, out = job
    batch._build_one = _stub_build  # the forked child's own module
    try:
        batch.build([_Named(n) for n in names], out, workers=1)
    except BaseException as exc:  # noqa: BLE001 - the test reports whatever a build died of
        return f"{names}: {type(exc).__name__}: {exc}"
    return ""


@_settings
@given(
    builds=st.lists(st.lists(st.sampled_from("abcdef"), min_size=1, max_size=3, unique=True), min_size=2, max_size=4),
    exists=st.booleans(),
    depth=st.integers(0, 2),
)
def test_concurrent_builds_into_one_out_all_publish(builds, exists, depth):
    """Builds side by side into one --out (new, under missing parents, or existing): every one
    succeeds, every folder is there, the page names each, no staging is left."""
    import multiprocessing
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as root:
        out = Path(root).joinpath(*["m"] * depth, "out")
        if exists:
            out.mkdir(parents=True)
        with multiprocessing.get_context("fork").Pool(len(builds)) as pool:
            errors = [e for e in pool.map(_concurrent, [(b, out) for b in builds]) if e]
        assert errors == []
        names = sorted({n for b in builds for n in b})
        assert sorted(os.listdir(out)) == [*names, "index.html"]
        page = (out / "index.html").read_text(encoding="utf-8")
        assert [n for n in names if f"{n}/index.html" not in page] == []
        assert list(Path(root).rglob(".gearcad-*")) == []


# ---------------------------------------------------------------------------------------------
# the other commands: sweep (keys, values, constraints, files), new and coupon (issue 34)
#
# Each case runs the command line in this process, on the cheapest profile (two circles) at the
# pitch stage, one worker: what is under test is what each command accepts and refuses, and
# that it refuses before any design runs.

_CIRCLES = '[gear1]\ncurve = "circle"\nradius = 20.0\n[output]\ntolerance = 0.05\n'
_SWEEP_KEYS = ["gear1.radius", "pair.driver_rpm", "gear2.lobes", "output.tolerance"]
_BAD_KEYS = ["gear1", "..", "gear1..a", "output.formats.0", "", "gear1.nosuch", "nosuch.key", "gear1.radius.x"]
_NUMBERS = st.one_of(
    st.sampled_from(["10", "25", "1e-300", "1e300", "nan", "inf", "-inf", "-3", "0", "abc", "", "1_0", "0x10", "25e"]),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
)
_OPS = ["<", "<=", ">", ">=", "==", "!=", "=", "~", ""]


@st.composite
def _sweep_args(draw: Callable) -> list[str]:
    """A sweep's command line: a --vary or two (a known key or a malformed one; a list, a grid or
    a range of any values), a constraint and an objective (a report key or not; any value)."""
    args = []
    for _ in range(draw(st.integers(1, 2))):
        key = draw(st.sampled_from(_SWEEP_KEYS + _BAD_KEYS))
        form = draw(st.sampled_from(["list", "grid", "range"]))
        values = draw(st.lists(_NUMBERS, min_size=1, max_size=3))
        if form == "grid":
            text = f"{values[0]}:{draw(_NUMBERS)}:{draw(st.sampled_from(['1', '2', '3', '0', '-1', '1e9', 'x']))}"
        elif form == "range":
            text = f"{values[0]}:{draw(_NUMBERS)}"
            args += ["--samples", str(draw(st.integers(0, 3)))]
        else:
            text = ",".join(values)
        args += ["--vary", f"{key}={text}"]
    if draw(st.booleans()):
        key = draw(st.sampled_from(["pair.center_distance", "pair.ratio_max", "nosuch", "gears.0.r_min", ""]))
        value = draw(st.one_of(_NUMBERS, st.sampled_from(["true", "false", '"50"', "[1, 2]", "1979-05-27"])))
        args += ["--constraint", f"{key} {draw(st.sampled_from(_OPS))} {value}".strip()]
    if draw(st.booleans()):
        flag = draw(st.sampled_from(["--minimise", "--maximise"]))
        args += [flag, draw(st.sampled_from(["pair.center_distance", "nosuch", "", "name", "gears.0.r_max"]))]
    return args


@st.composite
def _sweep_files(draw: Callable) -> str:
    """A sweep TOML: its profile, stage, [vary] and the rest, each right or wrong."""
    lines = [
        draw(st.sampled_from(['profile = "c.toml"', "profile = 5", 'profile = ["c.toml"]', 'profile = "nosuch.toml"'])),
        draw(st.sampled_from(['stage = "pitch"', 'stage = "nosuch"', "stage = 1"])),
        draw(st.sampled_from(["", "samples = 2", "samples = true", "samples = -1", "seed = 1.5", "workers = -3"])),
        draw(st.sampled_from(["", 'constraints = ["pair.center_distance > 10"]', "constraints = 5"])),
        draw(st.sampled_from(["", 'minimise = ["pair.center_distance"]', "minimise = [1]"])),
        "[vary]",
        draw(
            st.sampled_from(
                [
                    '"gear1.radius" = [10, 20]',
                    '"gear1.radius" = []',
                    '"gear1.radius" = [10, "x"]',
                    '"gear1.radius" = "10:20:2"',
                    '"gear1..a" = [1]',
                    '"gear1.radius" = [nan, inf]',
                    "x = 1",
                ]
            )
        ),
    ]
    return "\n".join(lines) + "\n"


def _run_cli(args: list[str]) -> tuple[int, list[str]]:
    """``gearcad ARGS`` here: its exit status and its lines on stderr (progress lines dropped)."""
    import contextlib
    import io

    from gearcad.cli import main

    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        code = main(args)
    return code, [line for line in err.getvalue().splitlines() if line and not line.startswith("[")]


def _check_refusal(code: int, lines: list[str], allowed=(0, 2)) -> None:
    assert code in allowed, (code, lines)
    if code == 2:
        assert lines and all(line.startswith("gearcad: error: ") for line in lines), lines
        assert all(len(line) <= _MAX_LINE for line in lines), lines


def _sweep_case(args: list[str], file_text: str | None) -> None:
    import csv
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as root:
        (Path(root) / "c.toml").write_text(_CIRCLES)
        out = Path(root) / "out"
        command = ["sweep", *([] if file_text else [f"{root}/c.toml"]), "--stage", "pitch", "--workers", "1"]
        if file_text:
            (Path(root) / "s.toml").write_text(file_text)
            command = ["sweep", "--file", f"{root}/s.toml", "--workers", "1"]
        with budget(SECONDS, MEMORY):
            code, lines = _run_cli([*command, *args, "--out", str(out)])
        _check_refusal(code, lines)
        assert sorted(os.listdir(root)) == sorted(
            ["c.toml", *(["s.toml"] if file_text else []), *(["out"] * (code == 0))]
        )
        if code == 2:
            assert not out.exists(), "a refused sweep left files"
            return
        for row in csv.reader((out / "sweep.csv").read_text(encoding="utf-8").splitlines()):
            assert not {"nan", "inf", "-inf", "NaN", "Infinity"} & set(row), row
        if any(f"{key}=" in a for a in args for key in _BAD_KEYS if key):
            pytest.fail(f"a malformed key swept with exit 0: {args}")


@_settings
@given(args=_sweep_args())
def test_sweep_arguments_end_in_a_table_or_one_line_each(args):
    """Any --vary, --constraint and objective: a table without NaN or infinity, or lines of
    ``gearcad: error:`` and exit 2 with nothing written; a malformed key never sweeps."""
    _sweep_case(args, None)


@_settings
@given(text=_sweep_files())
def test_sweep_files_end_in_a_table_or_one_line_each(text):
    """Any sweep TOML (its profile, stage, counts, constraints, [vary]): as for the arguments."""
    _sweep_case([], text)


_NEW_NAMES = st.one_of(
    st.sampled_from(["mine", "a", "../x", "a/b", "", ".hidden", "assembly", "x" * 65, "x" * 300, "é", "a\nb", "-"]),
    st.text(min_size=0, max_size=12),
)
_NEW_DIRS = ["fresh/deep", "here", "file", "loop", "dangling", "read-only", "read-only/sub", "long", "proc"]


@_settings
@given(
    name=_NEW_NAMES,
    source=st.sampled_from(
        ["elliptic_focus", "spur_pair", "nosuch", "binary.toml", "latin1.toml", "c.toml", "x" * 300]
    ),
    where=st.sampled_from(_NEW_DIRS),
    planted=st.sampled_from(["", "schema-folder", "schema-link", "schema-read-only", "name-link"]),
)
def test_new_writes_its_two_files_or_nothing(name, source, where, planted):
    """``gearcad new`` with any name, source and --dir: the profile and the schema written inside
    --dir (the profile valid), or lines of ``gearcad: error:``, exit 2 and nothing changed."""
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as root:
        base = Path(root)
        (base / "c.toml").write_text(_CIRCLES)
        (base / "binary.toml").write_bytes(bytes(range(256)))
        (base / "latin1.toml").write_bytes('name = "caf\xe9"\n'.encode("latin-1"))
        (base / "victim.txt").write_text("the user's file")
        folder = {
            "fresh/deep": base / "fresh" / "deep",
            "here": base / "here",
            "file": base / "victim.txt",
            "loop": base / "loop" / "sub",
            "dangling": base / "dangling",
            "read-only": base / "ro",
            "read-only/sub": base / "ro" / "sub",
            "long": base / ("y" * 300),
            "proc": Path("/proc/self"),
        }[where]
        (base / "loop").symlink_to(base / "loop")
        (base / "dangling").symlink_to(base / "nowhere")
        (base / "ro").mkdir(mode=0o555)
        (base / "here").mkdir()
        plant = base / "here"
        if planted == "schema-folder":
            (plant / "profile.schema.json").mkdir()
        elif planted == "schema-link":
            (plant / "profile.schema.json").symlink_to(base / "victim.txt")
        elif planted == "schema-read-only":
            (plant / "profile.schema.json").write_text("{}")
            (plant / "profile.schema.json").chmod(0o444)
        elif planted == "name-link" and name and "/" not in name and "\0" not in name and len(name) < 200:
            with contextlib_suppress():
                (plant / f"{name}.toml").symlink_to(base / "victim.txt")
        source_arg = str(base / source) if source.endswith(".toml") else source
        before = {p: _entry(p) for p in base.rglob("*")}
        try:
            with budget(SECONDS, MEMORY):
                code, lines = _run_cli(["new", name, "--from", source_arg, "--dir", str(folder)])
            after = {p: _entry(p) for p in base.rglob("*")}
        finally:
            (base / "ro").chmod(0o755)
        _check_refusal(code, lines)
        assert (base / "victim.txt").read_text() == "the user's file"
        if code == 2:
            assert after == before
            return
        written = {p for p in after if p not in before or after[p] != before[p]}
        resolved = Path(os.path.realpath(folder))
        assert written <= {resolved / f"{name}.toml", resolved / "profile.schema.json", resolved, *resolved.parents}
        gearcad.load_profile(resolved / f"{name}.toml")


def contextlib_suppress():
    import contextlib

    return contextlib.suppress(OSError)


def _entry(path) -> tuple:
    info = os.lstat(path)
    if stat.S_ISLNK(info.st_mode):
        return ("link", os.readlink(path))
    if stat.S_ISREG(info.st_mode):
        with open(path, "rb") as fh:
            return ("file", fh.read(), info.st_mode)
    return ("folder", info.st_mode)


_COUPON_DEFECTS = {
    "not-a-pair": "[mechanism]\n",  # replaced below by a roller body
    "no-process": "",
    "bad-kerf": '[process]\nkind = "laser"\nkerf = KERF\n',
    "out-a-file": '[process]\nkind = "laser"\n',
    "out-empty": '[process]\nkind = "laser"\n',
    "out-loop": '[process]\nkind = "laser"\n',
    "bad-set": '[process]\nkind = "laser"\n',
}


@_settings
@given(
    defects=st.lists(st.sampled_from(sorted(_COUPON_DEFECTS)), min_size=1, max_size=3, unique=True),
    kerf=st.sampled_from(["nan", "inf", "-0.1", "1e300", '"0.1"', "[0.1]", "true"]),
    setting=st.sampled_from(["teeth.module=-1", "process.variation=nan", "gear1.radius=1e309", "process.kind=5"]),
)
def test_coupon_refuses_before_any_design(defects, kerf, setting):
    """``gearcad coupon`` with a profile that is no gear pair or names no process, a bad
    [process] value or --set, or a bad --out: refused in lines of ``gearcad: error:``, exit 2,
    nothing written — before any design runs (well within a CPU second)."""
    import tempfile
    import time
    from pathlib import Path

    with tempfile.TemporaryDirectory() as root:
        base = Path(root)
        text = '[gear1]\ncurve = "circle"\nradius = 20.0\n[teeth]\nmodule = 1.0\n'
        if "not-a-pair" in defects:
            text = 'mechanism = "roller-body"\n'
        text += next((_COUPON_DEFECTS[d].replace("KERF", kerf) for d in defects if "process" in _COUPON_DEFECTS[d]), "")
        (base / "p.toml").write_text(text)
        (base / "file").write_text("x")
        (base / "loop").symlink_to(base / "loop")
        out = {"out-a-file": base / "file", "out-empty": "", "out-loop": base / "loop"}
        given_out = next((str(out[d]) for d in defects if d in out), str(base / "out"))
        sets = ["--set", setting] if "bad-set" in defects else []
        before = {p: _entry(p) for p in base.rglob("*")}
        start = time.process_time()
        with budget(SECONDS, MEMORY):
            code, lines = _run_cli(["coupon", str(base / "p.toml"), *sets, "--out", given_out])
        spent = time.process_time() - start
        _check_refusal(code, lines, allowed=(2,))
        assert {p: _entry(p) for p in base.rglob("*")} == before
        assert spent < 2.0, f"{spent:.2f} CPU s: a design ran before the refusal"
