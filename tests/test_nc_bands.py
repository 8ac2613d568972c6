"""The bands of the noncircular internal pair's and planetary set's meshes (gearcad.fitting.band_nc):
their geometry checked on circles against the closed forms (the play is the backlash on the pitch
circle; a centre error Δa the tight way takes 2·Δa·tan α), the certificate's bound against a
function whose least value is known, and bad sets refused in one line."""

import math

import numpy as np
import pytest

from gearcad.fitting import band_nc
from gearcad.fitting.band_mesh import mesh_play
from gearcad.mechanisms import nc_internal, nc_planetary
from gearcad.profiles import validated
from gearcad.profiles.nc_internal import NcInternalParams
from gearcad.profiles.nc_planetary import NcPlanetaryParams

OUTPUT = {"tolerance": 0.01, "charts": False, "animation": False}
TAKEN = 2 * 0.05 * math.tan(math.radians(20))
"""What 0.05 mm of centre distance the tight way takes from a spur mesh's play (2·Δa·tan α)."""


def _plays(draft, every: int):
    out = {}
    for mesh in band_nc.nc_meshes(draft):
        g = mesh.at(mesh.first[::every])
        out[mesh.name] = [mesh_play(g, (0.0, 0.0), shift, 0.01, reach=1.0) for shift in (0.0, 0.05)]
    return out


def test_a_circular_set_plays_its_backlash_and_the_centres_take_two_tan_alpha():
    """e = 0: sun, planets and ring are spur gears (the ring closes at 3n lobes with no sun of its
    own: the circular set), so both meshes play the 0.2 mm backlash on the pitch circles, and
    moving the planet 0.05 mm the tight way (into the sun; out, away from the ring's centre) takes
    2·0.05·tan 20° from each — the internal mesh's tight way is the centres apart."""
    p = validated(
        NcPlanetaryParams, set={"lobes": 4, "e": 0.0, "radius": 8.0, "planets": 4}, teeth={"count": 12}, output=OUTPUT
    )
    draft = nc_planetary.design(p)
    assert draft.data["set"]["sun_e"] == 0.0 and draft.data["set"]["closure_residual"] <= 1e-12
    plays = _plays(draft, 4)
    assert set(plays) == {"sun/planet", "planet/ring"}
    for free, tight in plays.values():
        assert free == pytest.approx(0.2, abs=0.01)
        assert free - tight == pytest.approx(TAKEN, abs=0.004)


def test_a_circle_in_a_two_lobe_ring_plays_its_backlash_the_same_way():
    """The internal spur pair (a circle in a "two-lobe" ring): the play is the 0.1 mm backlash,
    and the ring's centre moved 0.05 mm away from the pinion's takes 2·0.05·tan 20°."""
    p = validated(
        NcInternalParams,
        name="nci",
        mechanism="nc-internal",
        pinion={"name": "pinion", "curve": "circle", "radius": 15.0},
        ring={"lobes": 2},
        teeth={"count": 24, "backlash": 0.1},
        output=OUTPUT,
    )
    (free, tight), *more = _plays(nc_internal.design(p), 48).values()
    assert not more
    assert free == pytest.approx(0.1, abs=0.01)
    assert free - tight == pytest.approx(TAKEN, abs=0.004)


def test_the_certificate_bounds_a_known_least_value():
    """A play of 0.3 + 0.1·cos 5φ − 0.05·cos 11φ (least 0.1529, between positions), from 24 even
    positions (two a lobe of the fastest wave), to be proven above a margin of 0.12: the
    certified bound lies under the true least value and over the margin, and the least measured
    is the bound plus its slack."""
    play = lambda phi: 0.3 + 0.1 * np.cos(5 * phi) - 0.05 * np.cos(11 * phi)  # noqa: E731
    dense = np.linspace(0.0, 2 * math.pi, 2_000_001)
    least = float(play(dense).min())
    first = np.linspace(0.0, 2 * math.pi, 24, endpoint=False)
    phi, measured, cert = band_nc.certify(play, first, 2 * math.pi, module=1.0, tol=0.001, margin=0.12)
    assert cert.proven and len(phi) == cert.positions > 24
    assert 0.12 <= cert.lower <= least <= float(measured.min())
    assert float(measured.min()) - cert.lower == pytest.approx(cert.slack)


