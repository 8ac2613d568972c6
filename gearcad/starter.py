"""``gearcad new NAME --from PROFILE``: a design of one's own, started from an example.

The copy keeps the example's comments and first line ``#:schema ./profile.schema.json``, and
the schema is written beside it, so a TOML editor still completes and checks the copy.
"""

from __future__ import annotations

import errno
import json
import os
import re
import stat
import tomllib
from contextlib import suppress
from pathlib import Path

from .errors import OutputError, ProfileError
from .errors import shown as _shown
from .profiles import parse_profile, profile_schema, read_profile_text
from .publish import write_files

__all__ = ["SCHEMA_LINE", "example_folders", "new_profile"]

SCHEMA_LINE = "#:schema ./profile.schema.json"
_TOP_KEY = re.compile(r"^(name|title)\s*=.*$", re.M)


def example_folders() -> list[Path]:
    """Where example names are looked up: ./profiles, then the checkout gearcad runs from."""
    folders = [Path("profiles"), Path(__file__).resolve().parent.parent / "profiles"]
    return [f for f in dict.fromkeys(folders) if f.is_dir()]


def _is_file(path: Path) -> bool:
    try:
        return path.is_file()
    except OSError:  # a name too long for the system, a loop: not a profile
        return False


def _source(name: str) -> Path:
    path = Path(name)
    if path.suffix == ".toml" and _is_file(path):
        return path
    for folder in example_folders():
        if "/" not in name and _is_file(folder / f"{name}.toml"):
            return folder / f"{name}.toml"
    known = sorted({p.stem for folder in example_folders() for p in folder.glob("*.toml")})
    allowed = f"one of {', '.join(known)}" if known else "a profile file's path (no profiles/ folder found)"
    raise ProfileError(f"--from = {_shown(name)}: no such profile; give {allowed}")


def _writable(path: Path, st: os.stat_result) -> bool:
    """Writable, and meant to be: a folder or file with no write bit is read-only to root too."""
    return bool(st.st_mode & 0o222) and os.access(path, os.W_OK)


def _folder(folder: Path) -> tuple[Path, list[Path]]:
    """``--dir`` as the path every write goes to, checked before anything is written, and the
    folders that ``new`` would make (removed again if it fails).  Refuses (one line) an empty
    path, a loop, a link to nothing, a name too long, a file, a read-only folder."""
    text = os.fspath(folder)
    label = f"--dir {_shown(text)}"
    if not text.strip():
        raise ProfileError("--dir '': empty; give a folder (is a shell variable unset?)")
    if "\0" in text:
        raise ProfileError(f"{label}: contains a NUL character")
    missing: list[Path] = []
    here = Path(text)
    while True:
        try:
            st = os.stat(here)
            break
        except OSError as exc:
            if exc.errno == errno.ELOOP:
                raise ProfileError(f"{label}: a symbolic link loop; give a folder or a new path") from None
            if exc.errno == errno.ENAMETOOLONG:
                raise ProfileError(f"{label}: the path or one of its names is too long for this system") from None
            if exc.errno == errno.ENOTDIR:
                raise ProfileError(f"{label}: a file stands where a folder must be") from None
            if exc.errno != errno.ENOENT:
                raise ProfileError(f"{label}: cannot use it ({exc.strerror or exc})") from None
            if os.path.islink(here):
                raise ProfileError(f"{label}: {_shown(here)} is a symbolic link to nothing; give a folder") from None
            missing.append(here)
            here = here.parent
    which = "" if not missing else f"{_shown(here)}, where it would be made, is "
    if not stat.S_ISDIR(st.st_mode):
        raise ProfileError(f"{label}: {which or 'is '}a file, not a folder")
    if not _writable(here, st):
        raise ProfileError(f"{label}: {which}read-only; give a folder you can write")
    resolved = Path(os.path.realpath(text))
    if len(os.fsencode(resolved)) >= 4096 - 64 or any(len(os.fsencode(c)) > 255 - 32 for c in resolved.parts):
        raise ProfileError(f"{label}: the path or one of its names is too long for this system")
    return resolved, [Path(os.path.realpath(m)) for m in missing]


def _schema_needed(path: Path, text: bytes) -> bool:
    """Whether ``profile.schema.json`` must be (re)written; refuses a folder or a read-only file
    there (a link is replaced, never written through; the same schema is left as it is)."""
    try:
        st = os.lstat(path)
    except FileNotFoundError:
        return True
    if stat.S_ISLNK(st.st_mode):
        return True
    if stat.S_ISDIR(st.st_mode):
        raise ProfileError(f"{_shown(path)}: a folder stands where the schema goes; move it or choose another --dir")
    if not stat.S_ISREG(st.st_mode):
        raise ProfileError(f"{_shown(path)}: not a regular file; move it or choose another --dir")
    try:
        with open(path, "rb") as f:
            if f.read(len(text) + 1) == text:
                return False
    except OSError:
        pass
    if not _writable(path, st):
        raise ProfileError(
            f"{_shown(path)}: read-only, and not this version's schema; make it writable or choose another --dir"
        )
    return True


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

    Returns the two paths written (the schema is left as it is when it is this version's).
    Raises :class:`ProfileError` or :class:`OutputError` (one line, nothing written) for a bad
    name, an unknown or unreadable source (16 MiB of UTF-8 TOML at most), a profile that exists
    already (a link of its name too), a ``folder`` that is no writable folder (a file, a loop, a
    name too long, read-only) or a schema that cannot be replaced (a folder, a read-only file).
    """
    path = _source(source)
    text = _retitled(read_profile_text(path), name, path.stem)
    try:
        parse_profile(tomllib.loads(text))  # the copy must be a valid profile (and the name a valid name)
    except tomllib.TOMLDecodeError as exc:
        raise ProfileError(f"--from = {_shown(source)}: not valid TOML ({exc})") from None
    except ValueError as exc:  # an integer of more than 4300 digits
        raise ProfileError(f"--from = {_shown(source)}: not valid TOML ({exc})") from None
    except RecursionError:
        raise ProfileError(f"--from = {_shown(source)}: not valid TOML: lists or tables nested hundreds deep") from None
    except ProfileError as exc:
        lines = str(exc).splitlines()
        raise ProfileError("\n".join(ln if ln.startswith("name = ") else f"{path}: {ln}" for ln in lines)) from None
    shown, target = Path(folder), Path(folder) / f"{name}.toml"
    folder, made = _folder(Path(folder))
    if os.path.lexists(folder / f"{name}.toml"):
        link = " (a symbolic link)" if os.path.islink(folder / f"{name}.toml") else ""
        raise ProfileError(f"{target}: exists already{link}; choose another NAME or --dir (nothing was written)")
    schema_text = (json.dumps(profile_schema(), indent=2, ensure_ascii=False) + "\n").encode("utf-8")
    schema = folder / "profile.schema.json"
    rewrite = _schema_needed(schema, schema_text)
    created = False
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with open(folder / f"{name}.toml", "x", encoding="utf-8") as f:  # O_EXCL: never through a link
            created = True
            f.write(text)
        if rewrite:  # renamed over a file or link of its name, never written through it
            write_files(folder, {"profile.schema.json": schema_text}, what="--dir")
    except (OSError, OutputError) as exc:
        if created:
            with suppress(OSError):
                os.unlink(folder / f"{name}.toml")
        for made_folder in made:  # the innermost first
            with suppress(OSError):
                os.rmdir(made_folder)
        if isinstance(exc, OutputError):
            raise
        raise OutputError(f"{target}: cannot write the profile ({exc.strerror or exc}; nothing was written)") from None
    return target, shown / "profile.schema.json"
