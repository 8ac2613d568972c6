"""Design profiles: TOML files turned into validated, typed parameters.

Every value is checked once, here; each bad value gives one line naming the key, the value and
what is allowed.  Lengths are mm, angles are degrees at this boundary (``…_deg``) and radians
everywhere after it.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .errors import ProfileError

__all__ = [
    "EllipseParams",
    "OvalParams",
    "CircleParams",
    "RatioParams",
    "WalkerParams",
    "SamplesParams",
    "ClaimParams",
    "OutputParams",
    "GearPairParams",
    "load_profile",
    "parse_profile",
    "apply_overrides",
    "CURVES",
]


@dataclass(frozen=True)
class BoreParams:
    diameter: float = 0.0
    keyway_width: float = 0.0
    keyway_depth: float = 0.0
    flat: float = 0.0


@dataclass(frozen=True)
class EllipseParams:
    a: float
    b: float
    pivot: str  # "focus" | "centre"

    @property
    def lobes(self) -> int:
        return 1 if self.pivot == "focus" else 2


@dataclass(frozen=True)
class OvalParams:
    a: float
    b: float
    lobes: int = 2


@dataclass(frozen=True)
class CircleParams:
    radius: float
    lobes: int = 1


@dataclass(frozen=True)
class RatioParams:
    """k(φ1) = ω2/ω1 = mean + Σ (c_j cos jφ + s_j sin jφ)."""

    mean: float | None
    harmonics: tuple[tuple[int, float, float], ...]
    lobes: int


@dataclass(frozen=True)
class WalkerParams:
    a: float
    b: float
    c: float
    blend_width: float  # rad
    lobes: int = 4


@dataclass(frozen=True)
class SamplesParams:
    radii: tuple[float, ...]
    lobes: int


@dataclass(frozen=True)
class ClaimParams:
    """A paper's claim to check: the driver meshes with an identical copy at this distance."""

    center_distance: float
    source: str


@dataclass(frozen=True)
class TeethParams:
    """The generating rack and how many teeth (exactly one of ``module`` / ``count``)."""

    module: float | None
    count: int | None
    pressure_angle: float = math.radians(20)  # rad
    addendum: float = 1.0
    dedendum: float = 1.25
    tip_radius: float = 0.38
    profile_shift: float = 0.0  # gear 1; gear 2 gets the opposite so the centre distance stays
    backlash: float = 0.0  # mm, for the pair, on the pitch curves
    clearance: float = 0.0  # mm, every toothed outline offset inwards by this


DXF_FLAVOURS = ("polyline", "lines-arcs", "polyline-flat")
FORMATS = ("dxf", "stl", "3mf")


@dataclass(frozen=True)
class OutputParams:
    tolerance: float = 0.001
    charts: bool = True
    animation: bool = True
    formats: tuple[str, ...] = FORMATS
    dxf: str = "polyline"
    thickness: float = 5.0
    chamfer: float = 0.0
    kerf: float = 0.0
    cut_layer: str = "CUT"
    mark_layer: str = "MARK"


CurveParams = EllipseParams | OvalParams | CircleParams | RatioParams | WalkerParams | SamplesParams


@dataclass(frozen=True)
class GearPairParams:
    name: str
    title: str
    gear1: CurveParams
    gear1_name: str
    gear2_name: str
    gear2_lobes: int
    center_distance: float | None  # None: solve from closure
    driver: int  # 1 or 2
    driver_rpm: float
    claim: ClaimParams | None = None
    teeth: TeethParams | None = None
    bore: BoreParams = field(default_factory=BoreParams)
    output: OutputParams = field(default_factory=OutputParams)


CURVES = ("ellipse", "oval", "circle", "ratio", "walker", "samples")
MECHANISMS = ("gear-pair", "roller-body", "rolling-wheel", "carrier-train")


