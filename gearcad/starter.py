"""``gearcad new NAME --from PROFILE``: a design of one's own, started from an example.

The copy keeps the example's comments and first line ``#:schema ./profile.schema.json``, and
the schema is written beside it, so a TOML editor still completes and checks the copy.
"""

from __future__ import annotations

import json
import os
import re
import tomllib
from pathlib import Path

from .errors import OutputError, ProfileError
from .profiles import parse_profile, profile_schema
from .publish import write_files

__all__ = ["SCHEMA_LINE", "example_folders", "new_profile"]

SCHEMA_LINE = "#:schema ./profile.schema.json"
_TOP_KEY = re.compile(r"^(name|title)\s*=.*$", re.M)


def example_folders() -> list[Path]:
    """Where example names are looked up: ./profiles, then the checkout gearcad runs from."""
    folders = [Path("profiles"), Path(__file__).resolve().parent.parent / "profiles"]
    return [f for f in dict.fromkeys(folders) if f.is_dir()]


def _source(name: str) -> Path:
    path = Path(name)
    if path.suffix == ".toml" and path.is_file():
        return path
    for folder in example_folders():
        if (folder / f"{name}.toml").is_file():
            return folder / f"{name}.toml"
    known = sorted({p.stem for folder in example_folders() for p in folder.glob("*.toml")})
    allowed = f"one of {', '.join(known)}" if known else "a profile file's path (no profiles/ folder found)"
    raise ProfileError(f"--from = {name!r}: no such profile; give {allowed}")


def _retitled(text: str, name: str, source: str) -> str:
    """``text`` as the user's own design: its top-level ``name`` and ``title`` set (added if
    absent), the schema line first, a neutral header in place of the example's comments, no
    comment lines or comments after keys (they tell the example's paper: its tables, its 270 rpm),
    and no ``driver_rpm`` (the paper's speed: the default applies).  Every value that shapes the
    parts is kept."""

    def bare(line: str) -> str | None:
        """The line without its comment (None: a comment line, or the example's speed)."""
        if line.lstrip().startswith("#") or re.match(r"\s*driver_rpm\s*=", line):
            return None
        for at in (i for i, c in enumerate(line) if c == "#"):
            try:
                tomllib.loads(line[:at])  # a whole key = value (or [table]) before it: a comment
            except tomllib.TOMLDecodeError:
                continue  # a '#' inside a string, or a line of a value spread over lines
            return line[:at].rstrip()
        return line.rstrip()

    kept = [ln for ln in map(bare, text.split("\n")) if ln is not None]
    head, table, rest = "\n".join(kept).partition("\n[")
    head = [ln for ln in _TOP_KEY.sub("", head).split("\n") if ln.strip()]
    header = f"# {name}: started from gearcad's example {source} (gearcad new); every key: docs/reference.md"
    keys = [f"name = {json.dumps(name)}", f"title = {json.dumps(f'{name} (started from {source})')}"]
    body = re.sub(r"\n{3,}", "\n\n", table + rest)
    return "\n".join([SCHEMA_LINE, header, *keys, *head]) + "\n" + body.rstrip("\n") + "\n"


def new_profile(name: str, source: str = "elliptic_focus", folder: str | Path = ".") -> tuple[Path, Path]:
    """Write ``folder/NAME.toml`` (from ``source``) and ``folder/profile.schema.json``.

    Parameters
    ----------
    name : the new profile's name (its file and output folder); the rules of ``name`` apply.
    source : an example's name (``elliptic_focus``) or a profile file's path.
    folder : where to write; made if missing.

    Returns the two paths written. Raises :class:`ProfileError` (nothing written) for a bad
    name, an unknown source, or a profile that exists already.
    """
    path = _source(source)
    text = _retitled(path.read_text(encoding="utf-8"), name, path.stem)
    try:
        parse_profile(tomllib.loads(text))  # the copy must be a valid profile (and the name a valid name)
    except tomllib.TOMLDecodeError as exc:
        raise ProfileError(f"--from = {source!r}: not valid TOML ({exc})") from None
    except ProfileError as exc:
        lines = str(exc).splitlines()
        raise ProfileError("\n".join(ln if ln.startswith("name = ") else f"{path}: {ln}" for ln in lines)) from None
    folder = Path(folder)
    target = folder / f"{name}.toml"
    if os.path.lexists(target):
        raise ProfileError(f"{target}: exists already; choose another NAME or --dir (nothing was written)")
    if folder.exists() and not folder.is_dir():
        raise ProfileError(f"--dir = {str(folder)!r}: is a file, not a folder")
    schema_text = json.dumps(profile_schema(), indent=2, ensure_ascii=False) + "\n"
    # the schema replaces a file or link of its name (renamed over it, never written through it)
    schema = write_files(folder, {"profile.schema.json": schema_text.encode("utf-8")}, what="--dir")
    try:
        with open(target, "x", encoding="utf-8") as f:  # O_EXCL: never through a link, never over a file
            f.write(text)
    except OSError as exc:
        raise OutputError(f"{target}: cannot write the profile ({exc.strerror or exc})") from None
    return target, schema["profile.schema.json"]
