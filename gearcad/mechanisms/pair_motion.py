"""A gear pair's driver fitted to what the user gives: a required motion (the limits teeth set,
the fit, its report block), or measured radii smoothed (the deviation that made)."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from ..errors import DesignError
from ..pitch.curve import TWO_PI, PitchCurve
from ..pitch.motion import MotionFit, MotionLimits, fit_motion, follower_from_ratio, smoothest_law
from ..profiles import GearPairParams, MotionParams

__all__ = ["motion_limits", "motion_law", "motion_block", "motion_phrase", "fitted_blocks"]


def motion_limits(
    params: GearPairParams, *, center_distance: float | None = None, mate_lobes: int | None = None, module=None
) -> MotionLimits:
    """What the teeth (and the bore) need of a law at this centre distance.

    Each pitch radius must reach the teeth's root plus a wall of one module round the bore (as
    the parts are made), so r1 = E·k/(1 + k) ≥ r and E − r1 ≥ r; each convex stretch must have a
    radius of curvature a rack cuts without undercut, m·(h_f − ρ_f(1 − sin α) + |x|)/sin²α.
    Without teeth, the ratio law's own rule: k stays above 2% of its mean (and below 50×).
    ``center_distance``, ``mate_lobes`` and ``module`` replace the profile's (a remedy tried).
    """
    e = params.center_distance if center_distance is None else center_distance
    mean = params.gear1.lobes / (params.gear2_lobes if mate_lobes is None else mate_lobes)
    bore = params.bore.diameter / 2
    t = params.teeth
    if t is None:
        lo = max(0.02 * mean, bore / (e - bore) if bore < e else math.inf)
        return MotionLimits((lo, min(50 * mean, 1 / lo if lo > 0 else math.inf)), 0.0, "2% of the mean ratio")
    # a count sets the module through the perimeter: that of the mean circle, r = E·mean/(1 + mean)
    module = module or t.module or 2 * e * mean / (1 + mean) / t.count
    root = bore + module * (1 + t.dedendum)
    why = f"pitch radius ≥ {root:.4g} mm: the root at module {module:.4g} and a wall of one module round the bore"
    depth = t.dedendum - t.tip_radius * (1 - math.sin(t.pressure_angle)) + abs(t.profile_shift)
    rho = module * depth / math.sin(t.pressure_angle) ** 2
    if root >= e / 2:
        return MotionLimits((math.inf, 0.0), rho, why + f", more than half the centre distance {e:g} mm")
    return MotionLimits((root / (e - root), (e - root) / root), rho, why)


def motion_law(params: GearPairParams) -> MotionFit:
    """The smoothest closing law for ``params.gear1`` (a :class:`MotionParams`); a law that cannot
    be fitted is refused naming the change that lets it be (tried: the fit is redone with it)."""
    psi, key = _follower(params.gear1)
    try:
        return _fit(params, psi, key)
    except DesignError as exc:
        remedy = _lobes_remedy(params, psi, key) or _size_remedy(params, psi, key)
        raise DesignError(f"{exc}{remedy}") from None


def _follower(g: MotionParams) -> tuple[np.ndarray, str]:
    if g.follower_deg is not None:
        return np.radians(np.asarray(g.follower_deg, dtype=float)), "gear1.follower_deg"
    return follower_from_ratio(np.asarray(g.ratio, dtype=float)), "gear1.ratio"


def _fit(params: GearPairParams, psi: np.ndarray, key: str, **change) -> MotionFit:
    e = change.get("center_distance", params.center_distance)
    return fit_motion(
        psi,
        lobes=params.gear1.lobes,
        mate_lobes=change.get("mate_lobes", params.gear2_lobes),
        center_distance=e,
        tolerance=math.radians(params.gear1.tolerance_deg),
        limits=motion_limits(params, **change),
        key=key,
    )


def _fits(params: GearPairParams, psi: np.ndarray, key: str, **change) -> MotionFit | None:
    try:
        return _fit(params, psi, key, **change)
    except DesignError:
        return None


def _lobes_remedy(params: GearPairParams, psi: np.ndarray, key: str) -> str:
    """When the motion turns the follower another fraction of a turn than the lobes give (a 2:1
    reduction with 1:1 lobes): the mate's lobes that give it, offered only when the law then fits."""
    turns = _closing_turns(psi)
    lobes1, lobes2 = params.gear1.lobes, params.gear2_lobes
    if turns is None or abs(turns - lobes1 / lobes2) <= 0.1 * turns:  # a motion that nearly closes: no hint
        return ""
    near = Fraction(turns).limit_denominator(12)
    shown = str(near) if abs(near - turns) <= 0.03 * turns else f"{turns:.3g}"
    asked = f"; the motion turns the follower about {shown} of a turn per driver turn, not "
    asked += f"gear1.lobes/gear2.lobes = {Fraction(lobes1, lobes2)}"
    mate = round(lobes1 / turns)
    if 1 <= mate <= 24 and abs(lobes1 / mate - turns) <= 0.03 * turns:
        fit = _fits(params, psi, key, mate_lobes=mate)
        if fit is not None:
            return asked + f": set gear2.lobes = {mate}, where the law fits within {math.degrees(fit.error):.2g}°"
    return asked


