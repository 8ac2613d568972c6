"""Command line: ``gearcad build``, ``check``, ``schema``, ``bench`` and ``sweep``.

Parses arguments and calls the API; prints what it returns.  Exit status 2 for anything the
user can mend (a bad value, a design that cannot be made), with one line per problem.
"""

from __future__ import annotations

import argparse
import json
import logging
import math
import os
import sys
import time
from pathlib import Path

from .errors import GearcadError

__all__ = ["main"]

EXIT_BAD_INPUT = 2


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="gearcad", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    overrides = argparse.ArgumentParser(add_help=False)
    overrides.add_argument(
        "--set",
        dest="overrides",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="override a profile value by dotted key, e.g. --set gear1.a=30 (VALUE is read as TOML)",
    )
    overrides.add_argument(
        "--unset", dest="unset", action="append", default=[], metavar="KEY", help="remove a key from the profile"
    )
    b = sub.add_parser("build", parents=[overrides], help="build profiles into DXF, SVG, STL, 3MF, charts and reports")
    b.add_argument("profiles", nargs="*", type=Path, help="profile files (default: every profiles/*.toml)")
    b.add_argument("--out", type=Path, default=Path("out"), help="output folder (default: out)")
    c = sub.add_parser("check", parents=[overrides], help="run every check of a build without writing anything")
    c.add_argument("profiles", nargs="+", type=Path)
    c.add_argument("--stage", choices=["pitch", "teeth", "full"], default="full", help="stop early (gear pairs)")
    s = sub.add_parser("schema", help="print the JSON Schema of profiles (for TOML editors)")
    s.add_argument("--out", type=Path, help="write it to this file instead")
    bench = sub.add_parser("bench", help="measure speed against accuracy; charts, CSV and markdown")
    bench.add_argument("--out", type=Path, default=Path("out/bench"), help="output folder (default: out/bench)")
    bench.add_argument("--quick", action="store_true", help="fewer points: a smoke run")
    bench.add_argument(
        "--skip",
        action="append",
        default=[],
        choices=["peers", "goals", "stages"],
        help="leave out a section that runs whole processes (repeatable)",
    )
    from .sweeps.command import add_parser as add_sweep

    add_sweep(sub)
    return parser


def _profile_paths(paths: list[Path]) -> list[Path]:
    if paths:
        return paths
    found = sorted(Path("profiles").glob("*.toml"))
    if not found:
        raise GearcadError("no profiles given and none found in ./profiles")
    return found


def _load_all(args) -> list:
    from .profiles import load_profile

    profiles, errors = [], []
    for path in _profile_paths(args.profiles):
        try:
            profiles.append(load_profile(path, args.overrides, unset=args.unset))
        except GearcadError as exc:
            errors.append(str(exc))
    if errors:
        raise GearcadError("\n".join(errors))
    return profiles


def _progress(n: int, total: int, result) -> None:
    print(f"[{n}/{total}] {result.name}: {result.summary} ({1000 * result.seconds:.0f} ms)", flush=True)


def _check(args) -> None:
    from .batch import design_all

    for d in design_all(_load_all(args), args.stage):
        print(f"{d.name}: {d.summary}")
        for line in d.details:
            print(f"  {line}")
        for f in d.findings:
            print(f"  warning [{f.code}] {f.message}")


def _run(args) -> int:
    if args.command == "schema":
        from .profiles import profile_schema

        text = json.dumps(profile_schema(), indent=2, ensure_ascii=False) + "\n"
        if args.out:
            args.out.write_text(text, encoding="utf-8")
        else:
            sys.stdout.write(text)
        return 0
    if args.command == "bench":
        from .bench import run_bench

        rows = run_bench(args.out, quick=args.quick, skip=args.skip, echo=print)
        print(f"{len(rows)} measurements written to {args.out}/ (results.md, results.csv, *.png)")
        return 0
    if args.command == "sweep":
        from .sweeps.command import run

        return run(args)
    if args.command == "check":
        _check(args)
        return 0
    from .batch import build

    start = time.perf_counter()
    results = build(_load_all(args), args.out, _progress)
    wall, work = time.perf_counter() - start, math.fsum(r.seconds for r in results)
    side = f" ({work:.2f} s of building side by side)" if len(results) > 1 else ""
    print(f"built {len(results)} profile(s) into {args.out}/ in {wall:.2f} s{side}")
    return 0


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    logging.basicConfig(level=logging.ERROR, format="%(levelname)s: %(message)s")
    try:
        if args.command == "build":
            from .publish import check_out

            check_out(args.out)  # before any work: a bad --out is found in a moment
        return _run(args)
    except GearcadError as exc:
        code = getattr(exc, "exit_code", EXIT_BAD_INPUT)
        prefix = "gearcad: " if code != EXIT_BAD_INPUT else "gearcad: error: "
        for line in str(exc).splitlines():
            print(f"{prefix}{line}", file=sys.stderr)
        return code
    except KeyboardInterrupt:  # Ctrl-C outside a build (a build turns it into Interrupted)
        print("gearcad: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # e.g. `gearcad check … | head -1`: the reader has gone
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0


if __name__ == "__main__":
    sys.exit(main())
