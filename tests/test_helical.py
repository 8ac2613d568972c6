"""Helical and herringbone gears: transverse sections against the rotation oracle, the section
spacing bound, the lofted solid (watertight, volume), the mesh proof across the face width."""

import math
from dataclasses import replace

import manifold3d as m3d
import numpy as np
import pytest
import trimesh

from gearcad.bench.helical import helical_benchmark
from gearcad.errors import DesignError
from gearcad.export.loft import loft
from gearcad.export.mesh import extrude
from gearcad.geometry.outline import Outline, ring_area, rotate
from gearcad.geometry.rings import bore_ring
from gearcad.mechanisms.pair_pitch import pitch_design
from gearcad.pitch import shapes
from gearcad.pitch.curve import PitchCurve
from gearcad.profiles import parse_profile
from gearcad.teeth.frame import arc_frame
from gearcad.teeth.gear import cut_teeth
from gearcad.teeth.helical import helical_sections, mid_section, pair_sections, ring_distance, section_mesh
from gearcad.teeth.helix import helix_data, transverse_teeth
from gearcad.teeth.mesh import mesh_check
from gearcad.teeth.pair import cut_pair
from gearcad.teeth.plan import plan_teeth
from gearcad.tolerances import DEFAULT

BETA = math.radians(30)


def _pair(gear1: dict, gear2: dict, teeth: dict, tol: float, beta: float):
    params = parse_profile(
        {"gear1": gear1, "gear2": gear2, "teeth": teeth, "output": {"tolerance": tol}}, default_name="helical"
    )
    t = replace(DEFAULT, outline_mm=tol)
    pitch = pitch_design(params, tol=t)
    alike = pitch.mate_shape_difference is not None and pitch.mate_shape_difference < 1e-6
    toothed = cut_pair(
        pitch.pair,
        pitch.gears,
        transverse_teeth(params.teeth, beta),
        mate_rotation=pitch.mate_rotation if alike else None,
        tol=t,
    )
    return params, pitch, toothed


@pytest.fixture(scope="module")
def spur():
    """A circle of 20 teeth (m_t = 2, r = 20 mm) and its 40-tooth mate, β = 30°, b = 6 mm."""
    tol = 0.01
    _, pitch, toothed = _pair(
        {"name": "pinion", "curve": "circle", "radius": 20.0},
        {"name": "gear", "lobes": 2},
        {"count": 20},
        tol,
        BETA,
    )
    sections = pair_sections(toothed, helix_angle=BETA, herringbone=False, face_width=6.0, tolerance=tol)
    return tol, pitch, toothed, sections


@pytest.fixture(scope="module")
def spur_base(spur):
    """The pinion's base section cut finely (at a 40th of the tolerance): the exact section."""
    tol, _, toothed, _ = spur
    return cut_teeth(toothed.frames[0], toothed.gears[0].rack, 20, toothed.plan.phases[0], tolerance=tol / 40)


@pytest.fixture(scope="module")
def ellipse():
    """The focus-ellipse pair (a = 25, b = 15 mm, m_n = 1), herringbone, β = 25°, b = 8 mm."""
    tol, beta = 0.02, math.radians(25)
    params, pitch, toothed = _pair(
        {"name": "driver", "curve": "ellipse", "pivot": "focus", "a": 25.0, "b": 15.0},
        {"name": "follower", "lobes": 1},
        {"module": 1.0},
        tol,
        beta,
    )
    sections = pair_sections(toothed, helix_angle=beta, herringbone=True, face_width=8.0, tolerance=tol)
    return tol, beta, params, pitch, toothed, sections


def _manifold(solid) -> m3d.Manifold:
    return m3d.Manifold(m3d.Mesh64(vert_properties=solid.vertices, tri_verts=solid.triangles.astype(np.uint64)))


def _slice(manifold: m3d.Manifold, z: float) -> np.ndarray:
    """The outer ring of the solid's section at height z."""
    return np.asarray(max(manifold.slice(z).to_polygons(), key=lambda p: abs(ring_area(np.asarray(p)))))


# ----------------------------------------------------------------------------- the helical rack


