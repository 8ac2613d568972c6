"""Publish built profile folders into ``--out``, each folder atomically.

Guarantee: **each profile folder is individually atomic: after a kill at any moment, every
folder ``out/<name>`` is either the complete previous build or the complete new one — never
missing, never half-written, never mixed. Folders of different profiles are replaced one
after another, so a build killed while publishing can leave some profiles new and others old.**
A build that fails or is interrupted (SIGINT, SIGTERM) publishes nothing; if ``--out`` did not
exist, neither it nor its missing parents exist afterwards.

Design
------
*Real folders, swapped.* The new ``out/<name>`` is swapped with the old one in one step by
``renameat2(RENAME_EXCHANGE)`` (Linux ≥ 3.15 on ext4, xfs, btrfs, tmpfs, …), then the old copy
is deleted. ``out/<name>`` stays a plain folder, unlike a symlink into a hidden version folder,
which ``cp -r``, zip, rsync or git copy as a link whose target is left behind. A program with a
file open keeps reading the old file (Linux keeps deleted files alive while open); one whose
current folder is the old ``out/<name>`` finds it emptied. A kill between swap and delete leaves
the old copy in a hidden staging folder, which the next build deletes. Where the swap is not
available (other systems, some network filesystems) two renames are used instead: a kill
between them leaves ``out/<name>`` missing until the next build, which puts the old one back.

*Staging.* Files are written into a hidden ``.gearcad-staging-XXXXXXXX`` folder: inside ``out``
when it exists, beside the folders they replace (a rename needs one filesystem); otherwise in
its nearest existing ancestor, standing for the first missing component of the path, so that
one rename publishes ``out`` and its missing parents at once. ``ls out`` shows the profile
folders only, and a staging folder while a build runs or after a kill, until the next build.

*Locks.* A build holds ``flock`` on its staging folder; every build deletes the staging
folders in ``out`` and its nearest existing ancestor that no live process holds (left by
killed builds). Concurrent builds
into one ``out`` both build, and a ``flock`` on ``out`` makes the second to finish wait while
the first publishes: ``out`` ends with the complete output of the later one (profiles it does
not build keep the earlier one's). Files are not fsynced: this guards against killed
processes, not power loss. POSIX only (``fcntl``).

Use
---
``with interrupt_guard(out), Publisher(out) as pub:`` give each profile ``pub.folder(name)``
(a plain path, so a process pool's workers can write into it), then ``pub.commit()``. SIGINT
and SIGTERM become :class:`Interrupted`, whose message is the one line to print and whose
``exit_code`` is 130 or 143; they are held off while ``commit`` publishes.
"""

from __future__ import annotations

import ctypes
import errno
import fcntl
import os
import re
import shutil
import tempfile
from contextlib import contextmanager, suppress
from pathlib import Path

from .errors import GearcadError, OutputError, ProfileError, shown
from .interrupts import Interrupted, held_signals, interrupt_guard

__all__ = ["Publisher", "Interrupted", "interrupt_guard", "check_out", "resolve_out", "out_lock", "write_files"]

_NAME = re.compile(r"[\w-][\w.-]*")
_PREFIX = ".gearcad-staging-"
_STAGING = re.compile(re.escape(_PREFIX) + "[a-z0-9_]{8}")  # tempfile.mkdtemp's 8 random characters
_AT_FDCWD, _RENAME_EXCHANGE = -100, 2


def _nearest(path: Path) -> Path:
    while not os.path.lexists(path):
        path = path.parent
    return path


def resolve_out(out: Path | str) -> Path:
    """The one absolute path every write into ``out`` goes to, resolved as the kernel resolves it.

    ``A/link/../x`` is ``x`` beside the link's target, not ``A/x`` (which a lexical
    normalisation would give): the profile folders, the staging and the index all use this one
    path.  Raises :class:`GearcadError` (one line) for an empty path (an unset shell variable
    would otherwise mean the current folder), a symbolic link loop, a link to nothing, or a
    name too long for the system.
    """
    text = os.fspath(out) if isinstance(out, (str, os.PathLike)) else None
    if text is None:
        raise GearcadError(f"--out {out!r}: must be a path (a string or pathlib.Path)")
    if not str(text).strip():
        raise GearcadError("--out '': empty; give a folder (is a shell variable unset?)")
    if "\0" in str(text):
        raise GearcadError(f"--out {text!r}: contains a NUL character")
    try:
        os.lstat(text)
    except OSError as exc:
        if exc.errno in (errno.ELOOP, errno.ENAMETOOLONG):
            raise GearcadError(f"--out {shown(text)}: {exc.strerror.lower()}") from None
    if os.path.islink(text) and not os.path.exists(text):
        try:
            os.stat(text)
        except OSError as exc:
            loop = exc.errno == errno.ELOOP
            what = "a symbolic link loop" if loop else f"a symbolic link to missing {shown(os.readlink(text))}"
            raise GearcadError(f"--out {shown(text)}: {what}; give a folder or a new path") from None
    path = Path(os.path.realpath(text))
    if len(os.fsencode(path)) >= 4096 - 64 or any(len(os.fsencode(c)) > 255 - 32 for c in path.parts):
        raise GearcadError(f"--out {shown(text)}: the path or one of its names is too long for this system")
    return path


