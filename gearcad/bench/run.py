"""``gearcad bench``: every study, the peers and goals sections, then the files."""

from __future__ import annotations

import logging
from collections.abc import Callable, Collection
from pathlib import Path

from . import stability
from .builds import bench_builds
from .commands import PROFILES, gearcad_commands
from .envelope import bench_envelope
from .front import bench_front, front_summary
from .goals import goal_rows, goals_table
from .helical import helical_benchmark
from .optimise import bench_optimise, optimise_summary
from .output import bench_output
from .peers import PEER, bench_peers, peer_version
from .process import measure
from .quadrature import bench_quadrature
from .report import markdown, peer_ratios, peers_table, write_csv
from .step import bench_step, step_lines
from .timing import Progress

__all__ = ["run_bench", "SECTIONS"]

SECTIONS = ("peers", "goals", "stages")
"""Sections that can be skipped (they run whole processes: minutes, not seconds)."""


def _studies(quick: bool, work: Path, progress) -> tuple[list[dict], list[dict]]:
    """The in-process studies, each a step of ``progress``: their rows, and the stability map's."""
    rows = bench_quadrature(quick)
    progress.step("quadrature")
    rows += bench_envelope(quick)
    progress.step("envelope")
    rows += bench_output(quick, work)
    progress.step("output size")
    rows += helical_benchmark(quick=quick)  # twisted solids: time and triangles against width and tolerance
    progress.step("helical solids")
    rows += bench_step(quick, work / "step")  # the focus pair's STEP files: time and size
    progress.step("STEP files")
    rows += bench_builds(quick, work, progress.step)
    rows += bench_front(quick)  # the sweep's Pareto front, 10⁴…10⁶ rows
    progress.step("Pareto front")
    rows += bench_optimise(quick)  # the sweep's NSGA-II against its grid; a screen the full stage refutes
    progress.step("optimiser")
    hard = stability.stability_map(quick)
    progress.step("stability map")
    return rows, hard


def _write_results(rows: list[dict], hard: list[dict], out: Path) -> None:
    """results.csv, stability.csv, results.md and the charts."""
    from ..export.charts import bench as charts_bench

    write_csv(rows, out / "results.csv")
    write_csv(hard, out / "stability.csv")
    (out / "results.md").write_text(markdown(rows, hard), encoding="utf-8")
    charts_bench.speed_accuracy(rows, out / "speed_accuracy.png")
    charts_bench.output_size(rows, out / "output_size.png")
    charts_bench.builds(rows, out / "builds.png")
    charts_bench.stability(hard, out / "stability.png")


def _peers(peer, commands: dict, work: Path, runs: int, quick: bool, progress, rows: list, lines: list) -> dict:
    """gearcad beside its peer (when importable): rows and lines added in place; what was measured."""
    measured: dict = {}
    if peer is None:
        lines.append(f"peers: {PEER} is not importable here (pip install {PEER}); the section is skipped")
    else:
        peer_rows, measured = bench_peers(
            {key: commands[key][1] for key in ("dxf", "all")},
            work / "peers",
            runs=runs,
            warm={"dxf": 3, "all": 2, PEER: 1},
            rack_cut_steps=None if quick else 96,
            step=progress.step,
        )
        rows += peer_rows
        lines += [f"peers: gearcad beside {PEER} {peer}", "", *peers_table(rows), "", *peer_ratios(rows)]
    return measured


def run_bench(
    out: Path,
    *,
    quick: bool = False,
    skip: Collection[str] = (),
    echo: Callable[[str], None] | None = None,
) -> list[dict]:
    """Run every study and write the charts, CSV and markdown into ``out``.

    ``skip``: sections of :data:`SECTIONS` to leave out.  ``echo`` receives the lines to show
    (the peers table, the ratios, the goals table, and notes such as a peer that is missing).
    """

    say = echo or (lambda line: None)
    unknown = set(skip) - set(SECTIONS)
    if unknown:
        raise ValueError(f"skip: {sorted(unknown)} are not sections; sections are {list(SECTIONS)}")
    out = Path(out).resolve()  # the children run in their own folders: every path they get is absolute
    logging.disable(logging.WARNING)
    try:
        out.mkdir(parents=True, exist_ok=True)
        work = out / "work"
        runs = 1 if quick else 5
        builds = 1 if quick else len(list(PROFILES.glob("*.toml")))
        peer = None if "peers" in skip else peer_version()
        timed = (3 * runs + 3 if peer else 0) + (0 if "goals" in skip else 8 * runs)
        staged = 0 if "stages" in skip else (7 if quick else 37)  # the stages, the overhead, (not quick) the bands
        progress = Progress(11 + builds + timed + staged)
        rows, hard = _studies(quick, work, progress)
        commands = gearcad_commands(work / "runs")
        labels = {key: text for key, (text, _) in commands.items()}
        measured, lines = {}, [*step_lines(rows), *front_summary(rows), *optimise_summary(rows)]
        if "peers" not in skip:
            measured = _peers(peer, commands, work, runs, quick, progress, rows, lines)
        if "goals" not in skip:
            todo = {key: command for key, (_, command) in commands.items() if key not in measured}
            measured.update(measure(todo, runs=runs, step=progress.step))
            goals = goal_rows(measured, labels)
            rows += goals
            lines += ["", "goals (medians of whole-process runs):", "", *goals_table(goals)]
        if "stages" not in skip:
            from .stages import bench_stages, stages_table

            stage_rows = bench_stages(quick, progress.step)
            rows += stage_rows
            lines += ["", "stages (warm, CPU time per design in process):", "", *stages_table(stage_rows)]
            from .overhead import bench_overhead, overhead_lines, overhead_summary

            over = bench_overhead(quick, progress.step)  # a sweep's cost per design beyond the design
            rows += over
            lines += ["", "a sweep's overhead per pitch-stage design (CPU):", "", *overhead_lines(over)]
            lines += overhead_summary(over)
            if not quick:  # a full design of each pair under a laser: minutes, not the quick run's seconds
                from .bands import bands_table, bench_bands

                band_rows = bench_bands(False, progress.step)
                rows += band_rows
                lines += ["", "bands (warm, CPU time of the certified band):", "", *bands_table(band_rows)]
                from .cluster import bench_throughput, throughput_lines

                flow = bench_throughput(progress.step)  # a sweep's designs/h, local pool and LocalCluster
                rows += flow
                lines += ["", "a sweep's throughput (wall, start-up included):", "", *throughput_lines(flow)]
        _write_results(rows, hard, out)
        progress.finish()
        for line in lines:
            say(line)
    finally:
        logging.disable(logging.NOTSET)
    return rows
