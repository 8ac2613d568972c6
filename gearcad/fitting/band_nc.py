"""The bands of the noncircular internal pair's mesh and of a carrier-less planetary set's meshes
(sun–planet, planet–ring), their least play certified over the whole cycle, and the backlash
chosen under a process (issue 38).

Each mesh is a :class:`~.band_mesh.MeshGeometry` at any driver angle (``at(phi)``): gear 1's own
frame, gear 2's pivot, turn and the pitch point there.

* The internal pair: the pinion (gear 1) turns by −φ1 about O, the ring by −φ2(φ1) about (−E, 0)
  (:mod:`gearcad.pitch.internal`); in the pinion's frame the ring's pivot is −E·u, u = (cos φ1,
  sin φ1), its turn φ1 − φ2, the pitch point r1(φ1)·u.  Both turn the same way.  A centre error
  takes play from an internal mesh with the centres *farther* apart (:mod:`.band_mesh`): the
  ring's pivot moves along −u.  The pitch curves repeat after a pinion lobe (2π/n1: the ring
  turns a ring lobe); where each toothed outline is its own vertices turned by its lobe that is
  the cycle, else n2/gcd(n1, n2) pinion turns (every tooth pair met).
* The planetary set, sun held (:mod:`gearcad.trains.nc_set`): at the sun angle θ the first planet
  is turned β(θ) about its centre C(θ), the ring φ_r(θ) about O.  Sun–planet in the sun's frame:
  the planet's pivot C, its turn β, the pitch point S(θ).  Planet–ring in the planet's frame
  (x ↦ Rot(−β)·(x − C)): the ring's pivot Rot(−β)·(−C), its turn φ_r − β, the pitch point
  Rot(−β)·(P2 − C).  The set repeats after one sun lobe (every toothing invariant under 2π/n),
  and every planet is the first turned by 2π/N: the cycle is one sun lobe, the first planet's
  meshes are all.  The planets float (no carrier): the process's centre tolerance is applied to
  each mesh alone, the worst a ring out of centre by it can do to one planet's either mesh — gear
  2 moved along the pitch curves' common normal at the contact, into the mesh (a shift v takes
  2·tan α·(v·N) from the play to first order: most along N; across N it only turns gear 2, and
  along the line of centres it moved the free turn off the rolling angle: nc_square under a
  laser, the ring measured from a flank at 0.34 rad, "jammed" where 0.036 mm was free).

Each mesh is gear 2 moved rigidly in gear 1's frame by one parameter (the driver angle): a
:class:`~.moving.MovingMesh` (pivot C(φ), turn A(φ), gear 2's pitch radius at the contact changing
along the cycle), its tight case's least play proven between positions by
:func:`~.moving.moving_band` (``output.certificate = "theorem"``, the default; "estimate": the slope
bound of :func:`~.certify.certify`), where each toothed outline repeats by its lobe (checked: then
the mesh a cycle on is the mesh turned, as the proof wraps it); the slope estimate otherwise.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..mechanisms.registry import MECHANISMS
from ..threads import side_by_side
from .band import band_of
from .band_mesh import clip, mesh_play, signed_mesh_play
from .band_trains import MeshBand, radial_room, with_mesh_bands
from .certify import certify
from .fit import smallest_fit
from .made import made, sliver
from .mesh_fit import closed_form, with_backlash
from .moving import moving_band
from .nc_meshes import NcMesh, moving, nc_meshes

__all__ = ["NcMesh", "certify", "nc_meshes", "nc_bands", "nc_fit", "nc_with_bands"]


def _band(mesh: NcMesh, params, *, quick: bool = False):
    """The certified band of one mesh under the profile's process (proven, :func:`moving`);
    ``quick``: the tight case alone at the first positions, not certified between them (the
    backlash search's look)."""
    process, tol = params.process, params.output.tolerance
    edge, spread = process.edge(params.output.chamfer), process.center_spread()
    if not quick and mesh.repeats:
        kind = params.output.certificate
        found = moving_band(
            moving(mesh), edge=edge, spread=spread, tol=tol, backlash=params.backlash, name=mesh.name, certificate=kind
        )
        return MeshBand(found, mesh.internal, mesh.contact)
    g0 = mesh.at(mesh.first)
    alpha = g0.pressure_angle
    grow = max(abs(x) for x in edge)
    m = mesh.module
    reach = params.backlash + 4 * grow / math.cos(alpha) + 2 * spread * math.tan(alpha) + 0.5 * m
    margin = 2 * tol if any(edge) or spread else -4 * tol / math.cos(alpha)

    def signed(phi, e, shift):
        g = mesh.at(phi)
        return signed_mesh_play(g, clip(g, grow + 0.5 * m), e, shift, tol, reach=reach)

    def tight(phi):
        return signed(phi, edge[2], spread)

    stack = any(edge) or spread
    if quick:  # every second first position: the certificate at the end looks at all and between
        first = mesh.first[::2]
        play = tight(first)
        plays = (play, play, play)
        found = band_of(mesh.name, plays, mesh.at(first).teeth, first, edge=edge, spread=spread, tol=tol, alpha=alpha)
        return MeshBand(found, mesh.internal, mesh.contact)
    with side_by_side() as pool:
        job = pool.submit(certify, tight, mesh.first, mesh.cycle, module=m, tol=tol, margin=margin)
        if stack:
            pieces = clip(g0, grow)
            nominal = pool.submit(mesh_play, g0, (edge[0], edge[0]), 0.0, tol, reach=reach, pieces=pieces)
            wide = pool.submit(mesh_play, g0, (edge[1], edge[1]), -spread, tol, reach=reach, pieces=pieces)
            nominal, wide = nominal.result(), wide.result()
        phi, play, cert = job.result()
    if not stack:
        nominal = wide = play
    else:
        more = np.full(len(play) - len(nominal), np.nan)
        nominal, wide = np.concatenate([nominal, more]), np.concatenate([wide, more])
    teeth = mesh.at(phi).teeth
    found = band_of(
        mesh.name, (nominal, play, wide), teeth, phi, edge=edge, spread=spread, tol=tol, alpha=alpha, certificate=cert
    )
    return MeshBand(found, mesh.internal, mesh.contact)


def nc_bands(draft, *, quick: bool = False) -> tuple[MeshBand, ...]:
    """The certified band of every mesh of the draft under its profile's process (``quick``:
    the tight case at the first positions only, :func:`_band`)."""
    return tuple(_band(mesh, draft.params, quick=quick) for mesh in nc_meshes(draft))


def nc_with_bands(draft, bands=None, *, chosen: bool = False):
    """The draft with its meshes' bands in the report, lines and findings (:func:`.band_trains.with_mesh_bands`)."""
    return with_mesh_bands(draft, nc_bands(draft) if bands is None else bands, chosen=chosen)


def _excess(bands) -> float:
    return min(mb.band.least - mb.band.margin for mb in bands)


def _left_out(params) -> bool:
    table = getattr(params, MECHANISMS[params.mechanism].backlash_table)
    return "backlash" not in table.model_fields_set


def chooses(params) -> bool:
    """Whether gearcad chooses the backlash: a process named, no fit preset, ``teeth.backlash``
    left out."""
    return params.process.kind != "none" and params.process.fit is None and _left_out(params)


def _tip_line(draft) -> object:
    """The draft with the fit preset's tip clearance set against the radial room (0.25 module less
    both edges grown and the centres' error) in its report and checks' lines; as it is without one."""
    p = draft.params
    preset = p.process.preset(p.pressure_angle)
    if preset is None:
        return draft
    room = radial_room(p, draft.data["teeth"]["module"])
    line = (
        f"process.fit = {p.process.fit!r}: backlash {preset[0]:.4f} mm on the pitch curves (normal "
        f"{preset[0] * math.cos(p.pressure_angle):.2f}), tip clearance {preset[1]:.2f} mm against a radial room of "
        f"{room:.3f} mm ({'kept' if room >= preset[1] else 'NOT kept'})"
    )
    data = {**draft.data, "fit_preset": {"name": p.process.fit, "backlash": preset[0], "tip_clearance": preset[1]}}
    data["fit_preset"]["radial_room"] = room
    return replace(draft, details=(*draft.details, line), data=data)


def nc_fit(given, design_of):
    """The draft as made under the process, its meshes' bands measured and certified, the
    backlash chosen (the smallest that keeps every mesh's worst case free by the margin, as
    :func:`.mesh_fit.chosen` chooses a train's) when the profile leaves it out."""
    params = made(given)
    preset = given.process.preset(given.pressure_angle)
    if preset is not None and _left_out(given):
        params = with_backlash(params, preset[0])
    if not chooses(given):
        return _tip_line(nc_with_bands(design_of(params)))
    tol = params.output.tolerance
    draft = design_of(with_backlash(params, closed_form(params)))
    module = draft.data["teeth"]["module"]

    def cut(backlash: float):
        d = design_of(with_backlash(params, backlash))
        found = nc_bands(d, quick=True)
        return d.params.backlash, _excess(found), (d, found)

    if radial_room(params, module) >= 2 * tol:  # else no backlash frees it: the closed form's flanks
        first = (draft.params.backlash, _excess(quick := nc_bands(draft, quick=True)), (draft, quick))
        draft, _ = smallest_fit(first, cut, tol, limit=sliver(module))  # looks at the first positions
        bands = nc_bands(draft)  # certified: between the positions it may ask a little more, once
        short = -_excess(bands)
        if short > 0 and draft.params.backlash + short + tol < sliver(module):
            draft = design_of(with_backlash(params, draft.params.backlash + short + tol / 4))
            bands = nc_bands(draft)
        return nc_with_bands(draft, bands, chosen=True)
    return nc_with_bands(draft, nc_bands(draft), chosen=True)