def test_transverse_rack_and_report_numbers_follow_the_textbook():
    """m_t = m_n/cos β, tan α_t = tan α_n/cos β, heights kept; axial pitch π·m_n/sin β and
    overlap ratio b·sin β/(π·m_n) (m_n = 2, β = 30°, b = 20: p_x = 4π, ε_β = 5/π)."""
    spec = type("T", (), {"module": 2.0, "count": None, "pressure_angle": math.radians(20), "addendum": 1.0,
                          "dedendum": 1.25, "tip_radius": 0.38, "profile_shift": 0.5, "backlash": 0.1,
                          "clearance": 0.0})()  # fmt: skip
    t = transverse_teeth(spec, BETA)
    assert t.module == pytest.approx(4 / math.sqrt(3), rel=1e-14)
    assert math.tan(t.pressure_angle) == pytest.approx(math.tan(math.radians(20)) * 2 / math.sqrt(3), rel=1e-14)
    for name in ("addendum", "dedendum", "tip_radius", "profile_shift"):
        assert getattr(t, name) * t.module == pytest.approx(getattr(spec, name) * 2.0, rel=1e-14)
    assert t.backlash == 0.1
    h = helix_data(t.module, BETA, face_width=20.0, herringbone=False, normal_pressure_angle=math.radians(20))
    assert h.normal_module == pytest.approx(2.0, rel=1e-14)
    assert h.axial_pitch == pytest.approx(4 * math.pi, rel=1e-14)
    assert h.overlap_ratio == pytest.approx(5 / math.pi, rel=1e-14)
    herring = helix_data(t.module, BETA, face_width=20.0, herringbone=True, normal_pressure_angle=math.radians(20))
    assert herring.overlap_ratio == pytest.approx(2.5 / math.pi, rel=1e-14)  # per helix
    flat = helix_data(2.0, 0.0, face_width=20.0, herringbone=False, normal_pressure_angle=math.radians(20))
    assert flat.axial_pitch == math.inf and flat.overlap_ratio == 0.0
    with pytest.raises(DesignError, match="helix_angle_deg"):
        transverse_teeth(spec, math.radians(90))


# ----------------------------------------------------------------------------- rotation oracle


def test_circular_sections_are_the_base_section_turned(spur):
    """On a circle the section at z is the base section turned by z·tan β/r (gear 1) and by
    −z·tan β/r2 (its mate, opposite hand): vertex for vertex.  The other hand is far off."""
    tol, pitch, toothed, sections = spur
    for i, g in enumerate(sections.gears):
        r = (20.0, 40.0)[i]
        sign = (1, -1)[i]
        assert np.all(np.diff(g.heights) > 0) and g.heights[0] == 0 and g.heights[-1] == pytest.approx(6.0)
        assert len(g.heights) >= 3
        for z, ring, shift in zip(g.heights, g.rings, g.shifts):
            assert shift == pytest.approx(sign * z * math.tan(BETA), abs=1e-12)
            turned = rotate(g.rings[0], sign * z * math.tan(BETA) / r)
            assert np.max(np.linalg.norm(ring - turned, axis=1)) < 1e-9
            if z > 0:
                wrong = rotate(g.rings[0], -sign * z * math.tan(BETA) / r)
                assert ring_distance(ring, wrong) > 20 * tol


def test_circular_loft_between_sections_is_the_turned_section_within_tolerance(spur, spur_base):
    """Slices of the lofted pinion at mid-interval (where the twist errs most) and elsewhere are
    the finely cut base section turned by z·tan β/r, within the tolerance."""
    tol, pitch, toothed, sections = spur
    g = sections.gears[0]
    manifold = _manifold(loft(g.heights, g.rings, name="pinion"))
    base = spur_base
    mids = 0.5 * (g.heights[:-1] + g.heights[1:])
    for z in [*mids, 0.37 * g.heights[1], 5.9]:
        exact = rotate(base.outline.outer, z * math.tan(BETA) / 20.0)
        assert ring_distance(_slice(manifold, z), exact) <= tol


def test_the_spacing_bound_is_what_keeps_the_loft_within_tolerance(spur, spur_base):
    """The bound and its floor bracket the spacing used; the measured mid-interval error is
    within the tolerance; and a loft spaced far wider than the bound (two sections over the
    face) strays well past the tolerance — the bound is doing work."""
    tol, pitch, toothed, sections = spur
    s = sections.spacing
    assert s.floor <= s.spacing <= s.bound
    assert s.measured <= tol * (1 - DEFAULT.fine_fraction)
    r, t = 20.0, math.tan(BETA)
    base = spur_base
    wide = pair_sections(toothed, helix_angle=BETA, herringbone=False, face_width=6.0, tolerance=tol, spacing=6.0)
    g = wide.gears[0]
    assert len(g.heights) == 2
    exact = rotate(base.outline.outer, 3.0 * t / r)
    assert ring_distance(mid_section(g.rings[0], g.rings[1]), exact) > 5 * tol


