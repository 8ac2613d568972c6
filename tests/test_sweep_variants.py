"""A sweep's designs' parameters made from the profile validated once (sweeps/variants.py) are
those ``parse_profile`` makes of the overridden data — every field, default and set key — and a
bad override is refused in its words; a row taken from the design (evaluate.scalars) is the
flattened report."""

import tomllib

import pytest
from pydantic import BaseModel

from gearcad.fitting import design
from gearcad.profiles.reading import parse_profile
from gearcad.sweeps.evaluate import flatten, overridden, scalars
from gearcad.sweeps.variants import Variants

from .conftest import ROOT

CASES = {
    "elliptic_focus": [
        {"gear1.eccentricity": 0.3},  # b given: the override removes it, the validator fills it
        {"gear1.eccentricity": 0.3, "teeth.count": 41},  # teeth.module removed
        {"gear1.a": 30, "gear1.b": 10},  # an int validated to a float
        {"gear1.pivot": "centre", "gear2.lobes": 2},
        {"gear1.curve": "oval"},  # another model of the union
        {"pair.center_distance": 50.0},
        {"gear2.name": "Driver"},  # a rule between tables (names differ, ignoring case)
        {"pair.driver": "nobody"},
        {"gear1.eccentricity": 0.999},  # out of range
        {"gear1.eccentricity": "x"},
        {"gear1.bogus": 1},  # unknown key
        {"teeth.dedendum": 0.5},  # a rule within a table
        {"claim.center_distance": 50.0},  # a table the profile does not have
        {"bore.diameter": 6.0, "bore.flat": 2.5},
        {"name": "v1"},  # the title follows the name
        {"mechanism": "roller-body"},
        {"output.tolerance": 0.01},
    ],
    "walker": [{"gear1.b": 48.0}, {"pair.driver": "wheel"}, {"gear2.lobes": 2}, {"pair.center_distance": "solve"}],
    "roller_body_m3": [{"body.amplitude": 0.05}, {"body.m": 4}, {"output.kerf": 0.2}],
}


def _same(a, b) -> bool:
    if isinstance(a, BaseModel):
        return (
            type(a) is type(b)
            and a.model_fields_set == b.model_fields_set
            and list(a.__dict__) == list(b.__dict__)
            and all(_same(a.__dict__[k], b.__dict__[k]) for k in a.__dict__)
        )
    if isinstance(a, (list, tuple)):
        return type(a) is type(b) and len(a) == len(b) and all(map(_same, a, b))
    return type(a) is type(b) and a == b


def _outcome(make):
    try:
        return make()
    except Exception as exc:  # noqa: BLE001 - the refusal is compared
        return exc


@pytest.mark.parametrize("name", sorted(CASES))
def test_variants_are_parse_profile(name):
    data = tomllib.loads((ROOT / "profiles" / f"{name}.toml").read_text())
    variants = Variants(data, name)
    for overrides in CASES[name]:
        slow = _outcome(lambda o=overrides: parse_profile(overridden(data, o), default_name=name))
        fast = _outcome(lambda o=overrides: variants.params(o))
        if isinstance(slow, Exception):
            assert (type(fast), str(fast)) == (type(slow), str(slow)), overrides
        else:
            assert _same(fast, slow), overrides
    assert variants.fast >= len(CASES[name]) // 2  # the fast route is taken, not only its fallback


def test_row_is_the_flattened_report():
    data = tomllib.loads((ROOT / "profiles" / "elliptic_focus.toml").read_text())
    variants = Variants(data, "elliptic_focus")
    for stage, overrides in [("pitch", {"gear1.eccentricity": 0.3}), ("teeth", {"teeth.count": 41})]:
        d = design(variants.params(overrides), stage)
        flat = flatten(d.report())
        assert list(scalars(d).items()) == list(flat.items())
        assert all(type(v) is type(flat[k]) for k, v in scalars(d).items())
