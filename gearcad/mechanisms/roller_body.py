"""Bodies rolling on three rollers (seed 003): contour, exact amplitude limits, kinematics of the
centre, optional teeth (the rollers as pinions), parts and the interference proof."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..bodies import claims as C
from ..bodies import limits as LM
from ..bodies import rollers as RB
from ..errors import DesignError
from ..findings import Finding, finding
from ..geometry.rings import circle_ring
from ..pitch import shapes
from ..profiles import RollerBodyParams
from ..teeth.frame import ParametricFrame, arc_frame
from ..teeth.gear import cut_teeth
from ..teeth.rack import Rack, RackParams
from ..tolerances import budget
from .budget import COARSEST_TOLERANCE, POINT_BUDGET, check_backlash, check_teeth_work
from .chart_data import Blocks
from .finish import Contact, Draft, PartSpec
from .parts import Placement
from .roller_charts import charts as _charts

__all__ = ["RollerBodyDetail", "ToothedBody", "design", "PAPER_M"]

TWO_PI = 2 * math.pi
PAPER_M = (3, 6, 9, 12, 15)
"""The frequencies for which the paper gives its by-eye amplitude limits."""
UNITS = {"length": "mm (body lengths in units of R in 'body')", "speed": "mm/s", "acceleration": "mm/s^2"}


@dataclass(frozen=True)
class RollerBodyDetail:
    oscillation: RB.Oscillation
    roller_radius: float
    """Units of R, after fitting a whole number of teeth."""
    pitch: ParametricFrame | None = None
    """The toothed body's pitch curve (mm, counter-clockwise arc), None without teeth."""


def _oscillation(p: RollerBodyParams) -> RB.Oscillation:
    osc = RB.Oscillation(p.f, p.g) if p.direction == "series" else RB.harmonic(p.direction, p.amplitude, p.m)
    osc.check()
    return osc


def _limits(p: RollerBodyParams) -> dict[int, tuple[float, float]]:
    if p.direction == "series":
        return {}
    return {
        m: (
            RB.amplitude_limit(p.direction, m, r=p.roller_radius, test="convex"),
            RB.amplitude_limit(p.direction, m, r=p.roller_radius, test="simple"),
        )
        for m in sorted({*PAPER_M, p.m})
    }


@dataclass(frozen=True)
class ToothedBody:
    """The body's teeth with the rollers as pinions: the report's numbers (:meth:`block`) and the
    rings and turns the parts are drawn from."""

    body_teeth: int
    roller_teeth: int
    module: float
    backlash: float
    roller_radius: float
    """Units of R, adjusted so that the body carries a whole number of teeth."""
    requested_roller_radius: float
    body_undercut: bool
    roller_undercut: bool
    body_ring: np.ndarray
    roller_ring: np.ndarray
    roller_turns: tuple[float, float, float]
    """Each roller's turn (rad) that meshes it with the body where it stands."""
    pitch: ParametricFrame
    """The body's pitch curve (mm, counter-clockwise arc)."""

    def block(self) -> dict:
        """The report's ``teeth`` block."""
        names = (
            "body_teeth",
            "roller_teeth",
            "module",
            "backlash",
            "roller_radius",
            "requested_roller_radius",
            "body_undercut",
            "roller_undercut",
        )
        return {name: getattr(self, name) for name in names}