def test_the_path_curvature_bound_holds_for_generated_points(ellipse):
    """|dP/dσ| ≤ V and |d²P/dσ²| ≤ A for rack points (a, v) = (∓v·cot α, v) on the flank line,
    by central differences of P = C + a·T + v·N over the ellipse — the premises of the bound."""
    tol, beta, params, pitch, toothed, sections = ellipse
    s = sections.spacing
    frame, rack = toothed.frames[0], toothed.gears[0].rack
    sigma = np.linspace(0, frame.perimeter, 1500, endpoint=False)
    h = 1e-3
    for v in np.linspace(rack.v_low, rack.v_tip, 7):
        a = -v * rack.cot_a

        def p(x, a=a, v=v):
            c, tan, n = frame.frame(x)
            return c + a * tan + v * n

        first = (p(sigma + h) - p(sigma - h)) / (2 * h)
        second = (p(sigma + h) - 2 * p(sigma) + p(sigma - h)) / h**2
        assert np.max(np.linalg.norm(first, axis=1)) <= s.lateral_speed
        assert np.max(np.linalg.norm(second, axis=1)) <= s.path_curvature * (1 + 1e-3)


# ----------------------------------------------------------------------------- the solid


def test_loft_is_a_watertight_twisted_prism_of_the_right_volume(spur, spur_base):
    """manifold3d accepted it (loft checks the status) and trimesh agrees it is watertight and
    consistently wound.  The volume is the section's area times the thickness, within the
    lateral surface (≤ perimeter · b · √(1 + (tan β·V)²)) times the tolerance."""
    tol, pitch, toothed, sections = spur
    g = sections.gears[0]
    solid = loft(g.heights, g.rings, name="pinion")
    mesh = trimesh.Trimesh(solid.vertices, solid.triangles, process=False)
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert mesh.euler_number == 2
    assert mesh.volume == pytest.approx(solid.volume, rel=1e-9)
    exact = spur_base
    area = ring_area(exact.outline.outer)
    perimeter = float(np.sum(np.linalg.norm(np.diff(g.rings[0], axis=0, append=g.rings[0][:1]), axis=1)))
    slope = math.sqrt(1 + (math.tan(BETA) * sections.spacing.lateral_speed) ** 2)
    assert abs(solid.volume - area * 6.0) <= perimeter * 6.0 * slope * tol
    # exactly: each slice's vertices move linearly along the loft's edges, so its area is
    # quadratic in z and Simpson's rule over each interval (mid-slice = mid_section) is exact
    simpson = sum(
        (hi - lo) / 6 * (ring_area(a) + 4 * ring_area(mid_section(a, b)) + ring_area(b))
        for lo, hi, a, b in zip(g.heights[:-1], g.heights[1:], g.rings[:-1], g.rings[1:])
    )
    assert solid.volume == pytest.approx(simpson, rel=1e-12)


def test_a_straight_loft_with_bore_and_chamfer_is_the_extrusion(spur):
    """β = 0: one section top and bottom; with a bore it is the solid export.mesh.extrude builds
    (equal volume to round-off), watertight with one hole; chamfered, the two agree but for the
    quads beside the inset's collapsed segments (not planar), which they split differently."""
    tol, pitch, toothed, _ = spur
    straight = pair_sections(toothed, helix_angle=0.0, herringbone=False, face_width=6.0, tolerance=tol, chamfer=0.5)
    g = straight.gears[0]
    assert list(g.heights) == [0.0, 0.5, 5.5, 6.0]
    hole = bore_ring(5.0, tol)
    outline = Outline((g.rings[0], hole))
    solid = loft(g.heights, g.rings, name="pinion", holes=[hole])
    # manifold3d's own extrusion snaps vertices within its tolerance; the loft keeps them
    assert solid.volume == pytest.approx(outline.area * 6.0, rel=1e-12)
    assert solid.volume == pytest.approx(extrude(outline, 6.0, name="pinion").volume, rel=1e-9)
    chamfered = loft(g.heights, g.rings, name="pinion", holes=[hole], chamfer=0.5)
    reference = extrude(outline, 6.0, name="pinion", chamfer=0.5)
    assert chamfered.volume == pytest.approx(reference.volume, rel=1e-5)
    assert solid.volume - chamfered.volume > 100 * abs(chamfered.volume - reference.volume)
    for s in (solid, chamfered):
        mesh = trimesh.Trimesh(s.vertices, s.triangles, process=False)
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.euler_number == 0
        assert np.min(s.vertices[:, 2]) == 0.0 and np.max(s.vertices[:, 2]) == 6.0