def _closing_turns(psi: np.ndarray) -> float | None:
    """The follower's turns per driver turn the samples ask for: their span, plus the step across
    the seam (from the last sample to the first, a turn on) interpolated from its neighbours'.
    None when the motion does not turn forward."""
    step = np.diff(psi)
    if len(step) < 4:
        return None
    seam = (9 * (step[-1] + step[0]) - (step[-2] + step[1])) / 16  # the cubic through the steps about it
    turns = (psi[-1] - psi[0] + seam) / TWO_PI
    return float(turns) if turns > 0 else None


def _size_remedy(params: GearPairParams, psi: np.ndarray, key: str) -> str:
    """When the teeth keep the law from the motion (their roots narrow the ratio range, their
    module sets the smallest radius of curvature a rack cuts): the smallest centre distance
    (whole mm, the module as given) and the largest module (hundredths of a mm, at this centre
    distance) at which the smoothest law within the tolerance keeps the limits — each offered
    only when a fit with it succeeds."""
    t = params.teeth
    lobes1, lobes2 = params.gear1.lobes, params.gear2_lobes
    tolerance = math.radians(params.gear1.tolerance_deg)
    law = smoothest_law(psi, lobes=lobes1, mate_lobes=lobes2, tolerance=tolerance) if t is not None else None
    if law is None or law[0] <= 0:
        return ""
    k_lo, k_hi, rho = law  # rho: the smallest convex radius of curvature at a centre distance of 1
    share = min(k_lo / (1 + k_lo), 1 / (1 + k_hi))  # each pitch radius ≥ share·E
    depth = (t.dedendum - t.tip_radius * (1 - math.sin(t.pressure_angle)) + abs(t.profile_shift)) / math.sin(
        t.pressure_angle
    ) ** 2  # a rack cuts a convex stretch of curvature radius ≥ module·depth
    e, bore = params.center_distance, params.bore.diameter / 2
    options = []
    if t.module:  # a count would grow the module with the centre distance
        root = bore + t.module * (1 + t.dedendum)
        wider = math.ceil(max(root / share, t.module * depth / rho if rho > 0 else math.inf) * (1 + 1e-9))
        if wider <= _FARTHEST * e and _fits(params, psi, key, center_distance=float(wider)):
            options.append(f"pair.center_distance = {wider}")
    module = min((e * share - bore) / (1 + t.dedendum), e * rho / depth)
    module = math.floor(module * 100 * (1 - 1e-9)) / 100
    given = t.module or 2 * e * lobes1 / (lobes1 + lobes2) / t.count
    if module * _FARTHEST >= given and _fits(params, psi, key, module=module):
        if t.module:
            options.append(f"teeth.module = {module:g}")
        else:  # the count sets the module: m = 2E·mean/(1 + mean)/count
            options.append(f"teeth.count = {math.ceil(2 * e * lobes1 / (lobes1 + lobes2) / module)}")
    return f"; it fits with {' or '.join(options)}" if options else ""


_FARTHEST = 10
"""A centre distance more than this many times the profile's, or a module less than its share,
is not offered: the law the motion needs is then too rough for teeth (a motion that does not
close, samples too coarse)."""


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


def motion_phrase(block: dict) -> str:
    """The fitted motion's error for a summary line: the report's ``motion`` block in words."""
    return f"motion error {block['error_deg']:.2g}° (allowed {block['tolerance_deg']:g}°, order {block['order']})"


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
