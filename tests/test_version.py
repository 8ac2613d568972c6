"""One version number: the package's, which the installed metadata reads."""

from importlib.metadata import version

import gearcad


def test_the_installed_version_is_the_packages():
    assert version("gearcad") == gearcad.__version__