def check_out(out: Path | str) -> None:
    """Raise :class:`GearcadError` (one line) if files cannot be published into ``out``.

    ``out`` must be a folder or a path that does not exist yet, inside a folder one can write in.
    """
    path = resolve_out(out)
    named = shown(out)
    ancestor = _nearest(path)
    if ancestor == path and not path.is_dir():
        raise GearcadError(f"--out {named}: exists and is not a folder; give a folder or a new path")
    if not ancestor.is_dir():
        raise GearcadError(f"--out {named}: {ancestor} is a file, so no folder can be made inside it")
    if not os.access(ancestor, os.W_OK | os.X_OK):
        raise GearcadError(f"--out {named}: {ancestor} is not writable")


def write_files(out: Path | str, contents: dict[str, bytes], *, what: str = "--out") -> dict[str, Path]:
    """Write each ``name: bytes`` of ``contents`` into the folder ``out`` (made if missing), whole.

    Each file is first written to a new file under a random hidden name (created exclusively:
    never through a link planted in ``out``), with the usual mode for the umask, then renamed
    over ``out/name`` — a rename replaces a link of that name, it does not follow it — under the
    lock a build holds while it publishes into ``out``.  A failure removes what was written and
    raises :class:`OutputError` (one line); files already renamed stay (each one is whole).
    Returns the paths written, in the order given.
    """
    for name in contents:
        if not _NAME.fullmatch(name) or name.startswith("."):
            raise ValueError(f"write_files: {name!r} is not a plain file name")
    path = resolve_out(out)
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"{what} {shown(out)}: cannot make the folder ({exc.strerror or exc})") from None
    umask = os.umask(0)
    os.umask(umask)
    written: dict[str, Path] = {}
    temporary: list[str] = []
    try:
        with out_lock(path):
            for name, data in contents.items():
                fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=path)
                temporary.append(tmp)
                with os.fdopen(fd, "wb") as f:
                    os.fchmod(f.fileno(), 0o666 & ~umask)
                    f.write(data)
                os.replace(tmp, path / name)
                temporary.remove(tmp)
                written[name] = path / name
    except OSError as exc:
        raise OutputError(f"{what} {shown(out)}: cannot write {exc.filename or path} ({exc.strerror or exc})") from None
    finally:
        for tmp in temporary:
            with suppress(OSError):
                os.unlink(tmp)
    return written


def _load_renameat2():
    try:
        fn = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError):
        return None
    fn.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    fn.restype = ctypes.c_int
    return fn


_renameat2 = _load_renameat2()


def _exchange(a: Path, b: Path) -> bool:
    """Swap two existing paths in one step; ``False`` where the system or filesystem cannot."""
    if _renameat2 is None:
        return False
    if _renameat2(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.EINVAL, errno.ENOSYS, errno.EOPNOTSUPP):
        return False
    raise OSError(err, os.strerror(err), str(b))


def _lock(folder: Path, *, wait: bool) -> int | None:
    """A descriptor of ``folder`` holding its exclusive flock, or ``None`` if another holds it."""
    fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
    except BaseException as exc:
        os.close(fd)
        if isinstance(exc, BlockingIOError):
            return None
        raise
    return fd


@contextmanager
def out_lock(out: Path):
    """Hold the lock a build holds while it publishes into ``out`` (an existing folder): the
    index page read and written under it is never older than a folder published before it."""
    fd = _lock(out, wait=True)
    try:
        yield
    finally:
        os.close(fd)


def _new_staging(parent: Path) -> tuple[Path, int]:
    """A new staging folder in ``parent`` and the descriptor that holds its lock."""
    while True:
        path = Path(tempfile.mkdtemp(prefix=_PREFIX, dir=parent))
        # mkdtemp makes it private (0700); it may become --out itself: give it a folder's usual mode
        umask = os.umask(0)
        os.umask(umask)
        try:
            os.chmod(path, 0o777 & ~umask)
            fd = _lock(path, wait=True)
        except FileNotFoundError:  # another build's cleaner took it before it was locked
            continue
        with suppress(FileNotFoundError):  # a cleaner took it, unlocked, for a killed build's
            if os.path.samestat(os.fstat(fd), os.stat(path)):
                return path, fd
        os.close(fd)


def _clean(folder: Path, *, repair: bool = False) -> None:
    """Delete the staging folders in ``folder`` no live build holds (``repair``: put back into
    ``folder`` each ``.old-<name>`` a killed two-rename publish left)."""
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return
    found = [Path(e.path) for e in entries if _STAGING.fullmatch(e.name) and e.is_dir(follow_symlinks=False)]
    for path in found:
        try:
            fd = _lock(path, wait=False)
        except OSError:  # removed meanwhile
            continue
        if fd is None:  # a live build's
            continue
        try:
            for old in path.glob(".old-*") if repair else ():
                if not os.path.lexists(folder / old.name[5:]):
                    os.rename(old, folder / old.name[5:])
            shutil.rmtree(path, ignore_errors=True)
        finally:
            os.close(fd)