def _toothed_body(osc: RB.Oscillation, p: RollerBodyParams) -> ToothedBody:
    """Teeth on the body, the rollers as pinions of pitch radius r (one generating rack).

    The rollers' count fixes the module (m = 2r/z_r); the body's contour is the roller path P
    moved in by r, so its perimeter is P_path − 2πr, and a whole body count z_b needs
    r = P_path·z_r / (2π(z_r + z_b)) — the roller radius is adjusted to it.
    """
    z_r = p.roller_teeth
    u = np.linspace(0, TWO_PI, 2048, endpoint=False)
    path = ParametricFrame(RB.roller_path(osc, -u))  # τ runs clockwise; u = −τ counter-clockwise
    body0 = path.perimeter - TWO_PI * p.roller_radius
    m0 = 2 * p.roller_radius / z_r
    z_b = max(3, int(round(body0 / (math.pi * m0))))
    r = path.perimeter * z_r / (TWO_PI * (z_r + z_b))
    if not RB.is_simple(osc, r=r):
        raise DesignError(f"teeth.roller_count = {z_r}: the roller radius it needs ({r:.4f} R) breaks the contour")
    module = 2 * r * p.scale / z_r
    check_teeth_work([(z_b, module), (3 * z_r, module)], p.output.tolerance, keys="teeth.roller_count / body.scale")
    check_backlash(p.backlash, module, "teeth.backlash")
    frame = ParametricFrame(RB.contour(osc, -u, r=r) * p.scale)
    if not math.isclose(frame.perimeter, z_b * math.pi * module, rel_tol=1e-9):
        raise DesignError("the body's perimeter does not fit its teeth (the contour is not a parallel of its path)")
    fine = budget(p.output.tolerance).fine
    rack = Rack.from_params(RackParams(module=module, pressure_angle=p.pressure_angle, thinning=p.backlash / 2))
    resize = "a larger teeth.roller_count (smaller teeth)"
    body = cut_teeth(frame, rack, z_b, rack.pitch / 2, tolerance=fine, resize=resize)
    roller = cut_teeth(arc_frame(shapes.circle(r * p.scale)), rack, z_r, rack.pitch / 2, tolerance=fine, resize=resize)
    turns = []
    for k in range(3):
        tau = TWO_PI * k / 3
        s_k = float(frame.arc_at(np.array([-tau]))[0])
        space = ((s_k - rack.pitch / 2) / rack.pitch) % 1.0  # 0 where a body space is centred
        centre = RB.roller_path(osc, np.array([tau]))[0] * p.scale
        contact = RB.contour(osc, np.array([tau]), r=r)[0] * p.scale
        theta = math.atan2(*(contact - centre)[::-1])
        # the two curves run opposite ways at the contact, so the tooth pattern is mirrored: a
        # body space centre `space` pitches behind the contact needs a roller tooth centre as far
        # ahead; the roller's spaces sit at arc r·(angle − turn) = pitch/2 + j·pitch
        turns.append(theta - (rack.pitch / 2 + ((0.5 - space) % 1.0) * rack.pitch) / (r * p.scale))
    return ToothedBody(
        body_teeth=z_b,
        roller_teeth=z_r,
        module=module,
        backlash=p.backlash,
        roller_radius=r,
        requested_roller_radius=p.roller_radius,
        body_undercut=body.undercut,
        roller_undercut=roller.undercut,
        body_ring=body.outline.outer,
        roller_ring=roller.outline.outer,
        roller_turns=tuple(turns),
        pitch=frame,
    )


def _body_ring(osc: RB.Oscillation, p: RollerBodyParams, r: float) -> tuple[np.ndarray, np.ndarray]:
    """The plain contour and the roller path, sampled so that chords sag at most the fine
    tolerance where they bend most (sag ≈ κ·ds²/8), counter-clockwise, mm."""
    fine = budget(p.output.tolerance).fine
    probe = np.linspace(0, TWO_PI, 4096, endpoint=False)
    kappa = float(np.max(np.abs(RB.contour_curvature(osc, probe, r=r)))) / p.scale
    ds = math.sqrt(8 * fine / max(kappa, 1e-12))
    length = float(np.sum(np.hypot(*np.diff(RB.contour(osc, probe, r=r), axis=0).T))) * p.scale
    need = 2 * length / ds
    if need > POINT_BUDGET:
        # near the simple limit the offset is a hair from a cusp (r·κ_P → 1): a bend no
        # tolerance within reach can follow; points grow as tolerance^−½
        key, what = (
            (f"body.amplitude = {p.amplitude:g}", "body.amplitude")
            if p.direction != "series"
            else ("body.f / body.g", "terms of body.f / body.g")
        )
        coarser = 1.05 * p.output.tolerance * (need / POINT_BUDGET) ** 2
        raise DesignError(
            f"{key}: the body contour is on the verge of a cusp (its tightest bend has radius {1 / kappa:.2g} mm), "
            f"so drawing it would take about {need / 1e6:.3g} million points (the budget is "
            f"{POINT_BUDGET / 1e6:.1f} million); use a smaller {what} or body.roller_radius"
            + (f", or output.tolerance ≥ {coarser:.2g} mm" if coarser <= COARSEST_TOLERANCE else "")
        )
    tau = np.linspace(0, TWO_PI, max(256, int(math.ceil(need))), endpoint=False)
    body = RB.contour(osc, tau, r=r)[::-1] * p.scale  # τ runs clockwise: reverse for CCW
    return body, RB.roller_path(osc, tau)[::-1] * p.scale


