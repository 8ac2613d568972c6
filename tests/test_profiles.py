"""Profiles read and validated: one line per bad value, naming the key, the value and what is allowed."""

import json
import math
import tomllib
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from pydantic import BaseModel, ValidationError

from gearcad.errors import ProfileError
from gearcad.profiles import (
    MECHANISMS,
    MODEL_OF,
    CircleParams,
    EllipseParams,
    GearPairParams,
    RatioParams,
    TeethParams,
    TrainParams,
    apply_overrides,
    load_profile,
    parse_profile,
    profile_error,
    profile_schema,
    validated,
)

from .conftest import PROFILES, ROOT

FOCUS = ROOT / "profiles" / "elliptic_focus.toml"
SCHEMA = ROOT / "profiles" / "profile.schema.json"
PARAMS = tuple(MODEL_OF.values())
"""Every mechanism's profile model, from the table the profiles are read by."""


def _lines(call, *args, **kwargs) -> list[str]:
    with pytest.raises(ProfileError) as info:
        call(*args, **kwargs)
    return str(info.value).splitlines()


def _write(tmp_path: Path, text: str, name: str = "p.toml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize("path", PROFILES, ids=lambda p: p.stem)
def test_every_profile_parses(path):
    params = load_profile(path)
    assert isinstance(params, PARAMS) and params.name == path.stem
    assert path.read_text(encoding="utf-8").startswith("#:schema ./profile.schema.json\n")


@pytest.mark.parametrize("path", PROFILES, ids=lambda p: p.stem)
def test_params_round_trip(path):
    params = load_profile(path)
    assert type(params).model_validate(params.model_dump()) == params
    assert type(params).model_validate_json(params.model_dump_json()) == params
    assert hash(params) == hash(type(params).model_validate(params.model_dump()))


def test_flattened_values():
    focus = load_profile(FOCUS)
    assert (focus.gear1_name, focus.gear2_name, focus.gear2_lobes, focus.driver) == ("driver", "follower", 1, 1)
    assert focus.center_distance is None and focus.driver_rpm == 270.0
    assert focus.teeth.pressure_angle == pytest.approx(math.radians(20))
    walker = load_profile(ROOT / "profiles" / "walker.toml")
    assert walker.driver == 2 and walker.center_distance == 75.0
    assert walker.gear1.lobes == 4 and walker.gear1.blend_width == pytest.approx(math.radians(12))
    body = load_profile(ROOT / "profiles" / "roller_body_m3.toml")
    assert (body.scale, body.roller_radius, body.direction, body.m, body.rpm, body.roller_teeth) == (
        100.0,
        0.1,
        "vertical",
        3,
        90.0,
        12,
    )
    series = load_profile(ROOT / "profiles" / "roller_body_m3.toml", {"body.direction": "series"})
    assert series.amplitude == 0.0
    train = load_profile(ROOT / "profiles" / "planetary_internal.toml")
    assert train.teeth == (20, 16, 52) and train.meshes == ("external", "internal")
    assert train.names == ("sun", "planet", "ring") and train.pressure_angle == pytest.approx(math.radians(20))
    wheel = load_profile(ROOT / "profiles" / "rolling_wheel.toml")
    assert (wheel.r, wheel.R, wheel.L, wheel.H, wheel.driver_rpm, wheel.travel) == (20, 60, 300, 150, 30, 200)


# (override on elliptic_focus, the whole line after the path)
BAD = [
    ("gear1.bb=3", "gear1.bb: unknown key (allowed here: a, b, curve, eccentricity, name, pivot)"),
    ('gear1.a="big"', "gear1.a = 'big': must be a length in mm from 0.001 to 100000"),
    ('gear1.a="3"', "gear1.a = '3': must be a length in mm from 0.001 to 100000"),
    ("gear1.b=-3", "gear1.b = -3: must be a length in mm from 0.001 to 100000"),
    ("gear1.a=0", "gear1.a = 0: must be a length in mm from 0.001 to 100000"),
    ("gear1.a=nan", "gear1.a = nan: must be a length in mm from 0.001 to 100000"),
    ("gear1.a=1e400", "gear1.a = inf: must be a length in mm from 0.001 to 100000"),
    ("gear1.b=30", "gear1.b = 30.0: must not exceed gear1.a = 25 (b is the semi-minor axis)"),
    ("pair.driver_rpm=true", "pair.driver_rpm = true: must be a speed in rev/min > 0"),
    ('pair.driver="crank"', "pair.driver = 'crank': must be one of 'driver', 'follower' (the gears' names)"),
    ("gear2.lobes=0", "gear2.lobes = 0: must be an integer from 1 to 24"),
    ("gear2.lobes=1.0", "gear2.lobes = 1.0: must be an integer from 1 to 24"),
    ("output.tolerance=0", "output.tolerance = 0: must be a length in mm from 0.0001 to 0.5"),
    ("output.charts=1", "output.charts = 1: must be true or false"),
    ("output.formats=['dxf', 'pdf']", "output.formats[1] = 'pdf': must be one of 'dxf', 'svg', 'stl', '3mf'"),
    ("output.sheet=[600]", "output.sheet = [600]: must be [width, height]: two lengths in mm > 0"),
    ("output.mark_layer='cut'", "output.mark_layer = 'cut': must differ from output.cut_layer = 'CUT'"),
    (
        "color=1",
        "color: unknown key (allowed here: bore, claim, gear1, gear2, mechanism, name, output, pair, process, teeth, "
        "title)",
    ),
    ("gear1.eccentricity=1.0", "gear1.eccentricity = 1.0: must be an eccentricity from 0 to 0.998"),
    ("gear1.curve='spiral'", "gear1.curve = 'spiral': must be one of 'ellipse', 'oval', 'circle', 'ratio', 'walker'"),
    ("gear1=3", "gear1 = 3: must be a table ([gear1])"),
    ("teeth.count=2.5", "teeth.count = 2.5: must be an integer from 6 to 2000"),
    ("teeth.dedendum=0.9", "teeth.dedendum = 0.9: must be ≥ teeth.addendum = 1 (the mate's tips need room)"),
    ("pair.center_distance=-4", 'pair.center_distance = -4: must be a length in mm from 0.001 to 100000 or "solve"'),
    ("gear2.name='Driver'", "gear2.name = 'Driver': must differ from gear1.name = 'driver'"),
    ("bore.flat=2", "bore.diameter = 0.0: must be > 0: a keyway or a flat needs a bore"),
    ("mechanism='crank'", "mechanism = 'crank': must be one of 'gear-pair', 'roller-body', 'rolling-wheel'"),
    ("gear1.a=" + "7" * 400, "gear1.a = <an integer of 400 digits>: must be a length in mm from 0.001 to 100000"),
    ("gear2.lobes=" + "7" * 400, "gear2.lobes = <an integer of 400 digits>: must be an integer from 1 to 24"),
]


@pytest.mark.parametrize("override,line", BAD, ids=[b[0][:30] for b in BAD])
def test_bad_value_gives_one_line(override, line):
    (only,) = _lines(load_profile, FOCUS, [override])
    assert only.startswith(f"{FOCUS}: {line}"), only


def test_eccentricity_instead_of_b():
    params = parse_profile({"gear1": {"curve": "ellipse", "a": 10, "eccentricity": 0.6}})
    assert params.gear1.b == pytest.approx(8.0) and params.gear1.eccentricity == 0.6
    assert EllipseParams(a=10, eccentricity=0.6) == params.gear1.model_copy(update={"name": "gear1"})
    (line,) = _lines(parse_profile, {"gear1": {"curve": "ellipse", "a": 10}})
    assert line.startswith("gear1.b is missing: give gear1.b (a length in mm) or gear1.eccentricity")
    (line,) = _lines(parse_profile, {"gear1": {"curve": "ellipse", "a": 10, "b": 5, "eccentricity": 0.6}})
    assert line.startswith("gear1.eccentricity = 0.6: gives b = a·√(1 − e²) = 8 mm, but gear1.b = 5 is given too")
    both = {"gear1": {"curve": "ellipse", "a": 10, "b": 8, "eccentricity": 0.6}}  # agreeing: a round trip
    assert parse_profile(both).gear1.b == 8


def _law(**gear1) -> dict:
    return {"gear1": {"curve": "ratio", **gear1}, "pair": {"center_distance": 50}}


def test_ratio_law_closes_and_stays_positive():
    params = parse_profile(_law(harmonics=[[1, 0.3, 0.0]]))
    assert isinstance(params.gear1, RatioParams) and params.gear1.mean == 1.0
    assert parse_profile({**_law(lobes=2, harmonics=[[2, 0.1, 0]]), "gear2": {"lobes": 3}}).gear1.mean == 2 / 3
    (line,) = _lines(parse_profile, _law(mean=1.2, harmonics=[[1, 0.3, 0.0]]))
    assert line.startswith("gear1.mean = 1.2: the law cannot close") and "must be 1 " in line
    (line,) = _lines(parse_profile, _law(harmonics=[[1, 1.5, 0.0]]))
    assert line.startswith("gear1.harmonics = [[1, 1.5, 0.0]]: the ratio law falls to -0.5 at φ1 = 180.0°")
    (line,) = _lines(parse_profile, _law(lobes=2, harmonics=[[3, 0.1, 0.0]]))
    assert line.startswith("gear1.harmonics[0] = [3, 0.1, 0.0]: the order must be a multiple of gear1.lobes = 2")
    (line,) = _lines(parse_profile, _law(harmonics=[[0, 0.1, 0.0]]))
    assert line.startswith("gear1.harmonics[0] = [0, 0.1, 0.0]: must be [order, cos, sin]: an integer order from 1")
    (line,) = _lines(parse_profile, {"gear1": {"curve": "ratio"}})
    assert line.startswith("pair.center_distance = 'solve': must be a length in mm for a ratio gear")


def test_other_mechanisms_rules():
    train = {
        "mechanism": "carrier-train",
        "train": {"module": 1.5, "teeth": [20, 16, 20], "meshes": ["external", "internal"]},
    }
    (line,) = _lines(parse_profile, train)
    assert line.startswith("train.teeth[2] = 20: an internal mesh needs the ring at least 12 teeth larger")
    defaults = parse_profile({"mechanism": "carrier-train", "train": {"module": 1, "teeth": [20, 30, 40]}})
    assert defaults.names == ("gear1", "gear2", "gear3") and defaults.meshes == ("external", "external")
    wheel = {"mechanism": "rolling-wheel", "drive": {"r": 20, "R": 60, "L": 100, "H": 10, "travel": 200}}
    assert _lines(parse_profile, wheel) == [
        "drive.H = 10.0: must be ≥ R − r = 40 mm: the rack slopes up to wheel 1 (H = R − r is the horizontal case)",
        "drive.travel = 200.0: must be under drive.L = 100 mm (wheel 2 would pass wheel 1)",
    ]
    body = {"mechanism": "roller-body", "body": {"m": 4, "roller_radius": 0, "f": [[2, 0, 0]]}}
    lines = _lines(parse_profile, body)
    assert [ln.split(" = ")[0] for ln in lines] == ["body.roller_radius", "body.m", "body.f[0]"]
    assert "must be a multiple of 3 from 3 to 30" in lines[1]
    (line,) = _lines(parse_profile, {"mechanism": "roller-body"})
    assert line == "[body] is missing: the table is required"


def test_several_bad_values_one_line_each(tmp_path):
    path = _write(tmp_path, '[gear1]\ncurve = "ellipse"\na = -1\nb = "x"\nwobble = 2\n')
    assert _lines(load_profile, path) == [
        f"{path}: gear1.a = -1: must be a length in mm from 0.001 to 100000",
        f"{path}: gear1.b = 'x': must be a length in mm from 0.001 to 100000",
        f"{path}: gear1.wobble: unknown key (allowed here: a, b, curve, eccentricity, name, pivot)",
    ]


def test_a_long_list_of_bad_values_is_summed_up():
    lines = _lines(parse_profile, {"gear1": {"curve": "samples", "radii": [-1] * 50}})
    assert len(lines) == 6 and lines[-1] == "gear1.radii: 45 more bad values like these"


def test_files_that_cannot_be_read(tmp_path):
    (line,) = _lines(load_profile, tmp_path / "missing.toml")
    assert line.startswith(f"{tmp_path / 'missing.toml'}: cannot read the profile (")
    (line,) = _lines(load_profile, tmp_path)
    assert "cannot read the profile" in line
    (line,) = _lines(load_profile, _write(tmp_path, "[gear1\n"))
    assert line.startswith(f"{tmp_path / 'p.toml'}: not valid TOML (")
    latin = tmp_path / "latin.toml"
    latin.write_bytes('title = "Zahnräder"\n'.encode("latin-1"))
    assert _lines(load_profile, latin) == [f"{latin}: not UTF-8 text (byte 0xe4 at offset 14)"]
    huge = _write(tmp_path, f'[gear1]\ncurve = "circle"\nradius = {"9" * 5000}\n')
    assert _lines(load_profile, huge) == [f"{huge}: not valid TOML (an integer of more than 4300 digits)"]


def test_byte_order_mark_and_large_integer(tmp_path):
    bom = tmp_path / "bom.toml"
    bom.write_bytes(b"\xef\xbb\xbf" + FOCUS.read_bytes())
    assert load_profile(bom).gear1.a == 25
    big = _write(tmp_path, f'[gear1]\ncurve = "circle"\nradius = {"1" * 400}\n')
    assert _lines(load_profile, big) == [
        f"{big}: gear1.radius = <an integer of 400 digits>: must be a length in mm from 0.001 to 100000"
    ]


def test_default_name_is_the_file_stem(tmp_path):
    text = FOCUS.read_text(encoding="utf-8").replace('name = "elliptic_focus"\n', "")
    assert load_profile(_write(tmp_path, text, "my-pair.toml")).name == "my-pair"
    (line,) = _lines(load_profile, _write(tmp_path, text, "my pair.toml"))
    assert "name = 'my pair': must be a name" in line and "comes from the file's name" in line


BAD_NAMES = ["../x", "/abs", "a/b", "a\\b", "", ".hidden", "assembly", "Report", "x" * 65, "nul\0", "a\n", "é", 3]
NAME_PLACES = {
    "name": (FOCUS, "name"),
    "gear1.name": (FOCUS, "gear1.name"),
    "gear2.name": (FOCUS, "gear2.name"),
    "train.names[1]": (ROOT / "profiles" / "planetary_external.toml", "train.names"),
}


@pytest.mark.parametrize("name", BAD_NAMES, ids=repr)
@pytest.mark.parametrize("place", NAME_PLACES)
def test_names_that_could_leave_the_output_folder_are_refused(place, name):
    path, key = NAME_PLACES[place]
    value = ["sun", name, "planet"] if key == "train.names" else name
    (line,) = _lines(load_profile, path, {key: value})
    assert line.startswith(f"{path}: {place} = {name!r}: must ")
    if name in ("assembly", "Report"):
        assert "the build writes its own files under that name" in line
    elif isinstance(name, str):
        assert "1 to 64 characters: letters A–Z a–z, digits, '-', '_' or '.', not starting with '.'" in line


def test_good_names_and_distinct_parts():
    renamed = load_profile(FOCUS, {"name": "v1.2_final-B", "gear1.name": "A.b", "pair.driver": "A.b"})
    assert (renamed.name, renamed.gear1_name, renamed.driver) == ("v1.2_final-B", "A.b", 1)
    (line,) = _lines(load_profile, ROOT / "profiles" / "planetary_external.toml", {"train.names": ["a", "b", "A"]})
    assert "train.names[2] = 'A': must differ from train.names[0] = 'a' (each part's name names its files" in line


def test_exclusive_keys_override_each_other():
    by_count = load_profile(FOCUS, ["teeth.count=39"])
    assert (by_count.teeth.count, by_count.teeth.module) == (39, None)
    back = load_profile(ROOT / "profiles" / "spur_pair.toml", {"teeth.module": 2.0})
    assert (back.teeth.count, back.teeth.module) == (None, 2.0)
    by_e = load_profile(FOCUS, ["gear1.eccentricity=0.8"])
    assert by_e.gear1.b == pytest.approx(15.0) and by_e.gear1.eccentricity == 0.8


def test_unset_and_none_remove_keys():
    data = tomllib.loads(FOCUS.read_text(encoding="utf-8"))
    out = apply_overrides(data, {"teeth": None, "gear1.a": 30}, unset=["claim.source", "pair.driver"])
    assert "teeth" not in out and out["gear1"]["a"] == 30 and "driver" not in out["pair"]
    assert data["gear1"]["a"] == 25.0 and "teeth" in data and "driver" in data["pair"]  # a copy, untouched
    plain = load_profile(FOCUS, unset=["teeth"])
    assert plain.teeth is None
    assert load_profile(FOCUS, ["output.charts=false", "name=wider"]).name == "wider"


@pytest.mark.parametrize(
    "override,line",
    [
        ("gear1.a", "--set 'gear1.a': must be KEY=VALUE, e.g. gear1.a=30"),
        ("gear1..a=3", "--set 'gear1..a=3': the key must be dotted names, e.g. pair.driver_rpm"),
        ("gear1.a.x=3", "--set 'gear1.a.x=3': gear1.a is not a table"),
    ],
)
def test_malformed_overrides(override, line):
    assert _lines(load_profile, FOCUS, [override]) == [f"{FOCUS}: {line}"]


def test_params_built_in_python_are_validated():
    with pytest.raises(ValidationError):
        CircleParams(curve="circle", radius=-1)
    assert _lines(validated, CircleParams, radius=-1) == ["radius = -1: must be a length in mm from 0.001 to 100000"]
    assert _lines(validated, TeethParams, module=1, count=20) == [
        "count = 20: give teeth.module or teeth.count, not both"
    ]
    pair = GearPairParams(gear1=CircleParams(radius=20), gear2={"name": "mate", "lobes": 2})
    assert pair.gear2_lobes == 2 and pair.driver == 1 and pair.pair.driver == "gear1"
    assert pair.output.formats == ("dxf", "svg", "stl", "3mf") and pair.center_distance is None
    with pytest.raises(ValidationError) as info:
        GearPairParams(gear1={"curve": "ellipse", "a": 1, "b": 2}, teeth={"count": 3})
    assert str(profile_error(info.value)).splitlines() == [
        "gear1.b = 2.0: must not exceed gear1.a = 1 (b is the semi-minor axis)",
        "teeth.count = 3: must be an integer from 6 to 2000",
    ]
    assert _lines(parse_profile, {"gear1": {"curve": "circle", "radius": -1}}) == [
        "gear1.radius = -1: must be a length in mm from 0.001 to 100000"
    ]
    with pytest.raises(ValidationError):
        TrainParams(module=1, teeth=(20,))
    with pytest.raises(ValidationError):  # frozen
        pair.name = "other"


def test_committed_schema_is_current():
    regenerate = (
        "profiles/profile.schema.json is stale; regenerate it with: python -c 'import json; "
        "from gearcad.profiles import profile_schema as s; print(json.dumps(s(), indent=2, ensure_ascii=False))' "
        "> profiles/profile.schema.json"
    )
    assert json.loads(SCHEMA.read_text(encoding="utf-8")) == json.loads(json.dumps(profile_schema())), regenerate


def _schema_keys(schema: dict, node: dict, data: dict, where: str) -> list[str]:
    """Keys of ``data`` the schema does not list, the union's branch chosen by its tag."""

    def resolve(node: dict) -> dict:
        return schema["$defs"][node["$ref"].rsplit("/", 1)[-1]] if "$ref" in node else node

    def tagged(branch: dict) -> bool:
        tags = {k: p for k, p in branch.get("properties", {}).items() if "const" in p}
        return all(data.get(k, p.get("default")) == p["const"] for k, p in tags.items())

    node = resolve(node)
    branches = [resolve(b) for b in node.get("oneOf", [])]
    node = next((b for b in branches if tagged(b)), node)
    props = node.get("properties", {})
    unknown = []
    for key, value in data.items():
        if key not in props:
            unknown.append(f"{where}{key}")
        elif isinstance(value, dict):
            unknown += _schema_keys(schema, props[key], value, f"{where}{key}.")
    return unknown


@pytest.mark.parametrize("path", PROFILES, ids=lambda p: p.stem)
def test_schema_knows_every_key(path):
    schema = json.loads(SCHEMA.read_text(encoding="utf-8"))
    assert _schema_keys(schema, schema, tomllib.loads(path.read_text(encoding="utf-8")), "") == []


@pytest.fixture(scope="module")
def schema_validator():
    """The committed schema, itself checked against the 2020-12 meta-schema once, as a validator."""
    jsonschema = pytest.importorskip("jsonschema", reason="pip install jsonschema to check profiles against the schema")
    schema = json.loads(SCHEMA.read_text(encoding="utf-8"))
    jsonschema.Draft202012Validator.check_schema(schema)
    return jsonschema.Draft202012Validator(schema)


@pytest.mark.parametrize("path", PROFILES, ids=lambda p: p.stem)
def test_profiles_validate_against_the_schema(schema_validator, path):
    schema_validator.validate(tomllib.loads(path.read_text(encoding="utf-8")))


def _known_keys() -> list[str]:
    """Every dotted key a profile may write, tables included."""
    keys = {"mechanism"}
    for cls in PARAMS:
        for name, field in cls.model_fields.items():
            keys.add(name)
            models = [a for a in getattr(field.annotation, "__args__", (field.annotation,)) if isinstance(a, type)]
            for model in (m for m in models if issubclass(m, BaseModel)):
                keys.update(f"{name}.{sub}" for sub in model.model_fields)
    return sorted(keys)


_scalars = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(),
    st.integers(min_value=10**300, max_value=10**400),
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(min_value=-100, max_value=100),
    st.text(max_size=70),
    st.sampled_from(["solve", "ellipse", "ratio", "walker", "series", "internal", "dxf", "gear2", "driver"]),
)


