"""The sweep's optimiser against its grid (issue 35 items 4 and 5), and a screen the full stage refutes.

The focus pair over gear1.eccentricity 0.1…0.6 and teeth.count 21…61 at the teeth stage,
teeth not undercut, pair.ratio_max (the speed variation) and the driver's tip land both maximised: NSGA-II
(pymoo; 40 designs × 10 generations, seed 0) against a grid of the same budget (20 × 20), each
front's hypervolume from one reference point (the nadir of both fronts plus 10 % of their span).
Then issue 35's quick-return motion pair (ratio 0.5 for 240° of the driver, 2 for the rest, the
steps smoothed by a raised cosine 70° wide, E = 150 mm, module 1): what the teeth stage says,
and what ``--confirm full`` finds.
"""

from __future__ import annotations

import time

import numpy as np

__all__ = ["bench_optimise", "optimise_summary", "quick_return", "SEEDS"]

SEEDS = (0, 1, 2)
"""The search's seeds (one with ``--quick``): a search is one draw, so three are shown."""

FOCUS_RANGES = ["gear1.eccentricity=0.1:0.6", "teeth.count=21:61"]
FOCUS_GOALS = dict(
    constraints=["gears.0.teeth.undercut == false"],
    maximise=["pair.ratio_max", "gears.0.teeth.min_tip_thickness"],
)
"""A trade-off: a larger speed variation (eccentricity) sharpens the ends, thinning the tips."""


def quick_return(samples: int = 72, width: float = 70.0, center_distance: float = 150.0) -> dict:
    """Issue 35's quick-return law as a profile's data: ω₂/ω₁ = 0.5 for 240° of the driver and 2
    for the other 120° (the mean 1: the pair closes), each step a raised cosine ``width``° wide."""
    t = np.arange(samples) * 360.0 / samples

    def rise(u):
        return 0.5 - 0.5 * np.cos(np.pi * np.clip(u / width, 0.0, 1.0))

    ratio = 0.5 + 1.5 * (rise(t - 240 + width / 2) - rise(t - 360 + width / 2)) + 1.5 * (1 - rise(t + width / 2))
    ratio = ratio / ratio.mean()
    return {
        "name": "quick_return",
        "gear1": {"curve": "motion", "ratio": [round(float(v), 6) for v in ratio]},
        "pair": {"center_distance": center_distance},
        "teeth": {"module": 1.0},
    }


def _focus_data() -> dict:
    from ..sweeps.space import read_toml
    from .commands import PROFILES

    return read_toml(PROFILES / "elliptic_focus.toml", "profile")


def _spans():
    from ..sweeps.space import parse_vary

    return [parse_vary(v) for v in FOCUS_RANGES]


def _confirm_row() -> dict:
    """Row of study ``confirm``: the quick-return pair screened at the teeth stage, then proven
    at the full stage (minutes)."""
    from ..fitting import design
    from ..profiles.reading import parse_profile

    profile = parse_profile(quick_return(), default_name="quick_return")
    start = time.process_time()
    teeth = design(profile, "teeth")
    screened = time.process_time() - start
    start = time.process_time()
    full = design(profile, "full")
    proven = time.process_time() - start
    blind = [b["code"] for b in teeth.report().get("stage_blind", [])]
    return {
        "study": "confirm",
        "method": "quick-return motion pair (0.5 for 240°, 2 for 120°, E = 150 mm)",
        "n": 1,
        "seconds": screened + proven,
        "error": float(teeth.report()["motion"]["error_deg"]),
        "teeth_ok": teeth.ok,
        "stage_blind": " ".join(blind),
        "full_ok": full.ok,
        "failures": " ".join(f.code for f in full.failures()),
        "teeth_seconds": screened,
        "full_seconds": proven,
    }


def bench_optimise(quick: bool = False) -> list[dict]:
    """Rows of study ``optimise``: the search and the grid (evaluations, front points,
    hypervolume, CPU seconds); and ``confirm``: the quick-return pair screened and proven."""
    from ..sweeps import sweep
    from ..sweeps.optimise import grid_overrides
    from .commands import PROFILES

    try:
        import pymoo  # noqa: F401
    except ImportError:
        return []
    population, generations = (20, 5) if quick else (40, 10)
    rows = []
    for seed in (0,) if quick else SEEDS:
        start = time.process_time()
        table = sweep(PROFILES / "elliptic_focus.toml", FOCUS_RANGES, stage="teeth", method="nsga2",
                      population=population, generations=generations, seed=seed, against_grid=True, workers=1,
                      **FOCUS_GOALS)  # fmt: skip
        both = time.process_time() - start
        attrs = table.attrs
        start = time.process_time()  # the grid alone, timed again: the search's share is the rest
        grid_axes = zip(*[list(o.items()) for o in grid_overrides(_focus_data(), _spans(), attrs["grid_evaluations"])])
        lists = [f"{axis[0][0]}={','.join(str(v) for v in dict.fromkeys(v for _, v in axis))}" for axis in grid_axes]
        sweep(PROFILES / "elliptic_focus.toml", lists, stage="teeth", workers=1, **FOCUS_GOALS)
        gridded = time.process_time() - start
        seconds = max(both - gridded, 1e-6)
        common = {"study": "optimise", "seed": seed, "error": 0.0, "reference": attrs["reference_point"]}
        rows += [
            {
                **common,
                "method": "NSGA-II (pymoo), focus pair, teeth stage",
                "n": len(table),
                "seconds": seconds,
                "front_rows": attrs["front_sizes"][-1],
                "hypervolume": attrs["hypervolumes"][-1],
            },
            {
                **common,
                "method": "grid of the same budget",
                "n": attrs["grid_evaluations"],
                "seconds": gridded,
                "front_rows": len({tuple(p) for p in attrs["grid_front"]}),
                "hypervolume": attrs["grid_hypervolume"],
            },
        ]
    if not quick:
        rows.append(_confirm_row())
    return rows


def optimise_summary(rows: list[dict]) -> list[str]:
    """Lines for the bench's summary."""
    out = []
    found = [r for r in rows if r["study"] == "optimise"]
    for search, grid in zip(found[::2], found[1::2]):
        ref = ", ".join(f"{v:.4g}" for v in search["reference"])
        out.append(
            f"optimiser (seed {search['seed']}): NSGA-II {search['n']} designs, {search['front_rows']} front points, "
            f"hypervolume {search['hypervolume']:.4g}; grid {grid['n']} designs, {grid['front_rows']} front points, "
            f"{grid['hypervolume']:.4g} (reference {ref}; CPU-s {search['seconds']:.2f} and {grid['seconds']:.2f})"
        )
    for r in rows:
        if r["study"] == "confirm":
            out.append(
                f"confirm: {r['method']}: teeth stage ok={r['teeth_ok']} (motion error {r['error']:.2g}°, blind to "
                f"{r['stage_blind'] or 'nothing'}), full stage ok={r['full_ok']} ({r['failures'] or 'no failure'}); "
                f"{r['teeth_seconds']:.2f} + {r['full_seconds']:.2f} CPU-s"
            )
    return out
