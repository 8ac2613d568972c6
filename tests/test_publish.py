"""Publishing into --out: folders atomic under SIGKILL, nothing left by failures, interrupts, races."""

import os
import pickle
import random
import select
import signal
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import pytest

from gearcad import publish
from gearcad.errors import GearcadError, ProfileError
from gearcad.publish import Interrupted, Publisher, check_out

from .conftest import ROOT

NAMES = ("a", "b", "c")
FILES = 40
EXPECTED = sorted(f"f{i:03d}.txt" for i in range(FILES))

# A build the way the CLI will run one, with markers on stdout and knobs to slow it down.
CHILD = r"""
import os, sys, time
from pathlib import Path
from gearcad import publish

out, gen = Path(sys.argv[1]), sys.argv[2]
pause = float(os.environ.get("PAUSE", "0"))  # seconds slept after each step of the commit
slow_write = float(os.environ.get("SLOW_WRITE", "0"))

def say(text):
    os.write(1, f"{text}\n".encode())
    if text == os.environ.get("STOP_AT"):  # hold here until killed: the kill lands at this step, whatever the load
        time.sleep(3600)

exchange = (lambda a, b: False) if os.environ.get("NO_EXCHANGE") else publish._exchange
def slow_exchange(a, b):
    say(f"swap {b.name}")
    done = exchange(a, b)
    say(f"swapped {b.name}")  # the old copy is still in the staging folder
    time.sleep(pause)
    return done
publish._exchange = slow_exchange
clean = publish._clean
def marked_clean(folder, **kw):
    say(f"clean {folder.name}")  # deleting what killed builds left
    clean(folder, **kw)
publish._clean = marked_clean
rename = os.rename
def slow_rename(a, b):
    rename(a, b)
    say(f"renamed {Path(b).name}")
    time.sleep(pause)
os.rename = slow_rename

say("start")
try:
    with publish.interrupt_guard(out), publish.Publisher(out) as pub:
        for name in "abc":
            folder = pub.folder(name)
            say(f"staging {name}")
            for i in range(FILES):
                (folder / f"f{i:03d}.txt").write_text(f"{gen}\n" * 50)
                time.sleep(slow_write)
        say("staged")
        while os.environ.get("WAIT_FOR") and not Path(os.environ["WAIT_FOR"]).exists():
            time.sleep(0.002)
        pub.commit()
except publish.Interrupted as exc:
    sys.stderr.write(f"gearcad: {exc}\n")
    sys.exit(exc.exit_code)
say("done")
""".replace("FILES", str(FILES))


def _spawn(out: Path, gen: str, **env) -> subprocess.Popen:
    env = {**os.environ, "PYTHONPATH": str(ROOT), **{k: str(v) for k, v in env.items()}}
    return subprocess.Popen(
        [sys.executable, "-c", CHILD, str(out), gen], stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env
    )


def _wait_for(proc: subprocess.Popen, marker: str, lines: list[str], timeout: float = 120.0) -> None:
    """Read the child's markers into ``lines`` until ``marker`` (or its end)."""
    end = time.monotonic() + timeout
    buffer = b""
    while marker not in lines and time.monotonic() < end:
        if not select.select([proc.stdout], [], [], 0.01)[0]:
            continue
        chunk = os.read(proc.stdout.fileno(), 4096)
        if not chunk:
            return
        buffer += chunk
        *done, buffer = buffer.split(b"\n")
        lines += [line.decode() for line in done]


def _finish(proc: subprocess.Popen, lines: list[str]) -> tuple[int, list[str]]:
    out, err = proc.communicate(timeout=120)  # a hang guard: a generous multiple on a loaded machine
    lines += out.decode().splitlines()
    return proc.returncode, err.decode().splitlines()


def _generation(folder: Path) -> str:
    """The one generation all of a folder's files hold; fails on a missing, partial or mixed folder."""
    assert folder.is_dir(), f"{folder} is missing"
    assert sorted(p.name for p in folder.iterdir()) == EXPECTED, f"{folder} is incomplete"
    texts = {p.read_text() for p in folder.iterdir()}
    assert len(texts) == 1, f"{folder} mixes generations"
    gen = texts.pop().split("\n")[0]
    assert (folder / EXPECTED[0]).read_text() == f"{gen}\n" * 50, f"{folder} holds a truncated file"
    return gen


