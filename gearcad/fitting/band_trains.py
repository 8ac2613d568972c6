"""The bands of a carrier train's meshes (each, the ring's included) and of a toothed body's
rollers, with each mesh's contact ratio and working pressure angle (:mod:`.band_mesh` measures).

A carrier train's gears are circles turning about fixed centres in the carrier's frame: gear k
turned by Δ turns gear k + 1 by ∓Δ·r_k/r_{k+1} (external −, internal +), and the positions step
gear k by one pitch and a fraction over its turn, so they visit teeth all round and every phase
of a pitch.  On circles the working pressure angle is the rack's α everywhere and the contact
ratio is the textbook ε_α (a ring's tip circle is concave: :func:`~..teeth.contact.contact_ratio`).

A roller rolls on the body's pitch curve: in the body's frame its axle follows the curve's
parallel at its pitch radius ρ, and as the contact moves an arc δs along the body the roller
turns δs/ρ, from the assembled phase.  Its axle is fixed on the frame, so the tooth force, along
the line of action through the pitch point, makes α with the velocity both pitch points share:
the working pressure angle is α on both flanks; the contact ratio follows the body's curvature.
The positions step the body evenly over a turn; the tight case's least play is proven between
positions as a pair's is, for the roller's moving axle (:mod:`.moving`), and a train mesh's as a
pair's about fixed centres (:func:`fixed_pair`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import shapely
import shapely.affinity

from ..findings import finding
from ..mechanisms.registry import MECHANISMS
from ..teeth.contact import ContactData, contact_ratio
from .band import Band, pair_band
from .band_mesh import MeshGeometry, mesh_band
from .certify import PER_TOOTH
from .fit import least_said, process_block
from .moving import MovingMesh, moving_band
from .play import PairGeometry
from .written import written_regions, written_shapes

__all__ = ["MeshBand", "mesh_bands", "radial_room", "with_mesh_bands", "train_meshes", "roller_meshes"]

TWO_PI = 2 * math.pi
_CLEARANCE = 0.25
"""Radial clearance of the standard rack these teeth are cut by (dedendum 1.25 less addendum 1), × module."""


@dataclass(frozen=True)
class MeshBand:
    """A mesh's band, whether it is internal, and its contact along the positions."""

    band: Band
    internal: bool
    contact: ContactData

    def as_dict(self) -> dict:
        """report.json's ``bands[]`` entry: the pair's keys, the centre-distance change that frees
        it signed (an internal mesh: negative, the centres closer), ``internal`` and ``contact``."""
        out = self.band.as_dict()
        if self.internal:
            out["center_distance_change"] = -out["center_distance_change"]
        return {**out, "internal": self.internal, "contact": self.contact.as_dict()}

    def sentence(self) -> str:
        c = self.contact
        return (
            f"contact {self.band.mesh}: ratio {c.ratio.min():.3f}…{c.ratio.max():.3f}, working pressure angle "
            f"{math.degrees(c.pressure_angle.min()):.2f}°…{math.degrees(c.pressure_angle.max()):.2f}°"
        )


def _rotate(points: np.ndarray, angle: np.ndarray) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.column_stack([c * points[:, 0] - s * points[:, 1], s * points[:, 0] + c * points[:, 1]])


def _held(spec) -> shapely.Polygon:
    """A part's outline as the mechanism holds it (its hole with it)."""
    return shapely.Polygon(spec.outer, None if spec.hole is None else [spec.hole])


Meshes = list[tuple[str, MeshGeometry, bool, ContactData]]
"""Each mesh: (name, geometry, internal, contact)."""


