"""gearcad: noncircular gear pairs from TOML profiles to DXF, charts and a checked report.

The pipeline runs one way: ``profiles`` (TOML → parameters) → ``pitch`` (pitch curves,
synthesis, closure, kinematics) → ``design`` (checks) → ``export`` (files).
"""

__version__ = "0.1.0"
__all__ = ["__version__"]