@dataclass(frozen=True)
class RollerBodyParams:
    name: str
    title: str
    scale: float  # mm per unit of R
    roller_radius: float  # units of R
    direction: str  # "horizontal" | "vertical" | "series"
    amplitude: float
    m: int
    f: tuple[tuple[int, float, float], ...]
    g: tuple[tuple[int, float, float], ...]
    rpm: float
    bore: BoreParams
    output: OutputParams
    roller_teeth: int | None = None  # teeth on each roller (then the body is toothed too)
    pressure_angle: float = math.radians(20)


@dataclass(frozen=True)
class RollingWheelParams:
    name: str
    title: str
    r: float
    R: float
    L: float
    H: float
    driver_rpm: float
    travel: float  # mm rolled by wheel 2
    output: OutputParams


@dataclass(frozen=True)
class CarrierTrainParams:
    name: str
    title: str
    module: float
    teeth: tuple[int, ...]
    meshes: tuple[str, ...]
    names: tuple[str, ...]
    gear1_rpm: float
    carrier_rpm: float
    gear1_eps: float  # rad/s²
    carrier_eps: float
    pressure_angle: float
    bore: BoreParams
    output: OutputParams


_CURVE_KEYS = {
    "ellipse": {"a", "b", "eccentricity", "pivot"},
    "oval": {"a", "b"},
    "circle": {"radius"},
    "ratio": {"mean", "harmonics", "lobes"},
    "walker": {"a", "b", "c", "blend_width_deg"},
    "samples": {"radii", "lobes"},
}
_TABLE_KEYS = {
    "": {"name", "title", "mechanism", "gear1", "gear2", "pair", "claim", "teeth", "bore", "output"},
    "bore": {"diameter", "keyway_width", "keyway_depth", "flat"},
    "teeth": {
        "module",
        "count",
        "pressure_angle_deg",
        "addendum",
        "dedendum",
        "tip_radius",
        "profile_shift",
        "backlash",
        "clearance",
    },
    "gear2": {"name", "lobes"},
    "pair": {"center_distance", "driver", "driver_rpm"},
    "claim": {"center_distance", "source"},
    "output": {
        "tolerance",
        "charts",
        "animation",
        "formats",
        "dxf",
        "thickness",
        "chamfer",
        "kerf",
        "cut_layer",
        "mark_layer",
    },
}


class _Reader:
    """Reads values from one table, collecting one error line per bad value."""

    def __init__(self, data: dict, prefix: str, errors: list[str]):
        self.data, self.prefix, self.errors = data, prefix, errors

    def key(self, name: str) -> str:
        return f"{self.prefix}{name}"

    def fail(self, name: str, value: Any, allowed: str) -> None:
        self.errors.append(f"{self.key(name)} = {_show(value)}: {allowed}")

    def number(self, name, default=None, *, positive=False, minimum=None, maximum=None, below=None, what="a number"):
        value = self.data.get(name, default)
        if value is None:
            self.errors.append(f"{self.key(name)} is missing: {what} is required")
            return math.nan
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            self.fail(name, value, f"must be {what}")
            return math.nan
        if positive and value <= 0:
            self.fail(name, value, f"must be {what} > 0")
            return math.nan
        if minimum is not None and value < minimum:
            span = f"from {minimum:g} to {maximum:g}" if maximum is not None else f"≥ {minimum:g}"
            self.fail(name, value, f"must be {what} {span}")
            return math.nan
        if maximum is not None and value > maximum:
            self.fail(name, value, f"must be {what} from {minimum:g} to {maximum:g}")
            return math.nan
        if below is not None and value >= below:
            self.fail(name, value, f"must be {what} < {below:g}")
            return math.nan
        return float(value)

    def integer(self, name, default=None, *, minimum=1):
        value = self.data.get(name, default)
        if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
            self.fail(name, value, f"must be an integer ≥ {minimum}")
            return minimum
        return int(value)

    def text(self, name, default=None, *, choices=None):
        value = self.data.get(name, default)
        if value is None:
            self.errors.append(f"{self.key(name)} is missing: a string is required")
            return ""
        if not isinstance(value, str):
            self.fail(name, value, "must be a string")
            return ""
        if choices is not None and value not in choices:
            self.fail(name, value, "must be one of " + ", ".join(repr(c) for c in choices))
            return choices[0]
        return value

    def boolean(self, name, default):
        value = self.data.get(name, default)
        if not isinstance(value, bool):
            self.fail(name, value, "must be true or false")
            return default
        return value

    def unknown(self, allowed: set[str]) -> None:
        for name in self.data:
            if name not in allowed:
                self.errors.append(f"{self.key(name)}: unknown key (allowed here: {', '.join(sorted(allowed))})")


