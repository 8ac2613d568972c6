"""The fitting's hooks as the mechanisms' registry entries name them (``fit``, ``bands``): each
calls the fitting functions a kind of mesh needs, and none says a mechanism's name."""

from __future__ import annotations

from . import band_trains, fit, mesh_fit

__all__ = ["gear_pair_fit", "meshes_fit"]


def gear_pair_fit(params, design_of):
    """A toothed gear pair as made: the backlash gearcad chooses under the process
    (:func:`.fit.chosen`), the pair's band and then its trains' meshes in the report."""
    draft, bands = fit.chosen(params, design_of)
    return band_trains.with_mesh_bands(fit.with_bands(draft, bands))


def meshes_fit(params, design_of):
    """A carrier train's meshes or a toothed body's rollers as made: their backlash chosen under
    the process and their bands measured (:func:`.mesh_fit.chosen`)."""
    return mesh_fit.chosen(params, design_of)
