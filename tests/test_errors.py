"""Errors as the user meets them: a file that cannot be written is an OutputError (one line,
exit 2, nothing published), and the command line, going through the API, keeps each error's type."""

import errno
import os

import pytest

import gearcad
from gearcad.cli import main
from gearcad.errors import GearcadError, OutputError, ProfileError

from .conftest import EXAMPLES

CHEAP = {"output.charts": False, "output.animation": False, "output.formats": ["dxf"]}
CHEAP_ARGS = [a for k, v in CHEAP.items() for a in ("--set", f"{k}={str(v).lower().replace(chr(39), chr(34))}")]


@pytest.fixture
def disk_full(monkeypatch):
    """Every design's files fail to write as on a full disk, naming the file."""
    import gearcad.export.write as write

    def full(design, folder, **_):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(folder / "pinion.dxf"))

    monkeypatch.setattr(write, "write_design", full)


def test_a_write_that_fails_is_an_output_error_and_publishes_nothing(tmp_path, disk_full):
    params = gearcad.load_profile(EXAMPLES / "spur_pair.toml", CHEAP, unset=["teeth"])
    with pytest.raises(OutputError, match=r"pinion\.dxf: cannot write \(No space left on device\)") as exc:
        gearcad.build([params], tmp_path / "out")
    assert str(exc.value).startswith("spur_pair: ")  # the profile it came from
    assert os.listdir(tmp_path) == []


def test_the_command_line_says_it_in_one_line_and_exits_2(tmp_path, capsys, disk_full):
    out = tmp_path / "out"
    argv = ["build", str(EXAMPLES / "spur_pair.toml"), "--out", str(out), *CHEAP_ARGS, "--unset", "teeth"]
    assert main(argv) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert line.startswith("gearcad: error: spur_pair: ") and "No space left on device" in line
    assert "nothing was published" in line and not out.exists()


def test_a_schema_that_cannot_be_written_is_one_line(tmp_path, capsys):
    target = tmp_path / "missing" / "schema.json"
    assert main(["schema", "--out", str(target)]) == 2
    (line,) = capsys.readouterr().err.strip().splitlines()
    assert line == f"gearcad: error: --out {target}: cannot write the schema there (No such file or directory)"


def test_error_types_are_kept_through_the_api():
    assert issubclass(OutputError, GearcadError) and not issubclass(OutputError, ValueError)
    with pytest.raises(ProfileError, match="stage = 'mesh'"):
        gearcad.design_all([EXAMPLES / "spur_pair.toml"], stage="mesh")
    spur = EXAMPLES / "spur_pair.toml"
    with pytest.raises(ProfileError, match="two profiles build into the same folder"):
        gearcad.design_all([spur, spur], stage="pitch")
