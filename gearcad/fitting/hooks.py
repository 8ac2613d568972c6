"""The fitting's hooks as the mechanisms' registry entries name them (``fit``, ``bands``): each
calls the fitting functions a kind of mesh needs, and none says a mechanism's name."""

from __future__ import annotations

from . import band_nc, band_trains, fit, mesh_fit

__all__ = ["gear_pair_fit", "meshes_fit", "nc_fit"]


def gear_pair_fit(params, design_of):
    """A toothed gear pair as made: the backlash gearcad chooses under the process
    (:func:`.fit.chosen`), the pair's band and then its trains' meshes in the report.  A pair
    that jams under a process gets its remedies, each tried by a full design before it is named
    (:func:`.fit.remedies`; a remedy's own design names none)."""
    from . import design

    draft, bands = fit.chosen(params, design_of)
    # the design chosen: its least pinned down; a remedy's trial needs only its verdict where it
    # fits, and where it jams how far short, as a design reports it (the next try adds that)
    bands = tuple(b if _TRYING and b.fits else b.pinned() for b in bands)
    cures = None
    if bands and not bands[0].fits and params.process.kind != "none" and not _TRYING:
        module = draft.detail.teeth.plan.module
        cures = _tried(lambda: fit.remedies(params, bands[0], design, module))
    teeth = getattr(params, "teeth", None)
    fixed = teeth is not None and "backlash" in teeth.model_fields_set
    chosen = fit.chosen_values(params, draft.params)
    return band_trains.with_mesh_bands(fit.with_bands(draft, bands, cures, fixed, chosen=chosen))


_TRYING: list = []
"""Non-empty while a remedy is being tried: its own jam names none (no remedies of remedies)."""


def _tried(work):
    _TRYING.append(True)
    try:
        return work()
    finally:
        _TRYING.pop()


def meshes_fit(params, design_of):
    """A carrier train's meshes or a toothed body's rollers as made: their backlash chosen under
    the process and their bands measured (:func:`.mesh_fit.chosen`)."""
    return mesh_fit.chosen(params, design_of)


def nc_fit(params, design_of):
    """A noncircular internal pair's or planetary set's meshes as made: their backlash chosen
    under the process and their bands certified over the whole cycle (:func:`.band_nc.nc_fit`)."""
    return band_nc.nc_fit(params, design_of)