def _show(value: Any) -> str:
    return repr(value) if isinstance(value, str) else str(value).lower() if isinstance(value, bool) else str(value)


def _table(data: dict, name: str, errors: list[str], required: bool = True) -> dict:
    value = data.get(name)
    if value is None:
        if required:
            errors.append(f"[{name}] is missing: the table is required")
        return {}
    if not isinstance(value, dict):
        errors.append(f"{name} = {_show(value)}: must be a table ([{name}])")
        return {}
    return value


def _curve(t: dict, errors: list[str]) -> tuple[CurveParams | None, str]:
    g = _Reader(t, "gear1.", errors)
    kind = g.text("curve", choices=CURVES)
    name = g.text("name", "gear1")
    g.unknown({"name", "curve"} | _CURVE_KEYS.get(kind, set()))
    length = "a length in mm"
    if kind == "ellipse":
        a = g.number("a", what=length, positive=True)
        pivot = g.text("pivot", "focus", choices=("focus", "centre"))
        if "b" in t and "eccentricity" in t:
            errors.append("gear1.eccentricity: give either gear1.b or gear1.eccentricity, not both")
            return None, name
        if "eccentricity" in t:
            e = g.number("eccentricity", minimum=0, below=1, what="an eccentricity")
            b = a * math.sqrt(1 - e * e) if math.isfinite(e) else math.nan
        else:
            b = g.number("b", what=length, positive=True)
            if math.isfinite(a) and math.isfinite(b) and b > a:
                g.fail("b", t["b"], f"must not exceed gear1.a = {a:g} (the semi-minor axis)")
        return EllipseParams(a, b, pivot), name
    if kind == "oval":
        a = g.number("a", what=length, positive=True)
        b = g.number("b", what=length, positive=True)
        if math.isfinite(a) and math.isfinite(b) and b > a:
            g.fail("b", t["b"], f"must not exceed gear1.a = {a:g}")
        return OvalParams(a, b), name
    if kind == "circle":
        return CircleParams(g.number("radius", what=length, positive=True)), name
    if kind == "walker":
        a = g.number("a", what=length, positive=True)
        b = g.number("b", what=length, positive=True)
        c = g.number("c", what=length, positive=True)
        w = g.number("blend_width_deg", 0.0, minimum=0, below=45, what="an angle in degrees")
        if all(map(math.isfinite, (a, b, c))) and a - 4 * b + c <= 0:
            errors.append(
                f"gear1.b = {b:g}: the walker law needs a − 4b + c > 0 so that the ratio stays "
                f"positive (got {a - 4 * b + c:g} mm)"
            )
        return WalkerParams(a, b, c, math.radians(w) if math.isfinite(w) else 0.0), name
    if kind == "ratio":
        lobes = g.integer("lobes", 1)
        # the mean is fixed by closure; a given one is checked against it in parse_profile
        mean = g.number("mean", positive=True, what="a speed ratio") if "mean" in t else None
        harmonics = []
        raw = t.get("harmonics", [])
        if not isinstance(raw, list):
            g.fail("harmonics", raw, "must be a list of [order, cos, sin] triples")
            raw = []
        for n, term in enumerate(raw):
            ok = (
                isinstance(term, list)
                and len(term) == 3
                and isinstance(term[0], int)
                and not isinstance(term[0], bool)
                and term[0] >= 1
                and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in term[1:])
            )
            if not ok:
                errors.append(
                    f"gear1.harmonics[{n}] = {_show(term)}: must be [order, cos, sin] with an "
                    "integer order ≥ 1 and two numbers"
                )
            elif term[0] % lobes:
                errors.append(
                    f"gear1.harmonics[{n}] = {_show(term)}: the order must be a multiple of "
                    f"gear1.lobes = {lobes} so that the curve has {lobes} lobes"
                )
            else:
                harmonics.append((int(term[0]), float(term[1]), float(term[2])))
        return RatioParams(mean, tuple(harmonics), lobes), name
    if kind == "samples":
        lobes = g.integer("lobes", 1)
        raw = t.get("radii")
        if (
            not isinstance(raw, list)
            or len(raw) < 8
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and v > 0 for v in raw)
        ):
            g.fail(
                "radii",
                raw,
                "must be a list of at least 8 positive lengths in mm, equally spaced over one turn from φ = 0",
            )
            return None, name
        return SamplesParams(tuple(float(v) for v in raw), lobes), name
    return None, name