def _build(out: Path, gen: str, names=NAMES) -> None:
    with Publisher(out) as pub:
        for name in names:
            folder = pub.folder(name)
            for f in EXPECTED:
                (folder / f).write_text(f"{gen}\n" * 50)
        pub.commit()


def _tree(folder: Path) -> dict:
    return {str(p.relative_to(folder)): p.read_bytes() if p.is_file() else None for p in sorted(folder.rglob("*"))}


def _leftovers(base: Path) -> list[Path]:
    return [p for p in base.rglob("*") if p.name.startswith((".gearcad", ".out-staging", ".old-"))]


@pytest.mark.parametrize("exchange", [True, False], ids=["exchange", "two-renames"])
def test_every_folder_is_whole_after_a_kill_at_any_moment(tmp_path, exchange):
    out = tmp_path / "out"
    _build(out, "gen-1")
    env = {"PAUSE": 0.003} if exchange else {"PAUSE": 0.003, "NO_EXCHANGE": 1}
    targets = [None, "clean out", "staging b", "staged", "swap a", "swapped a", "swapped b", "swapped c"]
    if not exchange:
        targets = ["renamed .old-a", "renamed .old-b", "renamed a", "staging c"]
    rng = random.Random(7)
    previous = dict.fromkeys(NAMES, "gen-1")
    phases: dict[str, int] = {}
    kills = 2 * len(targets)  # every target twice
    for k in range(kills):
        gen = f"gen-{k + 2}"
        target = targets[k % len(targets)]
        # a target: the child holds at that step until killed, so each kill lands where it is meant
        # to whatever the machine's load (not after a race the scheduler may lose)
        proc, lines = _spawn(out, gen, **env, **({"STOP_AT": target} if target else {})), []
        if target is None:  # anywhere from start-up to the end
            time.sleep(rng.uniform(0.0, 0.08))
        else:
            _wait_for(proc, target, lines)
        proc.kill()
        _finish(proc, lines)
        phase = lines[-1] if lines else "(python start-up)"
        assert target is None or phase == target, (target, lines[-3:])
        phases[phase] = phases.get(phase, 0) + 1
        if not exchange and phase.startswith("renamed .old-"):  # the documented gap of two renames
            gone = phase.removeprefix("renamed .old-")
            assert not (out / gone).exists()
            with pytest.raises(RuntimeError), Publisher(out) as pub:  # the next build, failing, repairs
                pub.folder("a")
                raise RuntimeError
            assert _generation(out / gone) == previous[gone]
        for name in NAMES:
            now = _generation(out / name)
            assert now in (previous[name], gen), (phase, name, now)
            previous[name] = now
        assert {p.name for p in out.iterdir() if not p.name.startswith(".gearcad-staging-")} == set(NAMES)
    print(f"{kills} kills, last marker at death: {dict(sorted(phases.items()))}")
    _build(out, "gen-final")
    assert all(_generation(out / name) == "gen-final" for name in NAMES)
    assert _leftovers(tmp_path) == []


def test_a_first_build_killed_leaves_nothing_but_what_the_next_one_removes(tmp_path):
    out = tmp_path / "x" / "y" / "out"
    rng = random.Random(3)
    for k in range(8):
        proc, lines = _spawn(out, f"gen-{k}"), []
        _wait_for(proc, ["staging a", "staging c", "staged", "renamed x"][k % 4], lines)
        time.sleep(rng.uniform(0.0, 0.003))
        proc.kill()
        _finish(proc, lines)
        assert not (tmp_path / "x").exists() or all(_generation(out / n) == f"gen-{k}" for n in NAMES)
        if (tmp_path / "x").exists():
            break
    _build(out, "gen-final")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x"]
    assert sorted(p.name for p in out.iterdir()) == list(NAMES)
    assert _leftovers(tmp_path) == []


def test_a_failed_build_creates_nothing(tmp_path):
    out = tmp_path / "x" / "y" / "out"
    with pytest.raises(RuntimeError), Publisher(out) as pub:
        (pub.folder("a") / "f.txt").write_text("half")
        raise RuntimeError
    assert list(tmp_path.iterdir()) == []