def _containers(inner: st.SearchStrategy) -> st.SearchStrategy:
    return st.lists(inner, max_size=5) | st.dictionaries(st.text(max_size=8), inner, max_size=3)


_junk = st.recursive(_scalars, _containers, max_leaves=12)


@settings(max_examples=120, deadline=None)
@given(
    base=st.sampled_from([None, *PROFILES]),
    mechanism=st.sampled_from([None, *MECHANISMS]),
    values=st.dictionaries(st.sampled_from(_known_keys()), _junk, max_size=6),
)
def test_junk_gives_params_or_a_profile_error(base, mechanism, values):
    data = tomllib.loads(base.read_text(encoding="utf-8")) if base else {}
    if mechanism:
        data["mechanism"] = mechanism
    try:
        params = parse_profile(apply_overrides(data, values))
    except ProfileError as exc:
        lines = str(exc).splitlines()
        assert lines and all(line.strip() and "Input should" not in line for line in lines), lines
    else:
        assert isinstance(params, PARAMS)


def test_the_reference_writer_takes_help_as_help_not_as_a_file_name(tmp_path, monkeypatch, capsys):
    """``python3 -m gearcad.profiles.reference --help`` once wrote the page to a file named
    ``--help`` (one was committed): it prints usage now, and writes nothing."""
    from gearcad.profiles.reference import main

    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit) as stop:
        main(["--help"])
    assert stop.value.code == 0 and "usage:" in capsys.readouterr().out
    assert list(tmp_path.iterdir()) == []
    assert main([str(tmp_path)]) == 2  # a folder: one line, nothing written
    assert capsys.readouterr().err.count("\n") == 1 and list(tmp_path.iterdir()) == []
    assert main(["page.md"]) == 0
    assert (tmp_path / "page.md").read_text(encoding="utf-8").startswith("# Profile reference")