def parse_profile(data: dict, *, default_name: str = "profile"):
    """Validate a profile's TOML data; raise :class:`ProfileError` with one line per bad value."""
    mechanism = data.get("mechanism", "gear-pair")
    if mechanism not in MECHANISMS:
        raise ProfileError(f"mechanism = {_show(mechanism)}: must be one of " + ", ".join(repr(m) for m in MECHANISMS))
    if mechanism != "gear-pair":
        return _other(mechanism, data, default_name)
    errors: list[str] = []
    top = _Reader(data, "", errors)
    top.unknown(_TABLE_KEYS[""])
    name = top.text("name", default_name)
    if name and not all(ch.isalnum() or ch in "-_" for ch in name):
        top.fail("name", name, "must use only letters, digits, '-' and '_' (it names a folder)")
    title = top.text("title", "")
    gear1, gear1_name = _curve(_table(data, "gear1", errors), errors)

    t2 = _table(data, "gear2", errors, required=False)
    g2 = _Reader(t2, "gear2.", errors)
    g2.unknown(_TABLE_KEYS["gear2"])
    gear2_name = g2.text("name", "gear2")
    lobes1 = getattr(gear1, "lobes", 1)
    gear2_lobes = g2.integer("lobes", lobes1)
    if isinstance(gear1, RatioParams):
        gear1 = _close_ratio_law(gear1, gear2_lobes, errors)
    if gear2_name == gear1_name:
        g2.fail("name", gear2_name, "must differ from gear1.name (it names a file)")

    tp = _table(data, "pair", errors, required=False)
    p = _Reader(tp, "pair.", errors)
    p.unknown(_TABLE_KEYS["pair"])
    raw_e = tp.get("center_distance", "solve")
    center: float | None = None
    if raw_e != "solve":
        center = p.number("center_distance", what='a length in mm or "solve"', positive=True)
    if isinstance(gear1, (RatioParams, WalkerParams)) and center is None:
        p.fail(
            "center_distance",
            raw_e,
            f"must be a length in mm for a {_kind(gear1)} gear: its law fixes the shape, the centre distance its size",
        )
    driver_name = p.text("driver", gear1_name, choices=(gear1_name, gear2_name))
    driver = 2 if driver_name == gear2_name and driver_name != gear1_name else 1
    rpm = p.number("driver_rpm", 60.0, positive=True, what="a speed in rev/min")

    claim = None
    tc = _table(data, "claim", errors, required=False)
    if tc:
        c = _Reader(tc, "claim.", errors)
        c.unknown(_TABLE_KEYS["claim"])
        claim = ClaimParams(
            c.number("center_distance", what="a length in mm", positive=True),
            c.text("source", ""),
        )
        if gear2_lobes != lobes1:
            errors.append(
                f"claim.center_distance: an identical-mate claim needs gear2.lobes = "
                f"gear1 lobes = {lobes1}, got {gear2_lobes}"
            )

    teeth = _teeth(_table(data, "teeth", errors, required=False), errors) if "teeth" in data else None

    to = _table(data, "output", errors, required=False)
    o = _Reader(to, "output.", errors)
    o.unknown(_TABLE_KEYS["output"])
    output = _output(o, to, errors)
    bore = _bore(_table(data, "bore", errors, required=False), errors)

    if errors:
        raise ProfileError("\n".join(errors))
    return GearPairParams(
        name=name,
        title=title,
        gear1=gear1,
        gear1_name=gear1_name,
        gear2_name=gear2_name,
        gear2_lobes=gear2_lobes,
        center_distance=center,
        driver=driver,
        driver_rpm=rpm,
        claim=claim,
        teeth=teeth,
        bore=bore,
        output=output,
    )


