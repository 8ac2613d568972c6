"""Chamfered end faces within the tolerance of the exact mitred inset (issue 25, item 5)."""

from dataclasses import replace

import numpy as np
import pytest
import shapely
import trimesh

from gearcad.geometry.inset import inset_ring
from gearcad.geometry.outline import ring_area


def _hausdorff(ring: np.ndarray, polygon) -> float:
    """Both ways: the ring's vertices to the polygon's boundary, the boundary (every 4 µm: a
    chord's sag there is nanometres) to the ring."""
    line = shapely.LinearRing(ring)
    there = shapely.distance(shapely.points(ring), polygon.exterior).max()
    back = shapely.distance(shapely.points(shapely.get_coordinates(shapely.segmentize(polygon.exterior, 0.004))), line)
    return float(max(there, back.max()))


def _within(ring: np.ndarray, polygon, distance: float) -> bool:
    """Whether the ring and the polygon's boundary are within ``distance`` of each other both
    ways (each inside a band of that half-width round the other): the Hausdorff test, without
    measuring every pair of points."""
    line = shapely.LinearRing(ring)
    return bool(
        shapely.buffer(polygon.exterior, distance, quad_segs=32).covers(line)
        and shapely.buffer(line, distance, quad_segs=32).covers(polygon.exterior)
    )


def test_a_short_tip_land_is_dropped_where_the_flanks_insets_meet():
    """A tooth with a 0.1 mm tip land, inset 0.3 mm: the land's inset is eaten by the flanks', so
    the exact mitred inset (shapely's, mitre joins) ends where the flanks' inset lines meet; a
    ring inset vertex by vertex lands there (collapsing the land to its midpoint missed by 0.19 mm)."""
    tooth = np.array([(0.0, 0.0), (10.0, 0.0), (5.05, 8.0), (4.95, 8.0)])
    exact = shapely.Polygon(tooth).buffer(-0.3, join_style="mitre", mitre_limit=10)
    inset = inset_ring(tooth, 0.3)
    assert _hausdorff(inset, exact) < 1e-9
    assert np.array_equal(inset[2], inset[3]) and ring_area(inset) > 0
    # a long enough land keeps its own inset: the same as shapely's
    wide = np.array([(0.0, 0.0), (10.0, 0.0), (6.0, 8.0), (4.0, 8.0)])
    exact = shapely.Polygon(wide).buffer(-0.3, join_style="mitre", mitre_limit=10)
    assert _hausdorff(inset_ring(wide, 0.3), exact) < 1e-9


@pytest.fixture(scope="module")
def herringbone_z0():
    """The herringbone profile's sections at z = 0 (= z = b: the helix climbs back), cut finely
    (1e-4 mm, a hundredth of the 10 µm tolerance) at the phases the build cut them, with its
    clearance as a round offset."""
    from gearcad.mechanisms.pair_pitch import pitch_design
    from gearcad.profiles import load_profile
    from gearcad.teeth.gear import cut_teeth
    from gearcad.teeth.helix import transverse_teeth
    from gearcad.teeth.pair import cut_pair
    from gearcad.tolerances import DEFAULT

    params = load_profile("profiles/herringbone_elliptic.toml")
    tol = replace(DEFAULT, outline_mm=params.output.tolerance)
    pitch = pitch_design(params, tol=tol)
    spec = transverse_teeth(params.teeth, params.teeth.helix_angle)
    teeth = cut_pair(pitch.pair, pitch.gears, spec, mate_rotation=pitch.mate_rotation, tol=tol)
    exact = []
    for i, g in enumerate(teeth.gears):
        cut = cut_teeth(teeth.frames[i], g.rack, g.teeth, teeth.plan.phases[i], tolerance=1e-4)
        body = shapely.Polygon(cut.outline.outer).buffer(-params.teeth.clearance, quad_segs=256)
        exact.append(body.buffer(-params.output.chamfer, join_style="mitre", mitre_limit=10))
    return params, exact


def test_herringbone_chamfer_faces_are_the_exact_mitred_inset(built, herringbone_z0):
    """The written STL's bottom (z = 0) and top (z = b) faces of both gears: their outer rings
    within output.tolerance (10 µm) of the exact mitred inset, both ways (issue 25: 14.8 µm
    before, at the tooth tips where the inset dropped a short flank segment)."""
    params, exact = herringbone_z0
    b, tolerance = params.output.thickness, params.output.tolerance
    for name, reference in zip(("driver", "follower"), exact):
        mesh = trimesh.load(built / "herringbone_elliptic" / f"{name}.stl")
        for z in (0.0, b):
            flat = np.all(np.isclose(mesh.vertices[mesh.faces][..., 2], z, atol=1e-6), axis=1)
            face = shapely.union_all(shapely.polygons(mesh.vertices[mesh.faces[flat]][..., :2].astype(float)))
            assert face.geom_type == "Polygon" and len(face.interiors) == 1  # the cap, round its bore
            ring = np.asarray(face.exterior.coords)[:-1]
            assert len(ring) > 1000
            assert _within(ring, reference, tolerance), (name, z, _hausdorff(ring, reference))
