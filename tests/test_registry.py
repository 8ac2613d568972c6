"""The registry of mechanisms against the profiles, their models and the schema."""

import json
import tomllib
from importlib import import_module

from gearcad import profiles
from gearcad.mechanisms import MECHANISMS

from .conftest import PROFILES, ROOT


def test_registry_names_every_mechanism_the_profiles_and_the_schema_know():
    used = {tomllib.loads(p.read_text(encoding="utf-8")).get("mechanism", "gear-pair") for p in PROFILES}
    schema = json.loads((ROOT / "profiles" / "profile.schema.json").read_text(encoding="utf-8"))
    consts = {
        d["properties"]["mechanism"]["const"]
        for d in schema["$defs"].values()
        if "mechanism" in d.get("properties", {})
    }
    assert set(MECHANISMS) == set(profiles.MECHANISMS) == consts == used


def test_each_entry_names_its_module_and_params_model():
    for name, entry in MECHANISMS.items():
        assert entry.name == name
        module = import_module(f"gearcad.mechanisms.{entry.module}")
        assert module.design.__annotations__["return"].split("[")[0] == "Draft"  # Draft[its detail]
        assert entry.params.model_fields["mechanism"].default == name


def test_every_hook_an_entry_names_is_a_function():
    """A hook is named by a string (resolved when used): a misspelt one fails here, not in a build."""
    from dataclasses import fields

    for entry in MECHANISMS.values():
        for f in fields(entry):
            if (
                f.name not in ("name", "module", "coupons", "play", "backlash_table")
                and getattr(entry, f.name) is not None
            ):
                assert callable(entry.hook(f.name)), (entry.name, f.name)
        assert callable(entry.design)