def test_a_chamfered_helical_loft_is_watertight_and_smaller(spur):
    tol, pitch, toothed, _ = spur
    chamfered = pair_sections(toothed, helix_angle=BETA, herringbone=False, face_width=6.0, tolerance=tol, chamfer=0.4)
    g = chamfered.gears[0]
    assert 0.4 in g.heights.tolist() and pytest.approx(5.6) in g.heights.tolist()
    hole = bore_ring(5.0, tol)
    solid = loft(g.heights, g.rings, name="pinion", holes=[hole], chamfer=0.4)
    plain = loft(g.heights, g.rings, name="pinion", holes=[hole])
    mesh = trimesh.Trimesh(solid.vertices, solid.triangles, process=False)
    assert mesh.is_watertight and mesh.is_winding_consistent
    assert 0 < plain.volume - solid.volume < 2 * 0.4**2 / 2 * 400  # two 45° edge bands, perimeter < 400
    with pytest.raises(DesignError, match="chamfer"):
        loft(g.heights, g.rings, name="pinion", chamfer=3.0)


def test_loft_is_deterministic(spur):
    tol, pitch, toothed, sections = spur
    g = sections.gears[1]
    a, b = loft(g.heights, g.rings, name="gear"), loft(g.heights, g.rings, name="gear")
    assert np.array_equal(a.vertices, b.vertices) and np.array_equal(a.triangles, b.triangles)
    assert a.xml == b.xml


# ----------------------------------------------------------------------------- herringbone ellipse


