"""Command line: ``gearcad build`` and ``gearcad check``."""

from __future__ import annotations

import argparse
import logging
import math
import sys
from pathlib import Path

from .build import build_all, build_any, pair_summary
from .design import design
from .errors import GearcadError
from .profiles import GearPairParams, load_profile
from .teeth.pair import cut_pair

__all__ = ["main"]

EXIT_BAD_INPUT = 2


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="gearcad", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    b = sub.add_parser("build", help="build profiles into DXF, charts and report.json")
    b.add_argument("profiles", nargs="*", type=Path, help="profile files (default: every profiles/*.toml)")
    b.add_argument("--out", type=Path, default=Path("out"), help="output folder (default: out)")
    b.add_argument(
        "--set",
        dest="overrides",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="override a profile value by dotted key, e.g. --set gear1.a=30",
    )
    bench = sub.add_parser("bench", help="measure speed against accuracy; charts, CSV and markdown")
    bench.add_argument("--out", type=Path, default=Path("out/bench"), help="output folder (default: out/bench)")
    bench.add_argument("--quick", action="store_true", help="fewer points: a smoke run")
    c = sub.add_parser("check", help="print the checks of profiles without writing anything")
    c.add_argument("profiles", nargs="+", type=Path)
    c.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE")
    return parser


def _profile_paths(paths: list[Path]) -> list[Path]:
    if paths:
        return paths
    found = sorted(Path("profiles").glob("*.toml"))
    if not found:
        raise GearcadError("no profiles given and none found in ./profiles")
    return found


def _progress(n: int, total: int, result) -> None:
    print(f"[{n}/{total}] {result.name}: {result.summary} ({1000 * result.seconds:.0f} ms)", flush=True)


def _check(params) -> None:
    if not isinstance(params, GearPairParams):
        result = build_any(params, None)
        print(f"{params.name}: {result.summary}")
        for f in result.findings:
            print(f"  warning [{f.code}] {f.message}")
        return
    data = design(params)
    teeth = cut_pair(data, params.teeth) if params.teeth is not None else None
    print(f"{params.name}: {pair_summary(data, teeth)}")
    for g in data.gears:
        print(
            f"  {g.name}: r {g.r_min:.4f}…{g.r_max:.4f} mm, perimeter {g.perimeter:.6f} mm, "
            f"{'convex' if g.shape.convex else 'not convex'}, "
            f"min radius of curvature {g.shape.min_curvature_radius:.4g} mm"
        )
    lo, hi = data.ratio_range
    print(f"  ratio ω2/ω1 {lo:.6g}…{hi:.6g}")
    if data.walker is not None:
        w = data.walker
        print(
            f"  walker: i (paper's method) = {w.i_paper:.6f}, i (rolls and closes) = {w.i:.6f}"
            + (f", i (blended) = {w.i_blended:.6f}" if w.blend_width else "")
        )
    if teeth is not None:
        for g, t in zip(data.gears, teeth.gears):
            print(
                f"  {g.name}: {t.teeth} teeth, thinnest tip land {t.tip_thickness.min():.3f} mm, "
                f"{'undercut' if t.undercut else 'no undercut'}, {t.outline.vertex_count} vertices"
            )
        lo, hi = teeth.backlash_range
        print(
            f"  mesh: max overlap {teeth.mesh.max_overlap:.3g} mm² (allowed {teeth.mesh.allowed_overlap:.3g}), "
            f"backlash {lo:.4f}…{hi:.4f} mm"
        )
    for f in data.findings + (teeth.findings if teeth else ()):
        print(f"  warning [{f.code}] {f.message}")


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    logging.basicConfig(level=logging.ERROR, format="%(levelname)s: %(message)s")
    if args.command == "bench":
        from .bench import run_bench

        rows = run_bench(args.out, quick=args.quick)
        print(f"{len(rows)} measurements written to {args.out}/ (results.md, results.csv, *.png)")
        return 0
    try:
        paths = _profile_paths(args.profiles)
        profiles, errors = [], []
        for path in paths:
            try:
                profiles.append(load_profile(path, args.overrides))
            except GearcadError as exc:
                errors.append(str(exc))
        if errors:
            for e in errors:
                print(f"gearcad: error: {e}".replace("\n", "\ngearcad: error: "), file=sys.stderr)
            return EXIT_BAD_INPUT
        if args.command == "check":
            for params in profiles:
                try:
                    _check(params)
                except GearcadError as exc:
                    raise type(exc)(f"{params.name}: {exc}") from None
            return 0
        results = build_all(profiles, args.out, _progress)
        total = math.fsum(r.seconds for r in results)
        print(f"built {len(results)} profile(s) into {args.out}/ in {total:.2f} s")
        return 0
    except GearcadError as exc:
        print(f"gearcad: error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT


if __name__ == "__main__":
    sys.exit(main())