def test_a_failed_build_leaves_out_byte_for_byte(tmp_path):
    out = tmp_path / "out"
    _build(out, "gen-1", names=("a", "b"))
    (out / "notes.txt").write_text("mine")
    before = _tree(tmp_path)
    with pytest.raises(RuntimeError), Publisher(out) as pub:
        for name in NAMES:
            (pub.folder(name) / "f000.txt").write_text("gen-2")
        raise RuntimeError
    assert _tree(tmp_path) == before


def test_first_build_publishes_out_with_its_parents_and_nothing_else(tmp_path):
    out = tmp_path / "x" / "y" / "out"
    _build(out, "gen-1")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x"]
    assert sorted(p.name for p in out.iterdir()) == list(NAMES)
    _build(out, "gen-2")
    assert sorted(p.name for p in out.iterdir()) == list(NAMES)
    assert {_generation(out / n) for n in NAMES} == {"gen-2"}


def test_a_file_held_open_keeps_reading_the_old_build(tmp_path):
    out = tmp_path / "out"
    _build(out, "gen-1")
    with (out / "a" / "f000.txt").open() as held:
        _build(out, "gen-2")
        assert held.read() == "gen-1\n" * 50
    assert (out / "a" / "f000.txt").read_text() == "gen-2\n" * 50


def test_two_renames_where_exchange_is_missing(tmp_path, monkeypatch):
    monkeypatch.setattr(publish, "_exchange", lambda a, b: False)
    out = tmp_path / "out"
    _build(out, "gen-1")
    _build(out, "gen-2")
    assert {_generation(out / n) for n in NAMES} == {"gen-2"}
    assert _leftovers(tmp_path) == []


def test_exchange_swaps_two_folders(tmp_path):
    (tmp_path / "p").mkdir()
    (tmp_path / "q").mkdir()
    (tmp_path / "p" / "from-p").touch()
    assert publish._exchange(tmp_path / "p", tmp_path / "q"), "renameat2(RENAME_EXCHANGE) unavailable here"
    assert [p.name for p in (tmp_path / "q").iterdir()] == ["from-p"]
    assert list((tmp_path / "p").iterdir()) == []


def test_check_out_refuses_a_file(tmp_path):
    (tmp_path / "file").write_text("x")
    with pytest.raises(GearcadError, match=r"exists and is not a folder"):
        check_out(tmp_path / "file")
    with pytest.raises(GearcadError, match=r"is a file, so no folder can be made inside it"):
        check_out(tmp_path / "file" / "sub" / "out")
    with pytest.raises(GearcadError, match=r"exists and is not a folder"):
        Publisher(tmp_path / "file")
    (tmp_path / "dangling").symlink_to(tmp_path / "nowhere")
    with pytest.raises(GearcadError, match=r"dangling: a symbolic link to missing .*nowhere"):
        check_out(tmp_path / "dangling")
    (tmp_path / "loop").symlink_to(tmp_path / "loop")
    with pytest.raises(GearcadError, match=r"loop: .*(loop|too many)"):
        check_out(tmp_path / "loop")
    check_out(tmp_path / "new" / "out")
    check_out(tmp_path)


def test_check_out_refuses_an_unwritable_ancestor(tmp_path):
    if os.geteuid() != 0:
        (tmp_path / "ro").mkdir(mode=0o555)
        with pytest.raises(GearcadError, match=r"is not writable"):
            check_out(tmp_path / "ro" / "x" / "out")
        return
    # root ignores permissions: ask as the unprivileged user 'nobody' (65534) instead
    base = Path(tempfile.mkdtemp())
    try:
        base.chmod(0o755)
        (base / "ro").mkdir(mode=0o555)
        script = "import sys; from gearcad.publish import check_out; check_out(sys.argv[1])"
        run = subprocess.run(
            [sys.executable, "-c", script, str(base / "ro" / "x" / "out")],
            user=65534,
            capture_output=True,
            text=True,
            env={**os.environ, "PYTHONPATH": str(ROOT)},
            cwd="/",
        )
        if "PermissionError" in run.stderr and "check_out" not in run.stderr:
            pytest.skip(f"user 65534 cannot run the interpreter: {run.stderr.splitlines()[-1]}")
        assert run.returncode == 1 and "is not writable" in run.stderr.splitlines()[-1], run.stderr
    finally:
        (base / "ro").rmdir()
        base.rmdir()


