"""Nothing escapes ``--out`` for the commands added after ``build`` (issue 34, items 1–3): files
planted as links under the names a command writes are replaced, never written through, and an
empty ``--out`` is refused by every command that takes one, with nothing written anywhere."""

import os

import pytest

from gearcad.cli import main
from gearcad.publish import write_files

from .conftest import ROOT

FOCUS = ROOT / "profiles" / "elliptic_focus.toml"


def _plant(folder, names, victim):
    """A link to ``victim`` under each of ``names`` in ``folder``."""
    folder.mkdir(parents=True, exist_ok=True)
    for name in names:
        os.symlink(victim, folder / name)


def test_write_files_replaces_links_and_never_writes_through_them(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_text("keep me")
    out = tmp_path / "out"
    # the names the old code wrote through, and the final names too
    _plant(out, [".a.tmp", "a", ".b.csv.tmp"], victim)
    written = write_files(out, {"a": b"new a", "b.csv": b"new b"})
    assert victim.read_text() == "keep me"
    assert not (out / "a").is_symlink() and (out / "a").read_bytes() == b"new a"
    assert (out / "b.csv").read_bytes() == b"new b"
    assert set(written) == {"a", "b.csv"}
    # no temporary file is left, and the files have a plain file's mode for the umask
    umask = os.umask(0)
    os.umask(umask)
    assert {p.name for p in out.iterdir()} == {".a.tmp", "a", ".b.csv.tmp", "b.csv"}
    assert (out / "a").stat().st_mode & 0o777 == 0o666 & ~umask


def test_new_replaces_a_planted_schema_link(tmp_path, capsys):
    victim = tmp_path / "victim.json"
    victim.write_text("keep me")
    folder = tmp_path / "mine"
    _plant(folder, ["profile.schema.json"], victim)
    assert main(["new", "mine", "--dir", str(folder)]) == 0
    assert victim.read_text() == "keep me"
    assert not (folder / "profile.schema.json").is_symlink()
    assert (folder / "mine.toml").is_file()


def test_new_refuses_a_dangling_link_under_its_name(tmp_path, capsys):
    folder = tmp_path / "mine"
    folder.mkdir()
    os.symlink(tmp_path / "nowhere.toml", folder / "mine.toml")
    assert main(["new", "mine", "--dir", str(folder)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "exists already" in err
    assert not (tmp_path / "nowhere.toml").exists() and not (folder / "profile.schema.json").exists()


@pytest.mark.parametrize(
    "argv",
    [
        [
            "sweep",
            str(FOCUS),
            "--vary",
            "gear1.eccentricity=0.2,0.3",
            "--stage",
            "pitch",
            "--workers",
            "1",
            "--out",
            "",
        ],
        ["coupon", str(FOCUS), "--set", "process.kind=laser", "--out", ""],
        ["schema", "--out", ""],
        ["bench", "--quick", "--out", ""],
        ["build", str(FOCUS), "--out", ""],
    ],
    ids=["sweep", "coupon", "schema", "bench", "build"],
)
def test_every_out_refuses_empty(argv, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--out ''" in err
    assert list(tmp_path.iterdir()) == []
