"""The profile as it will be cut (:func:`made`): the process's cutter width and, for a gear pair
that leaves ``teeth.backlash`` out, the backlash by the closed form (:func:`needed_backlash`)."""

from __future__ import annotations

import math

from ..mechanisms.registry import MECHANISMS

__all__ = ["chose_backlash", "made", "needed_backlash", "process_of", "sliver", "writing_play"]


def process_of(params):
    return getattr(params, "process", None)


def writing_play(params) -> float:
    """What the writing tolerance can take from a pair's play (mm on the pitch curve): each written
    outline strays up to ``output.tolerance`` towards its mate, on both flanks of a tooth space:
    4·tol/cos α."""
    return 4 * params.output.tolerance / math.cos(params.teeth.pressure_angle)


def needed_backlash(params) -> float:
    """The backlash the closed form asks for (mm): under a process 4·δ/cos α for the edges,
    2·Δa·tan α for the centres, and the band's margin (2·tol) with a quarter of a tolerance to
    spare, less what ``teeth.clearance`` leaves (4·c/cos α); with none, what the writing can take
    (:func:`writing_play`) and the mesh proof's
    allowed bite (its depth 2·tol, over cos α), less what ``teeth.clearance`` leaves."""
    process, teeth = process_of(params), getattr(params, "teeth", None)
    if teeth is None:
        return 0.0
    alpha, tol = teeth.pressure_angle, params.output.tolerance
    if process is None or process.kind == "none":
        return max(0.0, 1.5 * writing_play(params) - 4 * teeth.clearance / math.cos(alpha))
    edge = max(0.0, process.edge(params.output.chamfer)[2])
    need = 4 * edge / math.cos(alpha) + 2 * process.center_spread() * math.tan(alpha) + 9 * tol / 4
    return max(0.0, need - 4 * teeth.clearance / math.cos(alpha))  # the clearance moved every flank in


def chose_backlash(params) -> bool:
    """Whether gearcad chooses this profile's backlash: a gear pair with teeth that leaves
    ``teeth.backlash`` out (with no process: the play the writing tolerance needs)."""
    teeth = getattr(params, "teeth", None)
    return (
        MECHANISMS[params.mechanism].play == "pair" and teeth is not None and "backlash" not in teeth.model_fields_set
    )


def sliver(module: float | None) -> float:
    """The backlash (mm) at which teeth of ``module`` keep under half their thickness (a quarter
    pitch less 80 % of it): the band asking for more means the tips reach the mate's roots, and
    no backlash frees them.  Infinite for teeth given by count (no module yet)."""
    return 0.8 * math.pi * module / 2 if module else math.inf


def made(params, backlash: float | None = None):
    """The profile as it will be cut: ``output.kerf`` the process's cutter width, and (a gear
    pair that leaves ``teeth.backlash`` out) the backlash ``backlash``, by default the closed
    form's (:func:`needed_backlash`)."""
    process = process_of(params)
    update = {}
    if process is not None and process.kind != "none":
        update["output"] = params.output.model_copy(update={"kerf": process.cutter(params.output.kerf)})
        bore = getattr(params, "bore", None)
        if process.kind == "cnc" and bore is not None and "pilot" not in bore.model_fields_set:
            # a router cuts no hole narrower than its tool: the default pilot gives way to the cross
            update["bore"] = bore.model_copy(update={"pilot": 0.0})
    if chose_backlash(params):
        chosen = needed_backlash(params) if backlash is None else backlash
        update["teeth"] = params.teeth.model_copy(update={"backlash": chosen})
    return params.model_copy(update=update) if update else params