class Publisher:
    """Stage profile folders and publish them into ``out``; a context manager.

    Parameters
    ----------
    out : path
        The output folder; checked by :func:`check_out` at once, created only by :meth:`commit`.

    Leaving the ``with`` block without :meth:`commit` (an error, an interrupt) deletes the
    staging and leaves ``out`` as it was, apart from leftovers of killed builds.
    """

    def __init__(self, out: Path | str) -> None:
        check_out(out)
        self.out = Path(out)
        self._abs = resolve_out(out)  # every write goes here, however out was spelt
        self._root: Path | None = None  # this build's staging folder
        self._tree: Path | None = None  # the future ``out`` inside it
        self._fds: list[int] = []
        self._names: list[str] = []
        self._published = False

    @property
    def path(self) -> Path:
        """The resolved output folder (see :func:`resolve_out`)."""
        return self._abs

    def __enter__(self) -> Publisher:
        return self

    def __exit__(self, kind, exc, tb) -> None:
        with held_signals(deliver=exc is None):
            self._close()
        if isinstance(exc, Interrupted):
            done = "had already been published" if self._published else "left as it was"
            raise Interrupted(f"interrupted; {self.out} {done}", exc.signum) from None

    def folder(self, name: str) -> Path:
        """A new empty folder for the files of profile ``name``.

        Raises :class:`ProfileError` for a name given twice or not one safe path component:
        letters, digits, ``-``, ``_``, ``.``, not starting with ``.``.
        """
        if not isinstance(name, str) or not _NAME.fullmatch(name):
            raise ProfileError(f"name = {name!r}: must be letters, digits, '-', '_', '.', not starting with '.'")
        if name.casefold() == "index.html":
            raise ProfileError(f"name = {name!r}: reserved for the build's own page over every profile")
        if name in self._names:
            raise ProfileError(f"name = {name!r}: two profiles build into the same folder")
        if self._published:
            raise GearcadError(f"{self.out}: already published")
        if self._root is None:
            self._start()
        path = self._tree / name
        path.mkdir(parents=True)
        self._names.append(name)
        return path

    def _start(self) -> None:
        _clean(_nearest(self._abs.parent))
        if self._abs.is_dir():
            lock = _lock(self._abs, wait=True)  # not while another build publishes
            try:
                _clean(self._abs, repair=True)
            finally:
                os.close(lock)
        parent = _nearest(self._abs)
        with held_signals():  # an interrupt must not leave it unrecorded
            self._root, fd = _new_staging(parent)
            self._fds.append(fd)
        self._tree = self._root.joinpath(*self._abs.relative_to(parent).parts[1:])

    def commit(self) -> None:
        """Publish every staged folder into ``out``, each atomically, then delete the staging.

        With no folder staged nothing is published (``out`` is not created).
        """
        if self._published:
            raise GearcadError(f"{self.out}: already published")
        with held_signals():
            try:
                if self._names and (self._root.parent == self._abs or not self._publish_tree()):
                    self._publish_folders()
            except OSError as exc:
                raise OutputError(f"--out {self.out}: cannot publish {exc.filename} ({exc.strerror})") from None
            self._published = True
            self._close()

    def _publish_tree(self) -> bool:
        """Publish the missing part of the path, ``out`` in it, by one rename; ``False`` if out exists."""
        ancestor = self._root.parent
        parts = self._abs.relative_to(ancestor).parts
        for depth in range(1, len(parts) + 1):
            try:
                os.rename(self._root.joinpath(*parts[1:depth]), ancestor.joinpath(*parts[:depth]))
            except OSError as exc:
                if exc.errno not in (errno.EEXIST, errno.ENOTEMPTY):
                    raise
                continue  # made meanwhile, by another build or by hand
            if depth == 1:
                self._root = None  # it is part of the published path now
            return True
        return False

    def _publish_folders(self) -> None:
        lock = _lock(self._abs, wait=True)  # one build publishes into out at a time
        try:
            if self._root.parent != self._abs:  # staged in an ancestor, but out has appeared since
                root, fd = _new_staging(self._abs)
                self._fds.append(fd)
                for name in self._names:
                    os.rename(self._tree / name, root / name)
                shutil.rmtree(self._root, ignore_errors=True)
                self._root = self._tree = root
            for i, name in enumerate(self._names):
                try:
                    _swap(self._root / name, self._abs / name)
                except OSError as exc:
                    done = f"{i} of {len(self._names)} replaced"
                    raise OutputError(f"{self.out / name}: cannot publish ({exc.strerror}); {done}") from None
        finally:
            os.close(lock)

    def _close(self) -> None:
        if self._root is not None:
            shutil.rmtree(self._root, ignore_errors=True)
            self._root = None
        while self._fds:
            os.close(self._fds.pop())


def _swap(staged: Path, target: Path) -> None:
    """Put ``staged`` at ``target`` in one step; what was there stays in the staging folder."""
    if not os.path.lexists(target):
        os.rename(staged, target)
    elif not _exchange(staged, target):  # two renames; a kill between them is repaired by _clean
        os.rename(target, staged.parent / f".old-{target.name}")
        os.rename(staged, target)