def train_meshes(draft, positions: int = 12, *, written: bool = True) -> Meshes:
    """Each mesh of a carrier train: (name, geometry in gear k's frame, internal, contact), the
    parts as the files write them and a cutter leaves them (:mod:`.written`; ``written`` False:
    the outlines the mechanism holds, as its closed forms have them)."""
    from ..mechanisms.carrier_train import layout

    p = draft.params
    sides, alpha = layout(p).sides, p.pressure_angle
    if written:  # the regions the cut paths bound (a pair's proof grows them less the cutter) and the parts made
        regions, cut = written_regions(draft)
        shapes = written_shapes(draft, regions=(regions, cut))
    else:
        shapes = regions = [_held(s) for s in draft.parts]
        cut = 0.0
    out = []
    for k, (kind, (r_from, r_to)) in enumerate(zip(p.meshes, sides)):
        inside = kind == "internal"
        first_ring, second_ring = inside and r_from > r_to, inside and r_from < r_to
        z, m = (p.inner_teeth if k == p.compound else p.teeth[k]), p.modules[k + 1]
        one, two = draft.placements[k], draft.placements[k + 1]
        c1, c2 = np.array(one.offset, dtype=float), np.array(two.offset, dtype=float)
        line = (c2 - c1) / np.hypot(*(c2 - c1))
        contact = c1 + r_from * (-line if second_ring else line)
        i = np.arange(positions)
        turn = (np.floor(i * z / positions) + i / positions) * TWO_PI / z
        a1 = one.angle + turn
        ratio = (r_from / r_to) * (1.0 if inside else -1.0)
        tile = lambda v: np.tile(v, (positions, 1))  # noqa: E731
        material = (math.atan2(*(contact - c1)[::-1]) - a1) / (TWO_PI / z)
        teeth = (np.floor(material) if first_ring else np.round(material)).astype(int) % z
        z2 = p.teeth[k + 1]  # the compound gear meets the gear before it with its outer teeth
        ends = [(regions[k], one, r_from, z), (regions[k + 1], two, r_to, z2)]
        geometry = MeshGeometry(
            shapes=(shapes[k], shapes[k + 1]),
            phi1=turn,
            centre2=_rotate(tile(c2 - c1), -a1),
            angle2=two.angle + ratio * turn - a1,
            contact=_rotate(tile(contact - c1), -a1),
            tighter=_rotate(tile(line if inside else -line), -a1),
            module=m,
            pressure_angle=alpha,
            teeth=teeth,
            pair=fixed_pair(*(ends[::-1] if first_ring else ends), internal=inside, module=m, alpha=alpha, cut=cut),
        )
        k1 = np.full(positions, (-1.0 if first_ring else 1.0) / r_from)
        k2 = np.full(positions, (-1.0 if second_ring else 1.0) / r_to)
        ratio_along = contact_ratio(k1, k2, (m, m), alpha, m)
        flat = np.full(positions, alpha)
        name = f"{draft.parts[k].name}/{draft.parts[k + 1].name}"
        out.append((name, geometry, inside, ContactData(turn, ratio_along, flat, flat)))
    return out


def fixed_pair(one, two, *, internal: bool, module: float, alpha: float, cut: float = 0.0) -> PairGeometry | None:
    """A mesh of two circles about fixed centres as a :class:`~.play.PairGeometry` (what the proven
    certificate measures): ``one`` and ``two`` each (shape about its pivot, placement, pitch
    radius, teeth), ``two`` the ring of an internal mesh; None unless each toothed outline is its
    own vertices turned by a tooth (then one pitch of gear 1 is the whole cycle; otherwise every
    tooth pair would have to meet, z2/gcd(z1, z2) turns: minutes under the proof).  Both shapes are
    turned so that the line of centres lies along x, as assembled; gear 1 turned by −φ turns gear 2
    by φ2 = k·φ, k = r1/r2 (an internal mesh: −r1/r2, the ring the same way), and gear 1's contact
    lies r1 along the line (an internal mesh: −r1, its pitch point away from the ring's centre).
    ``cut``: the shapes are the regions of cut paths and a cutter of that radius runs along them
    (:attr:`~.play.PairGeometry.cut`)."""
    (shape1, place1, r1, z1), (shape2, place2, r2, z2) = one, two
    gap = np.asarray(place2.offset, dtype=float) - np.asarray(place1.offset, dtype=float)
    theta = math.atan2(gap[1], gap[0])
    rings = tuple(
        shapely.affinity.rotate(shape, place.angle - theta, origin=(0.0, 0.0), use_radians=True)
        for shape, place in ((shape1, place1), (shape2, place2))
    )
    k = -r1 / r2 if internal else r1 / r2
    contact = -r1 if internal else r1
    unit = abs(k / (1 + k))  # the instant centre's distance from gear 1's pivot over E (fixed)
    if not (_repeats(shape1.exterior, z1) and _repeats(shape2.interiors[0] if internal else shape2.exterior, z2)):
        return None
    cycle = TWO_PI / z1
    start = np.linspace(0.0, cycle, max(2 * PER_TOOTH, round(PER_TOOTH * z1 * cycle / TWO_PI)), endpoint=False)
    own = (math.pi if internal else 0.0) + theta - place1.angle  # the contact's angle on gear 1 at φ = 0

    def ratio(lo, hi) -> tuple[np.ndarray, ...]:
        n = len(np.atleast_1d(lo))
        # k itself, signed (constant: its largest; 1 + k the turn rate, E/(1 + k) gear 2's radius)
        return tuple(np.full(n, v) for v in (k, unit, 0.0, 0.0, unit))

    def at(phi1: np.ndarray) -> PairGeometry:
        phi1 = np.asarray(phi1, dtype=float)
        return PairGeometry(
            rings=rings,
            center_distance=float(np.hypot(*gap)),
            phi1=phi1,
            phi2=k * phi1,
            r1=np.full(len(phi1), contact),
            module=module,
            pressure_angle=alpha,
            teeth=np.floor(((own + phi1) % TWO_PI) / (TWO_PI / z1)).astype(int) % z1,
            at=at,
            ratio=ratio,
            slope=lambda phi: np.full(np.shape(phi), k),
            cycle=cycle,
            first=start,
            cut=cut,
        )

    return at(start)