def _output(o: _Reader, t: dict, errors: list[str]) -> OutputParams:
    tolerance = o.number("tolerance", 0.001, positive=True, what="a length in mm")
    if math.isfinite(tolerance) and tolerance > 0.5:
        o.fail("tolerance", tolerance, "must be ≤ 0.5 mm (coarser outlines would not mesh)")
    formats = t.get("formats", list(FORMATS))
    if not isinstance(formats, list) or not all(f in FORMATS for f in formats):
        o.fail("formats", formats, "must be a list drawn from " + ", ".join(repr(f) for f in FORMATS))
        formats = list(FORMATS)
    cut = o.text("cut_layer", "CUT")
    mark = o.text("mark_layer", "MARK")
    for key, layer in (("cut_layer", cut), ("mark_layer", mark)):
        if not layer or not all(ch.isalnum() or ch in "-_$" for ch in layer):
            o.fail(key, layer, "must be a DXF layer name: letters, digits, '-', '_' or '$'")
    if cut == mark:
        o.fail("mark_layer", mark, "must differ from output.cut_layer")
    return OutputParams(
        tolerance=tolerance,
        charts=o.boolean("charts", True),
        animation=o.boolean("animation", True),
        formats=tuple(formats),
        dxf=o.text("dxf", "polyline", choices=DXF_FLAVOURS),
        thickness=o.number("thickness", 5.0, positive=True, what="a thickness in mm"),
        chamfer=o.number("chamfer", 0.0, minimum=0, what="a length in mm"),
        kerf=o.number("kerf", 0.0, minimum=0, maximum=2, what="a kerf width in mm"),
        cut_layer=cut,
        mark_layer=mark,
    )


def _bore(t: dict, errors: list[str]) -> BoreParams:
    r = _Reader(t, "bore.", errors)
    r.unknown(_TABLE_KEYS["bore"])
    bore = BoreParams(
        diameter=r.number("diameter", 0.0, minimum=0, what="a diameter in mm"),
        keyway_width=r.number("keyway_width", 0.0, minimum=0, what="a length in mm"),
        keyway_depth=r.number("keyway_depth", 0.0, minimum=0, what="a length in mm"),
        flat=r.number("flat", 0.0, minimum=0, what="a length in mm"),
    )
    if (bore.keyway_width > 0) != (bore.keyway_depth > 0):
        errors.append("bore.keyway_width: a keyway needs both bore.keyway_width and bore.keyway_depth > 0")
    if bore.flat > 0 and bore.keyway_width > 0:
        errors.append("bore.flat: give a keyway or a flat, not both")
    if bore.flat > 0 and not bore.flat < bore.diameter / 2:
        r.fail("flat", bore.flat, f"must be under the bore radius {bore.diameter / 2:g} mm (distance from the centre)")
    if (bore.keyway_width > 0 or bore.flat > 0) and bore.diameter <= 0:
        errors.append("bore.diameter: a keyway or flat needs a bore (bore.diameter > 0)")
    if bore.keyway_width > 0 and bore.keyway_width >= bore.diameter:
        r.fail("keyway_width", bore.keyway_width, f"must be under the bore diameter {bore.diameter:g} mm")
    return bore