def _checked(p: RollerBodyParams, osc: RB.Oscillation, limits: dict) -> tuple[bool, bool, list[Finding]]:
    """The contour simple (or a one-line refusal) and whether it is convex."""
    r = p.roller_radius
    simple, convex = RB.is_simple(osc, r=r), RB.is_convex(osc, r=r)
    if not simple:
        if p.direction == "series":
            raise DesignError(
                "body.f / body.g: the body contour crosses itself or has cusps; use smaller terms "
                f"or a smaller body.roller_radius (now {r:g})"
            )
        limit = f" (largest simple amplitude for m = {p.m}: {limits[p.m][1]:.6f})" if limits else ""
        raise DesignError(f"body.amplitude = {p.amplitude:g}: the body contour crosses itself or has cusps{limit}")
    concave = "the body contour has concave stretches (it is not an 'oval')"
    return simple, convex, [] if convex else [finding("concave", concave, "body")]


def _body_block(p: RollerBodyParams, limits: dict, simple: bool, convex: bool) -> Blocks:
    """The report's ``body`` block: the profile's body and its contour's limits at its m."""
    return {
        "scale": p.scale,
        "roller_radius": p.roller_radius,
        "direction": p.direction,
        "amplitude": p.amplitude,
        "m": p.m,
        "convex": convex,
        "simple": simple,
        "amplitude_limit_convex": limits[p.m][0] if limits else None,
        "amplitude_limit_simple": limits[p.m][1] if limits else None,
    }


def _centre(p: RollerBodyParams, osc: RB.Oscillation) -> Blocks:
    """The kinematics of the centre at uniform rotation, numerically over one turn, against eq. 11."""
    w = p.rpm * TWO_PI / 60
    t = np.linspace(0.0, TWO_PI / w, 20001)
    _, vel, acc = RB.point_motion(osc, 0.0, 0.0, w=w, t=t)
    vmax, amax = float(np.max(np.hypot(*vel.T))) * p.scale, float(np.max(np.hypot(*acc.T))) * p.scale
    centre: Blocks = {"rpm": p.rpm, "w": w, "v_max": vmax, "a_max": amax}
    if p.direction == "horizontal":
        v_closed, a_closed = RB.centre_extremes(p.amplitude * p.scale, p.m, w)
        centre.update(v_max_closed_form=v_closed, a_max_closed_form=a_closed)
    return centre


def _limits_block(limits: dict) -> Blocks:
    """The exact amplitude limits at the paper's m, beside its by-eye ones and its regression."""
    ms = np.array(PAPER_M)
    conv = np.array([limits[m][0] for m in ms])
    k, logc = np.polyfit(np.log(ms), np.log(conv), 1)
    return {
        "m": ms.tolist(),
        "convex": conv.tolist(),
        "simple": [limits[m][1] for m in ms],
        "paper_by_eye": [0.15, 0.05, 0.025, 0.01, 0.005],
        "paper_regression": [C.EQ4["coefficient"] * m ** C.EQ4["exponent"] for m in ms],
        "power_law_convex": {"coefficient": float(math.exp(logc)), "exponent": float(k)},
    }


