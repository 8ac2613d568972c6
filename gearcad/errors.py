"""Exception hierarchy: every failure a user can cause is a :class:`GearcadError`."""

__all__ = ["GearcadError", "ProfileError", "DesignError"]


class GearcadError(Exception):
    """Base class of every error gearcad raises on purpose."""


class ProfileError(GearcadError, ValueError):
    """A profile value is missing, unknown, of the wrong type or out of range.

    The message names the key, the value and what is allowed, on one line.
    """


class DesignError(GearcadError):
    """The profile is well formed but describes something that cannot be made."""