def test_herringbone_sections_are_symmetric_about_mid_height(ellipse):
    tol, beta, params, pitch, toothed, sections = ellipse
    for g in sections.gears:
        n = len(g.heights)
        assert n % 2 == 1 and g.heights[n // 2] == 4.0
        np.testing.assert_allclose(g.heights + g.heights[::-1], 8.0, rtol=0, atol=1e-12)
        for k in range(n):
            assert np.array_equal(g.rings[k], g.rings[n - 1 - k])
        # and the helix did turn: the middle section is not the bottom one
        assert ring_distance(g.rings[n // 2], g.rings[0]) > 0.5
        assert abs(g.shifts[n // 2]) == pytest.approx(4.0 * math.tan(beta), rel=1e-12)
    assert sections.gears[0].hand == "herringbone-right" and sections.gears[1].hand == "herringbone-left"


def test_sections_mesh_at_both_ends_and_the_middle(ellipse):
    """The planar mesh proof holds on the section pairs at z = 0, b/2 and b; a section of the
    driver paired with a section of the follower from another height does not mesh."""
    tol, beta, params, pitch, toothed, sections = ellipse
    play = params.teeth.backlash
    checks = section_mesh(pitch.pair, sections, toothed.frames, tolerance=tol, play=play)
    assert [z for z, _ in checks] == [0.0, 4.0, 8.0]
    assert all(m.meshes for _, m in checks)
    g1, g2 = sections.gears
    n = len(g1.heights)
    # out of phase everywhere: a quarter of the positions shows it as well as all of them
    wrong = mesh_check(
        pitch.pair, (g1.gears[n // 2], g2.gears[0]), toothed.frames, tolerance=tol, play=play, positions=90
    )
    assert not wrong.meshes and wrong.max_overlap > 20 * wrong.allowed_overlap


def test_elliptic_herringbone_pair_lofts_within_tolerance(ellipse):
    """Both gears loft to watertight solids whose mid-interval slices are the exactly cut
    sections there within the tolerance, with the volume ∫ area dz (trapezoid over sections)."""
    tol, beta, params, pitch, toothed, sections = ellipse
    for i, g in enumerate(sections.gears):
        solid = loft(g.heights, g.rings, name=f"gear{i + 1}")
        mesh = trimesh.Trimesh(solid.vertices, solid.triangles, process=False)
        assert mesh.is_watertight and mesh.is_winding_consistent and mesh.euler_number == 2
        manifold = _manifold(solid)
        sign = (1, -1)[i]
        n = len(g.heights)
        # every interval of the driver; the follower's two beside the herringbone's kink
        for k in range(n - 1) if i == 0 else (n // 2 - 1, n // 2):
            z = 0.5 * (g.heights[k] + g.heights[k + 1])
            climbed = min(z, 8.0 - z)
            exact = cut_teeth(
                toothed.frames[i],
                toothed.gears[i].rack,
                toothed.plan.teeth[i],
                toothed.plan.phases[i] + sign * climbed * math.tan(beta),
                tolerance=tol / 20,
            )
            assert ring_distance(_slice(manifold, z), exact.outline.outer) <= tol
        areas = np.array([ring_area(r) for r in g.rings])
        perimeter = float(np.sum(np.linalg.norm(np.diff(g.rings[0], axis=0), axis=1)))
        trapezoid = float(np.sum(np.diff(g.heights) * (areas[:-1] + areas[1:]) / 2))
        assert abs(solid.volume - trapezoid) <= perimeter * 8.0 * tol


def test_the_identical_ellipses_become_mirror_image_parts(ellipse):
    """The planar pair is one part twice (the follower is the driver turned by δ); with a helix the
    follower has the other hand, so it is the driver mirrored (z ↦ −z, i.e. β ↦ −β) and turned —
    vertex for vertex — and not the driver turned."""
    tol, beta, params, pitch, toothed, sections = ellipse
    assert toothed.plan.identical
    mirrored = pair_sections(
        toothed, helix_angle=-beta, herringbone=True, face_width=8.0, tolerance=tol, spacing=sections.spacing.spacing
    )
    driver, follower = mirrored.gears[0], sections.gears[1]
    assert np.array_equal(driver.heights, follower.heights)
    delta = pitch.mate_rotation
    for k in range(len(follower.heights)):
        assert np.max(np.linalg.norm(rotate(driver.rings[k], -delta) - follower.rings[k], axis=1)) < 1e-9
    k = len(follower.heights) // 2
    assert np.max(np.linalg.norm(rotate(sections.gears[0].rings[k], -delta) - follower.rings[k], axis=1)) > 1.0


def test_sections_resample_within_a_quarter_tolerance(ellipse):
    tol, beta, params, pitch, toothed, sections = ellipse
    for g in sections.gears:
        assert g.deviation <= tol * DEFAULT.fine_fraction
        assert g.rings.shape[0] == len(g.heights) and not g.rings.flags.writeable


# ----------------------------------------------------------------------------- refusals, bench


def test_a_pitch_curve_with_corners_is_refused_in_one_line():
    """r = 10 + |sin φ| has corners at 0 and π: a helix cannot follow them."""
    v = PitchCurve(
        "v",
        r=lambda p: 10 + np.abs(np.sin(p)),
        dr=lambda p: np.sign(np.sin(p)) * np.cos(p),
        d2r=lambda p: -np.abs(np.sin(p)),
        lobes=2,
        breaks=(0.0, math.pi),
    )
    frame, circle = arc_frame(v), arc_frame(shapes.circle(10.0))
    plan = plan_teeth(frame, circle, (1, 1), count=20)
    with pytest.raises(DesignError) as err:
        helical_sections(
            (frame, circle), plan, (None, None), helix_angle=BETA, herringbone=True, face_width=5.0, tolerance=0.01
        )
    text = str(err.value)
    assert "\n" not in text and "corner" in text and "helix_angle_deg" in text and "gear1" in text


def test_helical_benchmark_rows():
    rows = helical_benchmark(face_widths=(2.0,), tolerances=(0.05,))
    (row,) = rows
    assert row["study"] == "helical" and row["n"] > 1000 and row["seconds"] > 0 and row["sections"] >= 2


def test_solid_picture(tmp_path):
    """The rendered solids: a PNG of the figure's size showing both items' colours."""
    from PIL import Image

    from gearcad.export.charts.solid import draw_solids
    from gearcad.export.mesh import SolidItem

    square = np.array([[-10.0, -10.0], [10.0, -10.0], [10.0, 10.0], [-10.0, 10.0]])
    solid = loft([0.0, 4.0], np.stack([square, rotate(square, 0.3)]), name="twisted")
    path = tmp_path / "solid.png"
    draw_solids(path, [SolidItem(solid), SolidItem(solid, 0.5, (30.0, 0.0, 0.0))], title="pair")
    image = np.asarray(Image.open(path).convert("RGB")).astype(int)
    assert image.shape == (660, 1100, 3)
    orange = (image[..., 0] > image[..., 2] + 60).sum()
    blue = (image[..., 2] > image[..., 0] + 60).sum()
    assert orange > 5000 and blue > 5000


def test_the_built_herringbone_pair_is_pictured(built):
    """solid.png as written by a build (thinned solids, placed as assembled): listed in the
    report, the figure's size, both gears' colours on it."""
    import json

    from PIL import Image

    folder = built / "herringbone_elliptic"
    report = json.loads((folder / "report.json").read_text(encoding="utf-8"))
    assert report["files"]["solid.png"]["bytes"] == (folder / "solid.png").stat().st_size
    image = np.asarray(Image.open(folder / "solid.png").convert("RGB")).astype(int)
    assert image.shape == (660, 1100, 3)
    orange = (image[..., 0] > image[..., 2] + 60).sum()
    blue = (image[..., 2] > image[..., 0] + 60).sum()
    assert orange > 20000 and blue > 20000