def _parts(p: RollerBodyParams, osc: RB.Oscillation, r: float, teeth: ToothedBody | None):
    """The body and the roller (plain or toothed), the three rollers placed, and their contacts."""
    fine = budget(p.output.tolerance).fine
    body, path = _body_ring(osc, p, r)
    roller_circle = circle_ring(r * p.scale, fine)
    # [bore] is the body's shaft; each roller turns on an axle of its own: a pilot hole marks it
    axle = p.bore.model_copy(update={"diameter": 0.0, "keyway_width": 0.0, "keyway_depth": 0.0, "flat": 0.0})
    if teeth is None:
        parts = (PartSpec("body", body, bore=p.bore), PartSpec("roller", roller_circle, bore=axle))
        turns = [0.0, 0.0, 0.0]
        # plain rollers touch the body along their whole rim at most
        contacts = tuple(Contact(0, k, length=TWO_PI * r * p.scale, touch="rolling") for k in (1, 2, 3))
    else:
        parts = (
            PartSpec("body", teeth.body_ring, bore=p.bore, wall=teeth.module, marks=(body,)),
            PartSpec("roller", teeth.roller_ring, bore=axle, marks=(roller_circle,)),
        )
        turns = list(teeth.roller_turns)
        contacts = tuple(
            Contact(0, k, module=teeth.module, radius=r * p.scale, touch="mesh", play=p.backlash) for k in (1, 2, 3)
        )
    centres = [(p.scale * math.sin(a), p.scale * math.cos(a)) for a in (0.0, TWO_PI / 3, 2 * TWO_PI / 3)]
    placements = (Placement("body"),) + tuple(Placement("roller", a, c) for a, c in zip(turns, centres))
    return parts, placements, contacts


def design(p: RollerBodyParams) -> Draft[RollerBodyDetail]:
    """The body, its three rollers and their proof, from a roller-body profile."""
    osc = _oscillation(p)
    r = p.roller_radius
    limits = _limits(p)
    simple, convex, findings = _checked(p, osc, limits)
    data: Blocks = {"body": _body_block(p, limits, simple, convex), "centre": _centre(p, osc)}
    if limits:
        data["limits"] = _limits_block(limits)
    # the paper's printed formulas and statements, each against an independent computation
    w = data["centre"]["w"]
    checks = C.kinematics_checks(a=p.amplitude * p.scale, m=p.m, w=w, radius=p.scale) if p.direction != "series" else []
    checks += C.amplitude_law_checks() + [LM.radius_claim_check(), LM.nodal_points_check()]
    data["paper_checks"] = checks
    findings += [finding(c["code"], c["message"], "body") for c in checks if not c["holds"]]
    if p.direction != "series":
        radii = sorted({*LM.PAPER_RADII, p.roller_radius})
        # both directions for limits_vs_r.png (0.9 CPU-s more than the profile's own: only with charts)
        directions = ("horizontal", "vertical") if p.output.charts else (p.direction,)
        data["limits_vs_r"] = LM.amplitude_limit_table(directions, radii=radii).as_dict()
    summary = (
        f"{'convex' if convex else 'not convex'}, "
        + (f"amplitude limits convex {limits[p.m][0]:.5f} / simple {limits[p.m][1]:.5f} R, " if limits else "")
        + f"centre Vmax {data['centre']['v_max']:.4g} mm/s"
    )
    teeth = _toothed_body(osc, p) if p.roller_teeth else None
    if teeth is not None:
        data["teeth"] = teeth.block()
        summary += f", {teeth.body_teeth}/{teeth.roller_teeth} teeth m = {teeth.module:.4f}"
        if teeth.roller_radius != r:
            findings.append(
                finding(
                    "teeth-fit",
                    f"roller radius {r:g} R adjusted to {teeth.roller_radius:.6f} R so that the body carries "
                    f"a whole number of teeth ({teeth.body_teeth}) of the rollers' module",
                    "body",
                )
            )
        r = teeth.roller_radius
    parts, placements, contacts = _parts(p, osc, r, teeth)
    return Draft(
        params=p,
        mechanism="roller-body",
        summary=summary,
        findings=tuple(findings),
        parts=parts,
        placements=placements,
        contacts=contacts,
        data=data,
        units=UNITS,
        detail=RollerBodyDetail(osc, r, None if teeth is None else teeth.pitch),
        charts=_charts(osc, p, r, data),
        where="body",
    )
