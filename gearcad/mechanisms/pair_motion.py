"""A gear pair's driver fitted to what the user gives: a required motion (the limits teeth set,
the fit, its report block), or measured radii smoothed (the deviation that made)."""

from __future__ import annotations

import math

import numpy as np

from ..pitch.curve import PitchCurve
from ..pitch.motion import MotionFit, MotionLimits, fit_motion, follower_from_ratio
from ..profiles import GearPairParams, MotionParams

__all__ = ["motion_limits", "motion_law", "motion_block", "fitted_blocks"]


def motion_limits(params: GearPairParams) -> MotionLimits:
    """What the teeth (and the bore) need of a law at this centre distance.

    Each pitch radius must reach the teeth's root plus a wall of one module round the bore (as
    the parts are made), so r1 = E·k/(1 + k) ≥ r and E − r1 ≥ r; each convex stretch must have a
    radius of curvature a rack cuts without undercut, m·(h_f − ρ_f(1 − sin α) + |x|)/sin²α.
    Without teeth, the ratio law's own rule: k stays above 2% of its mean (and below 50×).
    """
    e, mean = params.center_distance, params.gear1.lobes / params.gear2_lobes
    bore = params.bore.diameter / 2
    t = params.teeth
    if t is None:
        lo = max(0.02 * mean, bore / (e - bore) if bore < e else math.inf)
        return MotionLimits((lo, min(50 * mean, 1 / lo if lo > 0 else math.inf)), 0.0, "2% of the mean ratio")
    # a count sets the module through the perimeter: that of the mean circle, r = E·mean/(1 + mean)
    module = t.module or 2 * e * mean / (1 + mean) / t.count
    root = bore + module * (1 + t.dedendum)
    why = f"pitch radius ≥ {root:.4g} mm: the root at module {module:.4g} and a wall of one module round the bore"
    depth = t.dedendum - t.tip_radius * (1 - math.sin(t.pressure_angle)) + abs(t.profile_shift)
    rho = module * depth / math.sin(t.pressure_angle) ** 2
    if root >= e / 2:
        return MotionLimits((math.inf, 0.0), rho, why + f", more than half the centre distance {e:g} mm")
    return MotionLimits((root / (e - root), (e - root) / root), rho, why)


def motion_law(params: GearPairParams) -> MotionFit:
    """The smoothest closing law for ``params.gear1`` (a :class:`MotionParams`)."""
    g: MotionParams = params.gear1
    if g.follower_deg is not None:
        psi, key = np.radians(np.asarray(g.follower_deg, dtype=float)), "gear1.follower_deg"
    else:
        psi, key = follower_from_ratio(np.asarray(g.ratio, dtype=float)), "gear1.ratio"
    return fit_motion(
        psi,
        lobes=g.lobes,
        mate_lobes=params.gear2_lobes,
        center_distance=params.center_distance,
        tolerance=math.radians(g.tolerance_deg),
        limits=motion_limits(params),
        key=key,
    )


def motion_block(fit: MotionFit, params: GearPairParams) -> dict:
    """The report's ``motion`` block: what was asked, what the law achieves."""
    return {
        "source": "follower_deg" if params.gear1.follower_deg is not None else "ratio",
        "samples": len(params.gear1.follower_deg or params.gear1.ratio),
        "tolerance_deg": params.gear1.tolerance_deg,
        "error_deg": math.degrees(fit.error),
        "order": fit.order,
        "harmonics": len(fit.harmonics),
        "ratio_min": fit.ratio_range[0],
        "ratio_max": fit.ratio_range[1],
        "min_curvature_radius": fit.min_curvature_radius,
    }


def fitted_blocks(data: dict, params: GearPairParams, driver: PitchCurve, fit: MotionFit | None) -> None:
    """Add to a report's ``data`` the ``motion`` block, or gear 1's ``smoothing`` block: the
    largest distance of the smoothed curve from the given radii, mm."""
    if fit is not None:
        data["motion"] = motion_block(fit, params)
        return
    given = np.asarray(params.gear1.radii, dtype=float)
    at = driver.r(np.arange(len(given)) * (2 * np.pi / len(given)))
    data["gears"][0]["smoothing"] = {
        "allowed": params.gear1.smoothing,
        "deviation": float(np.max(np.abs(at - given))),
    }
