"""``gearcad sweep`` on the command line: its arguments, what it runs and what it prints (kept
here so gearcad/cli.py only registers it)."""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Callable
from pathlib import Path

from ..errors import ProfileError
from ..stages import STAGES

__all__ = ["add_parser", "run", "EXIT_NONE_FEASIBLE"]

EXIT_NONE_FEASIBLE = 3
"""The exit status of a sweep in which no design is feasible, or (``--confirm full``) no front row
passes the full stage (as ``build``'s failed check: the files are written all the same)."""


def add_parser(sub) -> None:
    s = sub.add_parser(
        "sweep",
        help="design a profile over varied keys at a stage: table (Parquet, CSV), Pareto front, HTML page",
        description="Vary profile keys (grids, lists, random or Latin-hypercube samples), design every point "
        "at a stage, and write sweep.parquet, sweep.csv, front.csv and sweep.html into --out.",
    )
    s.add_argument("profile", nargs="?", type=Path, help="the profile (or give it in --file)")
    s.add_argument("--file", type=Path, help="a sweep TOML: profile, stage, [vary], samples, constraints, objectives")
    s.add_argument(
        "--vary",
        action="append",
        default=[],
        metavar="KEY=a:b:n|a:b|v1,v2",
        help="vary a profile key: n values from a to b, a range to sample, or a list (repeatable)",
    )
    s.add_argument("--stage", choices=STAGES, help="how far each design goes (default: teeth)")
    s.add_argument("--samples", type=int, help="draws for the a:b ranges")
    s.add_argument("--sampling", choices=["lhs", "random"], help="how ranges are drawn (default: lhs)")
    s.add_argument("--seed", type=int, help="the draws' seed (default: 0)")
    s.add_argument(
        "--constraint",
        action="append",
        default=[],
        metavar="KEY OP VALUE",
        help="e.g. 'gears.0.teeth.undercut == false' (repeatable)",
    )
    s.add_argument("--minimise", action="append", default=[], metavar="KEY", help="an objective (a report key)")
    s.add_argument("--maximise", action="append", default=[], metavar="KEY", help="an objective (a report key)")
    s.add_argument(
        "--method",
        choices=["grid", "nsga2"],
        help="grid: the varies' points (default); nsga2: search the KEY=a:b ranges (pymoo: gearcad[optimise])",
    )
    s.add_argument("--population", type=int, help="--method nsga2: designs a generation (default: 40)")
    s.add_argument("--generations", type=int, help="--method nsga2: generations (default: 10)")
    s.add_argument("--evaluations", type=int, help="--method nsga2: the budget in designs, instead of --generations")
    s.add_argument("--against-grid", action="store_true", help="--method nsga2: also a grid of the same budget")
    s.add_argument(
        "--confirm", choices=["full"], help="re-design the front at the full stage; keep on it only what passes"
    )
    s.add_argument("--workers", type=int, help="local processes (default: every core)")
    s.add_argument("--scheduler", metavar="ADDRESS", help="run on this Dask scheduler, e.g. tcp://10.0.0.5:8786")
    s.add_argument(
        "--scheduler-timeout",
        type=float,
        metavar="SECONDS",
        help="give up when the scheduler cannot be reached, or has had no worker, for this long (default: 60)",
    )
    s.add_argument("--out", default="out/sweep", help="output folder (default: out/sweep)")  # a str: '' is refused


def run(args: argparse.Namespace) -> int:
    """The sweep, with Ctrl-C and SIGTERM one line naming ``--out`` (exit 130 / 143): the work
    not done is cancelled, the local workers ended at once, and nothing is written."""
    from ..interrupts import interrupt_guard

    with interrupt_guard(args.out):
        return _run(args)