@pytest.mark.parametrize("name", ["../x", "/abs", "a/b", "", ".x", ".", "..", "a\0b", 3])
def test_unsafe_names_are_refused(tmp_path, name):
    with pytest.raises(ProfileError, match="name = "), Publisher(tmp_path / "out") as pub:
        pub.folder(name)
    assert list(tmp_path.iterdir()) == []


def test_a_name_twice_is_refused(tmp_path):
    with pytest.raises(ProfileError, match="two profiles"), Publisher(tmp_path / "out") as pub:
        pub.folder("a")
        pub.folder("a")


@pytest.mark.parametrize("existing", [True, False], ids=["over-a-build", "new-out"])
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_an_interrupt_cleans_up_with_one_line(tmp_path, sig, existing):
    out = tmp_path / "out"
    if existing:
        _build(out, "gen-1")
    before = _tree(tmp_path)
    proc, lines = _spawn(out, "gen-2", SLOW_WRITE=0.002), []
    _wait_for(proc, "staging b", lines)
    proc.send_signal(sig)
    code, err = _finish(proc, lines)
    assert (code, err) == (128 + sig, [f"gearcad: interrupted; {out} left as it was"])
    assert _tree(tmp_path) == before


def test_an_interrupt_while_publishing_lets_the_publish_finish(tmp_path):
    out = tmp_path / "out"
    _build(out, "gen-1")
    proc, lines = _spawn(out, "gen-2", PAUSE=0.05), []
    _wait_for(proc, "swapped a", lines)
    proc.send_signal(signal.SIGTERM)
    code, err = _finish(proc, lines)
    assert (code, err) == (143, [f"gearcad: interrupted; {out} had already been published"])
    assert {_generation(out / n) for n in NAMES} == {"gen-2"}
    assert _leftovers(tmp_path) == []


def test_a_concurrent_build_leaves_the_staging_of_a_live_one_alone(tmp_path):
    out = tmp_path / "out"
    _build(out, "gen-1")
    go = tmp_path / "go"
    first, first_lines = _spawn(out, "first", WAIT_FOR=go), []
    _wait_for(first, "staged", first_lines)
    second, second_lines = _spawn(out, "second"), []
    assert _finish(second, second_lines) == (0, [])  # its clean-up ran beside the first's staging
    assert {_generation(out / n) for n in NAMES} == {"second"}
    go.touch()
    assert _finish(first, first_lines) == (0, [])
    assert {_generation(out / n) for n in NAMES} == {"first"}
    assert _leftovers(tmp_path) == []


def test_concurrent_builds_publish_one_after_the_other(tmp_path):
    out = tmp_path / "out"
    _build(out, "gen-1")
    first, first_lines = _spawn(out, "first", PAUSE=0.08), []
    _wait_for(first, "swapped a", first_lines)
    second, second_lines = _spawn(out, "second"), []  # unlocked, it would publish all between a and b
    assert _finish(second, second_lines) == (0, [])
    assert _finish(first, first_lines) == (0, [])
    assert {_generation(out / n) for n in NAMES} == {"second"}
    assert _leftovers(tmp_path) == []


def _write(folder: Path, gen: str) -> None:
    for f in EXPECTED:
        (folder / f).write_text(f"{gen}\n" * 50)


def test_workers_of_a_process_pool_write_into_the_folders(tmp_path):
    out = tmp_path / "out"
    with Publisher(out) as pub, ProcessPoolExecutor(2) as pool:
        list(pool.map(_write, [pub.folder(n) for n in NAMES], ["gen-1"] * 3))
        pub.commit()
    assert {_generation(out / n) for n in NAMES} == {"gen-1"}


def test_interrupted_crosses_a_process_boundary():
    exc = pickle.loads(pickle.dumps(Interrupted("interrupted; out left as it was", signal.SIGTERM)))
    assert (str(exc), exc.exit_code) == ("interrupted; out left as it was", 143)