def _repeats(ring, teeth: int) -> bool:
    """Whether the toothed ring is its own vertices turned by a tooth, to 1e-9 of its size (then
    a mesh of it repeats every pitch, not only when every tooth pair has met)."""
    xy = np.asarray(ring.coords)[:-1]
    n = len(xy)
    if n % teeth:
        return False
    turned = _rotate(xy, np.full(n, TWO_PI / teeth))
    size = float(np.max(np.abs(xy)))
    shifts = (n // teeth, -n // teeth)
    return any(np.max(np.abs(turned - np.roll(xy, shift, axis=0))) <= 1e-9 * size for shift in shifts)


def roller_meshes(draft, positions: int = 36) -> Meshes:
    """Each roller against a toothed body: (name, geometry in the body's frame, False, contact);
    none when the body has no teeth.  Each geometry's ``pair`` is the roller's
    :class:`~.moving.MovingMesh` (what the proof measures, at any turn of the body).  The parts are
    the outlines the mechanism holds, not yet the written paths: a fuzzed body's written roller
    that did not repeat by a tooth took its proof over 19 turns (40 CPU-s)."""
    p, detail = draft.params, draft.detail
    frame = getattr(detail, "pitch", None)
    if frame is None:
        return []
    teeth = draft.data["teeth"]
    m, z, alpha = teeth["module"], teeth["body_teeth"], p.pressure_angle
    rho = detail.roller_radius * p.scale
    shapes = tuple(_held(s) for s in draft.parts[:2])
    z_r = teeth["roller_teeth"]
    # a body's turn is the whole cycle where the roller is its own vertices turned by a tooth
    # (after it the roller has turned z_b/z_r turns); otherwise until the same roller tooth returns
    turns = 1 if _repeats(shapes[1].exterior, z_r) else z_r // math.gcd(z, z_r)
    cycle = TWO_PI * turns
    out = []
    for k, placed in enumerate(draft.placements[1:]):
        start = TWO_PI * k / 3  # τ runs clockwise, the body's arc s counter-clockwise (u = −τ)
        place = _roller_place(frame, shapes, placed, start, rho, module=m, teeth=z, alpha=alpha)
        turn = TWO_PI * np.arange(positions) / positions
        geometry = place(turn)
        moving = MovingMesh(mesh=geometry, place=place, cycle=cycle, passes=z * turns, arm=rho)
        geometry = replace(geometry, pair=moving)
        s = frame.arc_at(-(start + turn))
        ratio = contact_ratio(frame.curvature(s), np.full(positions, 1 / rho), (m, m), alpha, m)
        flat = np.full(positions, alpha)
        out.append((f"body/roller {k + 1}", geometry, False, ContactData(turn, ratio, flat, flat)))
    return out


def _roller_place(frame, shapes, placed, start: float, rho: float, *, module: float, teeth: int, alpha: float):
    """place(τ) -> the roller that starts at the body's turn ``start`` (rad) as a
    :class:`~.band_mesh.MeshGeometry` at the body's turns τ: its axle ρ out along the normal of
    the body's pitch curve at the contact, turned from its assembled angle by the arc the contact
    has run along the body over ρ (not wrapped: continuous in τ)."""
    length = frame.perimeter

    def arc(u: np.ndarray) -> np.ndarray:  # the body's arc at its curve parameter u, unwrapped
        return frame.arc_at(u) + length * np.floor(u / TWO_PI)

    s0 = float(arc(np.array([-start]))[0])
    _, _, n0 = frame.frame(np.array([s0 % length]))
    phase = math.atan2(-n0[0, 1], -n0[0, 0]) - placed.angle  # the roller's own angle at the contact

    def place(turn: np.ndarray) -> MeshGeometry:
        turn = np.asarray(turn, dtype=float)
        s = arc(-(start + turn))
        back = s0 - s  # the arc the contact has run along the body
        point, _, normal = frame.frame(s % length)
        centre = point + rho * normal  # the body's pitch curve is the axle's path moved in by ρ
        return MeshGeometry(
            shapes=shapes,
            phi1=turn,
            centre2=centre,
            angle2=np.arctan2(-normal[:, 1], -normal[:, 0]) - (phase + back / rho),
            contact=point,
            tighter=-normal,
            module=module,
            pressure_angle=alpha,
            teeth=np.round((s % length) / (math.pi * module)).astype(int) % teeth,
        )

    return place


def mesh_bands(draft) -> tuple[MeshBand, ...]:
    """The band of every mesh of a carrier train or a toothed body under its profile's process
    (none: the play as drawn); () for any other mechanism."""
    measured = MECHANISMS[draft.mechanism].hook("meshes")
    if measured is None:
        return ()
    meshes = measured(draft)
    params = draft.params
    edge, spread = params.process.edge(params.output.chamfer), params.process.center_spread()
    tol, backlash = params.output.tolerance, params.backlash

    def band(name, g, inside=False):
        if isinstance(g.pair, MovingMesh):  # a roller: its axle moves along the body
            kw = {"certificate": params.output.certificate}
            return moving_band(g.pair, edge=edge, spread=spread, tol=tol, backlash=backlash, name=name, **kw)
        if g.pair is not None:  # about fixed centres: the least play certified as a pair's is
            kw = {"internal": inside, "certificate": params.output.certificate}
            return pair_band(g.pair, edge=edge, spread=spread, tol=tol, backlash=backlash, name=name, **kw)
        return mesh_band(g, edge=edge, spread=spread, tol=tol, name=name, backlash=backlash)

    rollers = (draft.data.get("teeth") or {}).get("roller_teeth")  # a body's rollers, alike: one band turned
    if rollers is not None and meshes and _alike(meshes, rollers):
        first = band(*meshes[0][:2])
        bands = [_turned(first, name, TWO_PI * k / 3) for k, (name, *_) in enumerate(meshes)]
    else:
        bands = [band(name, g, inside) for name, g, inside, _ in meshes]
    return tuple(MeshBand(b, inside, contact) for b, (_, _, inside, contact) in zip(bands, meshes))


def _alike(meshes, roller_teeth: int) -> bool:
    """Whether every roller meets the body as the first does a third of a turn later: the same
    point of the body, the axle in the same place, turned by whole teeth (rollers phased as
    designed, positions a multiple of 3).  Then the three bands are one, found at other turns."""
    g0 = meshes[0][1]
    n = len(g0.phi1)
    if n % 3:
        return False
    pitch = TWO_PI / roller_teeth
    for k, (_, g, *_) in enumerate(meshes[1:], start=1):
        ahead = np.roll(np.arange(n), -k * n // 3)
        size = float(np.max(np.abs(g0.centre2)))
        if not (
            np.allclose(g0.centre2[ahead], g.centre2, rtol=0, atol=1e-9 * size)
            and np.allclose(g0.contact[ahead], g.contact, rtol=0, atol=1e-9 * size)
            and np.all(g0.teeth[ahead] == g.teeth)
            and np.allclose(np.remainder(g0.angle2[ahead] - g.angle2 + pitch / 2, pitch) - pitch / 2, 0, atol=1e-9)
        ):
            return False
    return True


def _turned(b: Band, name: str, turn: float) -> Band:
    """The first roller's band as the roller ``turn`` (rad) of the body further on has it."""
    return replace(b, mesh=name, worst_phi=float((b.worst_phi - turn) % TWO_PI))


def radial_room(params, module: float) -> float:
    """What is left of the radial clearance (mm) with both edges at their largest and the
    centres' error taken from it: below the band's margin, the tips reach the mate's roots."""
    process = params.process
    edge = max(0.0, process.edge(params.output.chamfer)[2])
    return _CLEARANCE * module - 2 * edge - process.center_spread()


def _jams(b: Band, internal: bool, key: str, room: float) -> str:
    apart = b.needed_backlash / (2 * math.tan(b.pressure_angle))
    where = f"tooth {b.worst_tooth} of {b.mesh.split('/')[0]} at its turn {math.degrees(b.worst_phi):.1f}°"
    text = (
        f"{b.mesh}: the play falls to {b.band[0]:.4f} mm at {where} (edges {b.edge[2]:+.3f} mm, centres "
        f"{'+' if internal else '−'}{b.center_spread:.3f} mm{', an internal mesh' if internal else ''}); "
        f"it needs at least {b.needed_backlash:.3f} mm more play: "
    )
    if room < 2 * abs(b.margin):
        return text + (
            f"no backlash gives it, the tips reach the mate's roots (the radial clearance, 0.25 module, keeps "
            f"{room:+.3f} mm with both edges {b.edge[2]:+.3f} mm and the centres {b.center_spread:.3f} mm off): "
            f"a larger module, smaller edges (output.chamfer takes the elephant foot off) or a tighter "
            f"process.center_distance_tolerance"
        )
    return text + (
        f"{key} +{b.needed_backlash:.3f} mm, or the centres {apart:.3f} mm {'closer' if internal else 'apart'}, "
        f"or the parts {b.needed_backlash * math.cos(b.pressure_angle) / 4:.3f} mm smaller on each edge"
    )


def with_mesh_bands(draft, bands: tuple[MeshBand, ...] | None = None, *, chosen: bool = False):
    """The draft with its train's or rollers' bands (default: measured here) and contact in the
    report, the checks' lines and the findings (``jams`` an error; ``loose``, ``backlash-fixed``
    warnings), as :func:`.fit.with_bands` does; ``chosen``: gearcad chose the backlash."""
    bands = mesh_bands(draft) if bands is None else bands
    if not bands:
        return draft
    params = draft.params
    table = MECHANISMS[draft.mechanism].backlash_table
    process, key = params.process, f"{table}.backlash"
    findings, lines = list(draft.findings), list(draft.details)
    fixed = "backlash" in getattr(params, table).model_fields_set
    module = min(params.modules) if hasattr(params, "modules") else draft.data["teeth"]["module"]
    room = radial_room(params, module)
    limit = process.value("max_play")
    how = "chosen for the process's worst case" if chosen else ("as given" if fixed else "the default")
    lines.append(f"{key} = {params.backlash:.4f} mm ({how})")
    for mb in bands:
        b = mb.band
        lines.append(
            f"band {b.mesh} ({process.kind}): play {b.nominal[0]:.4f}…{b.nominal[1]:.4f} mm as drawn, "
            f"{b.band[0]:.4f}…{b.band[1]:.4f} mm made; {'fits' if b.fits else 'JAMS'}{least_said(b)}"
        )
        lines.append(mb.sentence())
        if not b.fits:
            findings.append(finding("jams", _jams(b, mb.internal, key, room), b.mesh))
            if fixed and process.kind != "none" and room >= 2 * abs(b.margin):
                need = params.backlash + b.needed_backlash
                findings.append(finding("backlash-fixed", f"{b.mesh}: {key} = {need:.3f} mm keeps the worst case free"))
        if process.kind != "none" and limit and b.band[1] > limit:
            findings.append(
                finding("loose", f"{b.mesh}: the play may reach {b.band[1]:.3f} mm (process.max_play = {limit:g})")
            )
    cut = {"backlash": params.backlash, "backlash_chosen": chosen}
    bands_out = [*draft.data.get("bands", []), *(mb.as_dict() | cut for mb in bands)]
    data = {**draft.data, "bands": bands_out, "process": process_block(process)}
    return replace(draft, findings=tuple(findings), details=tuple(lines), data=data)