def _teeth(t: dict, errors: list[str]) -> TeethParams | None:
    r = _Reader(t, "teeth.", errors)
    r.unknown(_TABLE_KEYS["teeth"])
    if ("module" in t) == ("count" in t):
        errors.append("[teeth]: give exactly one of teeth.module (mm) or teeth.count (teeth on gear 1)")
        return None
    module = r.number("module", positive=True, what="a module in mm") if "module" in t else None
    count = r.integer("count", minimum=6) if "count" in t else None
    angle = r.number("pressure_angle_deg", 20.0, minimum=10, maximum=35, what="an angle in degrees")
    addendum = r.number("addendum", 1.0, positive=True, what="a coefficient (× module)")
    dedendum = r.number("dedendum", 1.25, positive=True, what="a coefficient (× module)")
    if math.isfinite(addendum) and math.isfinite(dedendum) and dedendum < addendum:
        r.fail("dedendum", t.get("dedendum"), f"must be ≥ teeth.addendum = {addendum:g} (the mate's tips need room)")
    return TeethParams(
        module=module,
        count=count,
        pressure_angle=math.radians(angle) if math.isfinite(angle) else math.nan,
        addendum=addendum,
        dedendum=dedendum,
        tip_radius=r.number("tip_radius", 0.38, minimum=0, what="a coefficient (× module)"),
        profile_shift=r.number("profile_shift", 0.0, minimum=-0.8, maximum=0.8, what="a coefficient (× module)"),
        backlash=r.number("backlash", 0.0, minimum=0, what="a length in mm"),
        clearance=r.number("clearance", 0.0, minimum=0, what="a length in mm"),
    )


def _close_ratio_law(law: RatioParams, mate_lobes: int, errors: list[str]) -> RatioParams:
    """A ratio law closes only if its mean is n1/n2; it must also stay positive."""
    need = law.lobes / mate_lobes
    if law.mean is None:
        law = RatioParams(need, law.harmonics, law.lobes)
    elif math.isfinite(law.mean) and abs(law.mean - need) > 1e-12 * need:
        errors.append(
            f"gear1.mean = {law.mean:g}: the law cannot close; with gear1.lobes = {law.lobes} and "
            f"gear2.lobes = {mate_lobes} the mate turns 2π·{law.lobes}/{mate_lobes} per driver "
            f"turn, so the mean ratio must be {need:g} (or leave gear1.mean out)"
        )
        return law
    phi = [2 * math.pi * j / 4096 for j in range(4096)]
    low, at = min(
        (law.mean + sum(c * math.cos(n * x) + s_ * math.sin(n * x) for n, c, s_ in law.harmonics), x) for x in phi
    )
    if low <= 0.02 * law.mean:
        errors.append(
            f"gear1.harmonics: the ratio law falls to {low:.4g} at φ1 = {math.degrees(at):.1f}°; "
            f"it must stay above 2% of its mean {law.mean:g} (the mate would need an infinite radius)"
        )
    return law


def _kind(curve: CurveParams) -> str:
    return {RatioParams: "ratio", WalkerParams: "walker"}.get(type(curve), "")


def apply_overrides(data: dict, overrides: list[str]) -> dict:
    """Apply ``KEY=VALUE`` overrides by dotted key; VALUE is read as TOML, else as a string."""
    data = _deep_copy(data)
    for item in overrides:
        if "=" not in item:
            raise ProfileError(f"--set {item!r}: must be KEY=VALUE, e.g. gear1.a=30")
        key, raw = item.split("=", 1)
        parts = key.strip().split(".")
        if not all(parts):
            raise ProfileError(f"--set {item!r}: the key must be dotted names, e.g. pair.driver_rpm")
        try:
            value = tomllib.loads(f"v = {raw}")["v"]
        except tomllib.TOMLDecodeError:
            value = raw
        node = data
        for part in parts[:-1]:
            child = node.setdefault(part, {})
            if not isinstance(child, dict):
                raise ProfileError(f"--set {item!r}: {part} is not a table")
            node = child
        node[parts[-1]] = value
    return data


def _deep_copy(data):
    if isinstance(data, dict):
        return {k: _deep_copy(v) for k, v in data.items()}
    if isinstance(data, list):
        return [_deep_copy(v) for v in data]
    return data