def test_planets_that_would_touch_are_refused_in_one_line():
    """Six planets round a six-lobe sun of the same curve: neighbours' pitch curves 2R·(1 + …)
    apart nearly touch (circles: exactly), and their tips, an addendum out each, would."""
    from gearcad.errors import DesignError

    p = validated(
        NcPlanetaryParams, set={"lobes": 6, "e": 0.01, "radius": 12.0, "planets": 6}, teeth={"count": 24}, output=OUTPUT
    )
    with pytest.raises(DesignError, match=r"^set.planets = 6: neighbouring planets' tips would touch .*: use fewer"):
        nc_planetary.design(p)


def test_the_fdm_fit_presets_are_the_makers_and_need_a_printer():
    """process.fit: the published fits (normal backlash, tip clearance) — the backlash on the pitch
    curve is the normal one over cos α — refused without process.kind = "fdm", and by a mechanism
    whose fit does not take it (a gear pair), each in one line naming the key."""
    from gearcad import api
    from gearcad.errors import GearcadError, ProfileError
    from gearcad.profiles.process import ProcessParams

    alpha = math.radians(20)
    for name, (normal, tip) in {"tight": (0.22, 0.08), "standard": (0.32, 0.14), "loose": (0.44, 0.22)}.items():
        backlash, clearance = validated(ProcessParams, kind="fdm", fit=name).preset(alpha)
        assert backlash * math.cos(alpha) == pytest.approx(normal, abs=1e-15) and clearance == tip
    with pytest.raises(ProfileError, match=r"^fit = 'standard': a printer's fit preset needs process.kind = 'fdm'"):
        validated(ProcessParams, kind="laser", fit="standard")
    spur = api.load_profile("profiles/spur_pair.toml", {"process.kind": "fdm", "process.fit": "tight"})
    with pytest.raises(GearcadError, match=r"^process.fit = 'tight': a gear-pair takes no printer's fit preset"):
        api.design(spur)


def test_a_ring_no_sun_closes_is_refused_in_one_line():
    """Four planets of e = 0.05 in a 16-lobe ring: the natural lobe count is about 12.01 and no sun
    eccentricity within convexity brings it to 16; refused naming set.e, its value and the count."""
    from gearcad.errors import DesignError

    p = validated(
        NcPlanetaryParams,
        set={"lobes": 4, "e": 0.05, "radius": 12.0, "planets": 4, "ring_lobes": 16},
        teeth={"count": 16},
        output=OUTPUT,
    )
    with pytest.raises(DesignError, match=r"^set.e = 0.05: no sun eccentricity .* at 16 lobes .* lobe count 12.0"):
        nc_planetary.design(p)


def test_a_spike_of_no_width_is_cut_like_a_loop():
    """The lobed sun's flank at backlash 0.3 (nc_square.toml) ran out to a vertex and back beside
    itself, 0.2 µm off its outgoing segment: no crossing, so no loop, but a spike a chamfer's
    inset crosses itself on.  The vertices are the sun's (mm)."""
    from gearcad.teeth.loops import remove_loops_each

    flank = np.array([[14.024086, 10.774451], [14.140218, 10.903768], [14.089339, 10.847426], [14.210684, 11.028043]])
    line = np.vstack([[13.784268, 10.4651], [13.928924, 10.659712], flank, [14.312155, 11.196619]])
    (cut, loops), (plain, none) = remove_loops_each([line, np.delete(line, 3, axis=0)])
    assert loops == 1 and none == 0
    assert np.array_equal(cut, plain)  # the spike's tip gone, nothing else
