"""Exception hierarchy: every failure a user can cause is a :class:`GearcadError`."""

__all__ = ["GearcadError", "ProfileError", "DesignError", "OutputError", "ChecksFailed", "shown"]


class GearcadError(Exception):
    """Base class of every error gearcad raises on purpose."""


class ProfileError(GearcadError, ValueError):
    """A profile value is missing, unknown, of the wrong type or out of range.

    The message names the key, the value and what is allowed, on one line.
    """


class DesignError(GearcadError):
    """The profile is well formed but describes something that cannot be made."""


class OutputError(GearcadError):
    """A file could not be written or published (disk full, no permission, a read-only file
    system): the message names the path and the system's reason; nothing is published."""


class ChecksFailed(GearcadError):
    """A design was made but a check failed (an error finding not allowed): exit status 3.

    ``findings`` holds the failing findings (``gearcad.findings.Finding``)."""

    exit_code = 3

    def __init__(self, message: str, findings: tuple = ()):
        super().__init__(message)
        self.findings = findings


def shown(text) -> str:
    """A path for a one-line message: control characters escaped, at most 200 characters."""
    escaped = str(text).encode("unicode_escape", "backslashreplace").decode("ascii")
    return escaped if len(escaped) <= 200 else escaped[:100] + "…" + escaped[-99:]
