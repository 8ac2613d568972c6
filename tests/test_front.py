"""The sweep's Pareto front: against a brute-force O(n²) oracle on random data (ties, NaN,
infeasible rows, one to four objectives), rounding noise making no front point, and the front
merged chunk by chunk in any order equal to the whole table's."""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gearcad.sweeps.front import BITS, FLOOR, RunningFront, pareto, snap

FAST = settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def oracle(values: np.ndarray, mask: np.ndarray) -> list[int]:
    """Every pair compared: row j is on the front when it is feasible, finite, and no other such
    row is as good in every objective and strictly better in one."""
    rows = np.flatnonzero(mask & np.all(np.isfinite(values), axis=1))
    v = values[rows]
    beats = np.all(v[:, None] <= v[None, :], axis=2) & np.any(v[:, None] < v[None, :], axis=2)  # [i, j]
    return rows[~beats.any(axis=0)].tolist()


@st.composite
def tables(draw, objectives=(1, 4), rows=60):
    """(exact values, the values as computed: each off by rounding noise, mask).  The exact
    values are multiples of 1/8 (a few of them, so that ties are common) or NaN/inf; the noise
    is at most 1e-13 relative (or 1e-14 about zero) — what floating point leaves, far below
    the front's tolerance."""
    m, n = draw(st.integers(*objectives)), draw(st.integers(0, rows))
    levels = draw(st.lists(st.integers(-40, 40), min_size=1, max_size=6, unique=True))
    picks = draw(st.lists(st.sampled_from(levels), min_size=n * m, max_size=n * m))
    exact = np.array(picks, dtype=float).reshape(n, m) / 8
    if n:
        for cell in draw(st.lists(st.integers(0, n * m - 1), max_size=3)):  # a few refused or unreported
            exact.flat[cell] = draw(st.sampled_from([np.nan, np.inf, -np.inf]))
    noise = np.array(draw(st.lists(st.floats(-1e-13, 1e-13), min_size=n * m, max_size=n * m))).reshape(n, m)
    computed = exact * (1 + noise) + noise / 10
    mask = np.array(draw(st.lists(st.booleans(), min_size=n, max_size=n)), dtype=bool)
    return exact, computed, mask


@FAST
@given(tables())
def test_front_is_the_brute_force_front_of_the_exact_values(table):
    exact, computed, mask = table
    assert np.flatnonzero(pareto(computed, mask)).tolist() == oracle(exact, mask)


@FAST
@given(tables(objectives=(2, 3)), st.randoms(use_true_random=False))
def test_front_merged_chunk_by_chunk_in_any_order(table, random):
    """The running front after every chunk is in, whatever their order and sizes, is the
    table's front (what the rows would be on one worker, two, or a cluster)."""
    exact, computed, mask = table
    order = list(range(len(computed)))
    random.shuffle(order)
    cuts = sorted(random.sample(range(1, len(order)), min(4, max(0, len(order) - 1)))) if order else []
    front = RunningFront(computed.shape[1])
    for chunk in np.split(np.array(order, dtype=int), cuts):
        front.add(chunk, computed[chunk], mask[chunk])
    assert front.rows().tolist() == oracle(exact, mask)


def test_rounding_ties_make_no_front_point():
    """Issue 35: a row whose ratio_max is 9.000000000000009 was on the front only because
    another had …007, with a thicker tip in the other.  Minimise the ratio, maximise the tip
    (negated): the thicker tip wins at an equal ratio."""
    values = np.array([[9.000000000000007, -1.5], [9.000000000000009, -1.6], [9.5, -1.7]])
    mask = np.ones(3, dtype=bool)
    assert values[0, 0] != values[1, 0]  # the noise is there
    assert pareto(values, mask).tolist() == [False, True, True]
    # noise about zero (a closure error of 1e-17 against 3e-17) ties as well
    assert pareto(np.array([[1e-17, 2.0], [3e-17, 1.0]]), np.ones(2, dtype=bool)).tolist() == [False, True]
    # a real difference (4e-9, relative) is kept: both rows are on the front
    real = np.array([[9.0, -1.5], [9.0 * (1 + 4e-9), -1.6]])
    assert pareto(real, np.ones(2, dtype=bool)).tolist() == [True, True]


def test_exact_ties_are_all_on_the_front_and_infeasible_rows_on_none():
    values = np.array([[1, 5], [2, 2], [3, 3], [5, 1], [1, 5], [0, 9], [np.nan, 0], [0, np.inf]], float)
    mask = np.array([True, True, True, True, True, False, True, True])
    assert np.flatnonzero(pareto(values, mask)).tolist() == [0, 1, 3, 4]
    assert not pareto(values, np.zeros(8, dtype=bool)).any() and pareto(values[:0], mask[:0]).tolist() == []


@FAST
@given(st.lists(st.floats(-1e300, 1e300), min_size=2, max_size=40))
def test_snap_is_monotone_close_and_idempotent(xs):
    x = np.sort(np.array(xs))
    s = snap(x)
    assert np.all(np.diff(s) >= 0)  # a <= b gives snap(a) <= snap(b)
    assert np.all(np.abs(s - x) <= np.maximum(np.abs(x) * 2.0**-BITS, 2.0**FLOOR))
    assert np.array_equal(snap(s), s)


def test_three_and_four_objectives_at_scale_against_the_oracle():
    """Kung's merges (a sorted 2-D query for three objectives, a block comparison for four)
    on 600 rows: random, and all on one plane (every row on the front)."""
    rng = np.random.default_rng(7)
    for m in (3, 4):
        values = rng.integers(0, 9, size=(600, m)).astype(float)
        mask = rng.random(600) < 0.9
        assert np.flatnonzero(pareto(values, mask)).tolist() == oracle(values, mask)
    plane = rng.random((600, 3))
    plane[:, 2] = 2 - plane[:, 0] - plane[:, 1]
    plane = np.round(plane, 3)  # multiples of 1e-3: distinct values far apart, the plane kept to rounding
    assert np.flatnonzero(pareto(plane, np.ones(600, dtype=bool))).tolist() == oracle(plane, np.ones(600, bool))


def test_values_of_the_wrong_shape_are_refused():
    with pytest.raises(ValueError, match="rows, objectives"):
        pareto(np.zeros(3), np.ones(3, dtype=bool))
