"""Command line: ``gearcad build``, ``check``, ``new``, ``compare``, ``coupon``, ``sweep``, ``schema``, ``bench``.

Parses arguments and calls the API; prints what it returns.  Exit status 2 for anything the
user can mend (a bad value, a design that cannot be made), with one line per problem; 3 when
``check`` or ``build`` made the design but a check failed (the assembly interferes, a mesh jams
under the process's tolerances): the files of a build are written all the same.  ``--allow CODE``
accepts a named finding deliberately.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import logging
import math
import os
import sys
import time
import warnings
from pathlib import Path
from typing import NoReturn

from .errors import GearcadError, OutputError
from .interrupts import Interrupted, interrupt_guard
from .stages import STAGES

__all__ = ["main"]

EXIT_BAD_INPUT = 2
EXIT_CHECKS_FAILED = 3


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
    overrides.add_argument(
        "--allow",
        action="append",
        default=[],
        metavar="CODE",
        help="accept a failing finding by its code (e.g. --allow jams); repeatable",
    )
    b = sub.add_parser("build", parents=[overrides], help="build profiles into DXF, SVG, STL, 3MF, charts and reports")
    b.add_argument("profiles", nargs="*", type=Path, help="profile files (default: every profiles/*.toml)")
    b.add_argument("--out", default="out", help="output folder (default: out)")  # a str: '' is refused, not '.'
    c = sub.add_parser("check", parents=[overrides], help="run every check of a build without writing anything")
    c.add_argument("profiles", nargs="+", type=Path)
    c.add_argument("--stage", choices=STAGES, default="full", help="stop early (gear pairs)")
    n = sub.add_parser("new", help="start a profile of your own from an example, with the schema beside it")
    n.add_argument("name", help="the new profile's name (NAME.toml, out/NAME)")
    n.add_argument("--from", dest="source", default="elliptic_focus", help="an example's name or a profile's path")
    n.add_argument("--dir", type=Path, default=Path("."), help="where to write (default: here)")
    cmp = sub.add_parser("compare", parents=[overrides], help="two designs side by side (--set, --unset: the 2nd)")
    cmp.add_argument("profiles", nargs=2, type=Path, metavar="PROFILE")
    cp = sub.add_parser("coupon", parents=[overrides], help="a gear pair's test piece: its teeth at five kerf steps")
    cp.add_argument("profile", type=Path, metavar="PROFILE")
    cp.add_argument("--out", default="out", help="output folder (default: out); writes OUT/NAME-coupon/")
    s = sub.add_parser("schema", help="print the JSON Schema of profiles (for TOML editors)")
    s.add_argument("--out", help="write it to this file instead")  # a str: '' is refused, not '.'
    bench = sub.add_parser("bench", help="measure speed against accuracy; charts, CSV and markdown")
    bench.add_argument("--out", default="out/bench", help="output folder (default: out/bench)")  # '' is refused
    bench.add_argument("--quick", action="store_true", help="fewer points: a smoke run")
    bench.add_argument(
        "--skip",
        action="append",
        default=[],
        choices=["peers", "goals", "stages"],
        help="leave out a section that runs whole processes (repeatable)",
    )
    from .sweeps.cli import add_parser as add_sweep

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
    from .api import load_profile

    profiles, errors = [], []
    for path in _profile_paths(args.profiles):
        try:
            profiles.append(load_profile(path, args.overrides, unset=args.unset))
        except Interrupted:  # the command's, not this profile's: its own line and exit status
            raise
        except GearcadError as exc:
            errors.append(str(exc))
    if errors:
        raise GearcadError("\n".join(errors))
    return profiles


def _progress(out: Path):
    """The line per built profile; it says when the build will replace an earlier one."""
    earlier = {p.name for p in out.iterdir() if p.is_dir()} if out.is_dir() else set()

    def line(n: int, total: int, result) -> None:
        replaces = f", replaces {out / result.name}" if result.name in earlier else ""
        print(f"[{n}/{total}] {result.name}: {result.summary} ({1000 * result.seconds:.0f} ms{replaces})", flush=True)
        for f in result.findings:  # each warning in one line, as check prints them
            print(f"  warning [{f.code}] {f.message}", flush=True)

    return line


def _check(args) -> int:
    from .api import design_all
    from .findings import check_codes

    allow = check_codes(args.allow)
    failed = []
    for d in design_all(_load_all(args), args.stage):
        print(f"{d.name}: {d.summary}")
        for line in d.details:
            print(f"  {line}")
        for f in d.findings:
            print(f"  warning [{f.code}] {f.message}")
        failed += [(d.name, f) for f in d.failures(allow)]
    return _failed(failed)


def _coupon(args) -> int:
    from .api import coupon, load_profile

    folder = coupon(load_profile(args.profile, args.overrides, unset=args.unset), args.out)
    print(f"wrote {folder}/ (coupon.dxf, coupon.svg, coupon.3mf, coupon.txt)")
    text = (folder / "coupon.txt").read_text(encoding="utf-8").strip()
    print(text[text.index("Play per step") :])  # each step's play and the key to set
    return 0


def _failed(failed: list) -> int:
    """Exit status 3 with one line per failing finding on stderr, else 0."""
    for name, f in failed:
        print(f"gearcad: check failed: {name}: [{f.code}] {f.message} (--allow {f.code} accepts it)", file=sys.stderr)
    return EXIT_CHECKS_FAILED if failed else 0


def _run(args) -> int:
    if args.command == "schema":
        from .api import profile_schema

        text = json.dumps(profile_schema(), indent=2, ensure_ascii=False) + "\n"
        if args.out is not None:
            if not args.out.strip():
                raise GearcadError("--out '': empty; give a file name (is a shell variable unset?)")
            try:
                Path(args.out).write_text(text, encoding="utf-8")
            except OSError as exc:  # a folder, a missing folder, a read-only place
                raise OutputError(f"--out {args.out}: cannot write the schema there ({exc.strerror or exc})") from None
        else:
            sys.stdout.write(text)
        return 0
    if args.command == "new":
        from .starter import new_profile

        print("wrote " + " and ".join(map(str, new_profile(args.name, args.source, args.dir))))
        return 0
    if args.command == "compare":
        from .compare import compare_lines

        print("\n".join(compare_lines(*args.profiles, args.overrides, args.unset)))
        return 0
    if args.command == "bench":
        from .bench import run_bench

        rows = run_bench(Path(args.out), quick=args.quick, skip=args.skip, echo=print)
        print(f"{len(rows)} measurements written to {args.out}/ (results.md, results.csv, *.png)")
        return 0
    if args.command == "sweep":
        from .sweeps.cli import run

        return run(args)
    if args.command == "check":
        return _check(args)
    if args.command == "coupon":
        return _coupon(args)
    from .api import build
    from .findings import check_codes

    allow = check_codes(args.allow)
    start = time.perf_counter()
    results = build(_load_all(args), args.out, _progress(Path(args.out)))
    wall, work = time.perf_counter() - start, math.fsum(r.seconds for r in results)
    side = f" ({work:.2f} s of building side by side)" if len(results) > 1 else ""
    print(f"built {len(results)} profile(s) into {args.out}/ in {wall:.2f} s{side}")
    return _failed([(r.name, f) for r in results for f in r.failures if f.code not in allow])


def _closed_streams() -> None:
    """A standard stream the caller closed (``gearcad build … >&-``) is the null device: Python
    leaves ``sys.stdout`` None (a write was an AttributeError), and the next file opened would
    take descriptor 1 (a child's output would go into it)."""
    for fd, name, mode in ((0, "stdin", os.O_RDONLY), (1, "stdout", os.O_WRONLY), (2, "stderr", os.O_WRONLY)):
        try:
            os.fstat(fd)
        except OSError:
            null = os.open(os.devnull, mode)
            if null != fd:  # the lowest free descriptor: fd itself unless a lower one is closed too
                os.dup2(null, fd)
                os.close(null)
        if getattr(sys, name) is None:
            setattr(sys, name, open(fd, "r" if fd == 0 else "w", encoding="utf-8", closefd=False))


def _printable_streams() -> None:
    """A terminal that is not UTF-8 (LC_ALL=C, PYTHONIOENCODING=latin-1) shows β, ω, ² escaped
    rather than ending the build with UnicodeEncodeError."""
    for stream in (sys.stdout, sys.stderr):
        encoding = (getattr(stream, "encoding", None) or "").lower().replace("-", "").replace("_", "")
        if encoding != "utf8" and hasattr(stream, "reconfigure"):
            stream.reconfigure(errors="backslashreplace")


def main(argv: list[str] | None = None) -> int:
    _closed_streams()
    _printable_streams()
    try:
        # Ctrl-C and SIGTERM from the first moment, not only once a build starts: one line and
        # 130 / 143, never a silent end (a build's and a sweep's own guards name their --out)
        with interrupt_guard():
            args = _parser().parse_args(argv)
            logging.basicConfig(level=logging.ERROR, format="%(levelname)s: %(message)s")
            with warnings.catch_warnings():
                # numpy's overflow or invalid-value notes on an extreme profile are no news to the
                # user: the design is checked, and what is wrong is the one line below
                warnings.simplefilter("ignore", RuntimeWarning)
                return _main(args)
    except Interrupted as exc:  # landed outside _main (while the arguments were read)
        print(f"gearcad: {exc}", file=sys.stderr)
        return exc.exit_code


def _main(args) -> int:
    try:
        if args.command in ("build", "bench", "coupon"):
            from .api import check_out

            check_out(args.out)  # before any work: a bad --out is found in a moment
        code = _run(args)
        sys.stdout.flush()  # into a pipe stdout is block-buffered: a reader gone shows here, not at exit
        return code
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


def run(argv: list[str] | None = None) -> NoReturn:
    """The command line as a program (the ``gearcad`` script, ``python -m gearcad``): :func:`main`,
    then exit with its status.  An interrupted command (130, 143) ends at once after its line:
    its workers are ended and reaped and its output left as it was, so nothing is left to do, and
    a process pool's queue-feeding thread, its workers killed, could otherwise print a traceback
    into the user's terminal while the interpreter shuts down (CPython's executor writes into a
    pipe its broken pool has closed)."""
    code = main(argv)
    if code in (130, 143):
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(Exception):
                stream.flush()
        os._exit(code)
    sys.exit(code)


if __name__ == "__main__":
    run()