def _run(args: argparse.Namespace) -> int:
    from . import sweep, write_sweep
    from .space import SweepSpec, parse_vary, read_sweep_file

    spec = read_sweep_file(args.file) if args.file else SweepSpec()
    profile = args.profile or spec.profile
    if profile is None:
        raise ProfileError('gearcad sweep: give a profile (or profile = "…" in --file)')
    for flag, value, least in (
        ("--workers", args.workers, 1),
        ("--samples", args.samples, 0),
        ("--seed", args.seed, 0),
    ):
        if value is not None and value < least:
            raise ProfileError(f"{flag} {value}: must be a whole number ≥ {least}")
    wait = args.scheduler_timeout
    if wait is not None and not 0 < wait <= 86400:  # NaN fails too
        raise ProfileError(f"--scheduler-timeout {wait:g}: must be seconds > 0 and ≤ 86400")
    from ..publish import check_out

    check_out(args.out)  # before any work: a bad --out is found in a moment
    vary = [*spec.vary, *(parse_vary(v) for v in args.vary)]
    from .executors import SCHEDULER_TIMEOUT, scheduler_address

    if args.scheduler is not None:
        scheduler_address(args.scheduler)  # before any work, as every other value
    start = time.perf_counter()
    table = sweep(
        profile,
        vary,
        stage=args.stage or spec.stage,
        samples=args.samples if args.samples is not None else spec.samples,
        sampling=args.sampling or spec.sampling,
        seed=args.seed if args.seed is not None else spec.seed,
        constraints=[*spec.constraints, *args.constraint],
        minimise=[*spec.minimise, *args.minimise],
        maximise=[*spec.maximise, *args.maximise],
        workers=args.workers,
        client=args.scheduler,  # an address: sweep connects once everything is checked, and closes
        scheduler_timeout=SCHEDULER_TIMEOUT if args.scheduler_timeout is None else args.scheduler_timeout,
        progress=stderr_progress(),
        **_search_arguments(args),
    )
    files = write_sweep(table, args.out)
    made, feasible = int(table["refusal"].isna().sum()), int(table["feasible"].sum())
    print(
        f"swept {len(table)} designs ({made} made, {len(table) - made} refused, {feasible} feasible, "
        f"{int(table['pareto'].sum())} on the front) in {time.perf_counter() - start:.2f} s: "
        f"{', '.join(str(p) for p in files.values())}"
    )
    for line in _search_lines(table):
        print(line)
    if feasible and "confirmed" in table and not table["pareto"].any():
        print("gearcad: no front row passed the full stage (confirm_refusal says why each failed)", file=sys.stderr)
        return EXIT_NONE_FEASIBLE
    if feasible:
        return 0
    why = "meets every constraint (the violation.* columns say by how much each missed)" if made else "was made"
    print(f"gearcad: no feasible design: none of the {len(table)} {why}", file=sys.stderr)
    return EXIT_NONE_FEASIBLE


def _search_arguments(args: argparse.Namespace) -> dict:
    """--method, its budget, --against-grid and --confirm, as sweep's keywords (only those given)."""
    given = {
        "method": args.method,
        "population": args.population,
        "generations": args.generations,
        "evaluations": args.evaluations,
        "against_grid": args.against_grid or None,
        "confirm": args.confirm,
    }
    return {k: v for k, v in given.items() if v is not None}


def _search_lines(table) -> list[str]:
    """What a search and a confirmation add to stdout: the hypervolumes, the survivors."""
    attrs, lines = table.attrs, []
    if "hypervolumes" in attrs:
        grid = (
            f"; a grid of {attrs['grid_evaluations']}: {attrs['grid_hypervolume']:.6g}"
            if "grid_hypervolume" in attrs
            else ""
        )
        lines.append(
            f"hypervolume after {len(attrs['hypervolumes'])} generations: {attrs['hypervolumes'][-1]:.6g}{grid}"
        )
    if "confirmed" in table:
        tried = table["confirmed"].notna()
        held = int(table["confirmed"].fillna(False).sum())
        lines.append(f"confirmed at the full stage: {held} of {int(tried.sum())} front rows re-designed")
    return lines


def stderr_progress(every: float = 1.0) -> Callable[[int, int], None]:
    """A progress line on stderr at most every ``every`` seconds, and at the end."""
    start, last = time.perf_counter(), [0.0]

    def show(done: int, total: int) -> None:
        now = time.perf_counter() - start
        if done == total or now - last[0] >= every:
            last[0] = now
            bar = "#" * (30 * done // total)
            rate = done / now if now > 0 else math.inf
            end = "\n" if done == total else "\r"
            print(
                f"\rsweep [{bar:<30}] {done}/{total} designs, {now:.1f} s, {rate:.0f}/s",
                end=end,
                file=sys.stderr,
                flush=True,
            )

    return show