def load_profile(path: str | Path, overrides: list[str] = (), *, unset=()):
    """Read, override and validate one profile file."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise ProfileError(f"{path}: cannot read the profile ({exc.strerror})") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ProfileError(f"{path}: not valid TOML ({exc})") from None
    data = apply_overrides(data, list(overrides))
    try:
        return parse_profile(data, default_name=path.stem)
    except ProfileError as exc:
        raise ProfileError("\n".join(f"{path}: {line}" for line in str(exc).splitlines())) from None


_OTHER_KEYS = {
    "roller-body": (
        {"name", "title", "mechanism", "body", "kinematics", "teeth", "bore", "output"},
        {"scale", "roller_radius", "direction", "amplitude", "m", "f", "g"},
    ),
    "rolling-wheel": ({"name", "title", "mechanism", "drive", "output"}, {"r", "R", "L", "H", "driver_rpm", "travel"}),
    "carrier-train": (
        {"name", "title", "mechanism", "train", "bore", "output"},
        {
            "module",
            "teeth",
            "meshes",
            "names",
            "gear1_rpm",
            "carrier_rpm",
            "gear1_eps",
            "carrier_eps",
            "pressure_angle_deg",
        },
    ),
}


def _terms(r: _Reader, key: str, t: dict) -> tuple[tuple[int, float, float], ...]:
    raw = t.get(key, [])
    out = []
    if not isinstance(raw, list):
        r.fail(key, raw, "must be a list of [order, cos, sin] triples")
        return ()
    for n, term in enumerate(raw):
        if not (
            isinstance(term, list)
            and len(term) == 3
            and isinstance(term[0], int)
            and term[0] >= 1
            and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in term[1:])
        ):
            r.errors.append(f"{r.key(key)}[{n}] = {_show(term)}: must be [order, cos, sin], order an integer ≥ 1")
        elif term[0] % 3:
            r.errors.append(
                f"{r.key(key)}[{n}] = {_show(term)}: the order must be a multiple of 3 — the three "
                "rollers touch the body together only if the oscillation repeats every 120°"
            )
        else:
            out.append((int(term[0]), float(term[1]), float(term[2])))
    return tuple(out)


def _other(mechanism: str, data: dict, default_name: str):
    errors: list[str] = []
    top = _Reader(data, "", errors)
    top_keys, main_keys = _OTHER_KEYS[mechanism]
    top.unknown(top_keys)
    name = top.text("name", default_name)
    if name and not all(ch.isalnum() or ch in "-_" for ch in name):
        top.fail("name", name, "must use only letters, digits, '-' and '_' (it names a folder)")
    title = top.text("title", "")
    table = {"roller-body": "body", "rolling-wheel": "drive", "carrier-train": "train"}[mechanism]
    t = _table(data, table, errors)
    r = _Reader(t, f"{table}.", errors)
    r.unknown(main_keys)
    to = _table(data, "output", errors, required=False)
    o = _Reader(to, "output.", errors)
    o.unknown(_TABLE_KEYS["output"])
    output = _output(o, to, errors)
    length = "a length in mm"
    if mechanism == "roller-body":
        direction = r.text("direction", "vertical", choices=("horizontal", "vertical", "series"))
        m = r.integer("m", 3) if direction != "series" else 3
        if direction != "series" and m % 3:
            r.fail(
                "m",
                m,
                "must be a multiple of 3: the three rollers touch the body together only if the "
                "oscillation repeats every 120°",
            )
        kin = _Reader(_table(data, "kinematics", errors, required=False), "kinematics.", errors)
        kin.unknown({"rpm"})
        tt = _table(data, "teeth", errors, required=False)
        tr = _Reader(tt, "teeth.", errors)
        tr.unknown({"roller_count", "pressure_angle_deg"})
        roller_teeth = tr.integer("roller_count", minimum=8) if "roller_count" in tt else None
        angle = tr.number("pressure_angle_deg", 20.0, minimum=10, maximum=35, what="an angle in degrees")
        params = RollerBodyParams(
            name=name,
            title=title,
            scale=r.number("scale", 100.0, positive=True, what="mm per unit of R"),
            roller_radius=r.number("roller_radius", 0.1, minimum=0, below=1, what="a radius in units of R"),
            direction=direction,
            amplitude=r.number("amplitude", 0.1, minimum=0, what="an amplitude in units of R")
            if direction != "series"
            else 0.0,
            m=m,
            f=_terms(r, "f", t),
            g=_terms(r, "g", t),
            rpm=kin.number("rpm", 90.0, positive=True, what="a speed in rev/min"),
            bore=_bore(_table(data, "bore", errors, required=False), errors),
            output=output,
            roller_teeth=roller_teeth,
            pressure_angle=math.radians(angle) if math.isfinite(angle) else math.nan,
        )
    elif mechanism == "rolling-wheel":
        params = RollingWheelParams(
            name=name,
            title=title,
            r=r.number("r", what=length, positive=True),
            R=r.number("R", what=length, positive=True),
            L=r.number("L", what=length, positive=True),
            H=r.number("H", what=length, minimum=0),
            driver_rpm=r.number("driver_rpm", 30.0, positive=True, what="a speed in rev/min"),
            travel=r.number("travel", 100.0, positive=True, what=length),
            output=output,
        )
        if all(map(math.isfinite, (params.r, params.R, params.L, params.H))) and params.H < params.R - params.r:
            r.fail(
                "H",
                params.H,
                f"must be ≥ R − r = {params.R - params.r:g} mm: the rack slopes up to wheel 1 "
                "(H = R − r is the horizontal case)",
            )
        if all(map(math.isfinite, (params.L, params.travel))) and params.travel >= params.L:
            r.fail("travel", params.travel, f"must be under drive.L = {params.L:g} mm (wheel 2 would pass wheel 1)")
    else:
        teeth = t.get("teeth")
        if not (
            isinstance(teeth, list)
            and len(teeth) >= 2
            and all(isinstance(z, int) and not isinstance(z, bool) and z >= 8 for z in teeth)
        ):
            r.fail("teeth", teeth, "must be a list of at least two tooth counts, each an integer ≥ 8")
            teeth = [20, 20]
        meshes = t.get("meshes", ["external"] * (len(teeth) - 1))
        if not (
            isinstance(meshes, list)
            and len(meshes) == len(teeth) - 1
            and all(x in ("external", "internal") for x in meshes)
        ):
            r.fail("meshes", meshes, f"must be a list of {len(teeth) - 1} entries, each 'external' or 'internal'")
            meshes = ["external"] * (len(teeth) - 1)
        for k, mesh in enumerate(meshes):
            if mesh == "internal" and abs(teeth[k] - teeth[k + 1]) < 12:
                r.fail(
                    "teeth",
                    teeth,
                    f"an internal mesh needs the ring at least 12 teeth larger than its pinion "
                    f"(gears {k + 1} and {k + 2})",
                )
        names = t.get("names", [f"gear{k + 1}" for k in range(len(teeth))])
        if not (
            isinstance(names, list)
            and len(names) == len(teeth)
            and len(set(names)) == len(names)
            and all(isinstance(x, str) and x and all(ch.isalnum() or ch in "-_" for ch in x) for x in names)
        ):
            r.fail("names", names, f"must be {len(teeth)} distinct names of letters, digits, '-' or '_'")
            names = [f"gear{k + 1}" for k in range(len(teeth))]
        params = CarrierTrainParams(
            name=name,
            title=title,
            module=r.number("module", what="a module in mm", positive=True),
            teeth=tuple(teeth),
            meshes=tuple(meshes),
            names=tuple(names),
            gear1_rpm=r.number("gear1_rpm", 0.0, what="a speed in rev/min"),
            carrier_rpm=r.number("carrier_rpm", 0.0, what="a speed in rev/min"),
            gear1_eps=r.number("gear1_eps", 0.0, what="an angular acceleration in rad/s²"),
            carrier_eps=r.number("carrier_eps", 0.0, what="an angular acceleration in rad/s²"),
            pressure_angle=math.radians(
                r.number("pressure_angle_deg", 20.0, minimum=10, maximum=35, what="an angle in degrees")
            ),
            bore=_bore(_table(data, "bore", errors, required=False), errors),
            output=output,
        )
    if errors:
        raise ProfileError("\n".join(errors))
    return params


ProfileParams = GearPairParams | RollerBodyParams | RollingWheelParams | CarrierTrainParams
