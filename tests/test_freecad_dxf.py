"""FreeCAD reads a part's DXF as one face per ring on its layer with the settings
docs/consumers.md names (issue 24, item 7), and its default shows why they are needed.

FreeCAD 0.20's DXF importer (the C++ one, its default) makes one object per edge of every
polyline and drops the layers; with *Group layers into blocks* (preference ``groupLayers``)
it makes one object per layer, ``CUT`` and ``MARK``, whose edges join into one closed wire
per ring (``Part.sortEdges``, as Draft ▸ Draft to Sketch joins them: not run here, it takes
seconds), and those wires make the part's face at its designed area.  Runs where
``freecadcmd`` is installed, with a throw-away user configuration (the user's own preferences
are neither read nor changed)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess

import pytest

PARTS = (("elliptic_focus", "driver"), ("planetary_internal", "ring"))
"""A toothed part with a pilot hole and engraving, and the thin internal ring."""

_SCRIPT = """
import json, FreeCAD, Import, Part
draft = FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Mod/Draft")
found = {}
for path in PATHS:
    found[path] = {}
    for group in (False, True):
        draft.SetBool("groupLayers", group)
        doc = FreeCAD.newDocument()
        FreeCAD.setActiveDocument(doc.Name)
        Import.readDXF(path)
        doc.recompute()
        row = {"objects": sorted(o.Label for o in doc.Objects)}
        if group:
            cut = doc.getObjectsByLabel("CUT")[0]
            wires = [Part.Wire(edges) for edges in Part.sortEdges(cut.Shape.Edges)]
            face = Part.makeFace(wires, "Part::FaceMakerBullseye")
            row.update(
                rings=[w.isClosed() for w in wires],
                area=face.Area,
                mark_edges=len(doc.getObjectsByLabel("MARK")[0].Shape.Edges),
            )
        found[path][str(group)] = row
        FreeCAD.closeDocument(doc.Name)
print("GEARCAD " + json.dumps(found))
"""


@pytest.fixture(scope="module")
def freecad_reads(built, tmp_path_factory):
    freecad = shutil.which("freecadcmd") or shutil.which("FreeCADCmd")
    if freecad is None:
        pytest.skip("FreeCAD is not installed: apt-get install -y freecad (or python3 tasks.py consumers)")
    home = tmp_path_factory.mktemp("freecad_home")
    paths = [str(built / profile / f"{part}.dxf") for profile, part in PARTS]
    script = home / "read.py"
    script.write_text(f"PATHS = {paths!r}\n{_SCRIPT}", encoding="utf-8")
    env = {**os.environ, "HOME": str(home), "XDG_CONFIG_HOME": str(home), "XDG_DATA_HOME": str(home)}
    run = subprocess.run([freecad, str(script)], capture_output=True, text=True, timeout=300, env=env, cwd=home)
    line = next((x for x in run.stdout.splitlines() if x.startswith("GEARCAD ")), None)
    assert line is not None, run.stdout[-2000:] + run.stderr[-2000:]
    found = json.loads(line.removeprefix("GEARCAD "))
    return {key: found[path] for key, path in zip(PARTS, paths)}


def test_freecad_default_import_splits_each_part_and_groups_its_layers_into_closed_rings(freecad_reads, built):
    """Both parts read in one test (one FreeCAD run, also under pytest-xdist): by default one
    object per polyline segment and no layers; with *Group layers into blocks* ``CUT`` and
    ``MARK``, one closed ring per outline and hole, the face at the designed area."""
    for profile, part in PARTS:
        where = f"{profile}/{part}"
        default = freecad_reads[(profile, part)]["False"]["objects"]
        assert len(default) > 100, where  # one object per polyline segment
        assert "CUT" not in default and "MARK" not in default, where
        report = json.loads((built / profile / "report.json").read_text(encoding="utf-8"))
        entry = next(p for p in report["parts"] if p["name"] == part)
        grouped = freecad_reads[(profile, part)]["True"]
        assert grouped["objects"] == ["CUT", "MARK"], where
        assert grouped["rings"] == [True] * (entry["holes"] + 1), where  # the outline and each hole, closed
        assert grouped["area"] == pytest.approx(entry["area"], rel=5e-4), where  # the face with its holes
        assert grouped["mark_edges"] > 0, where  # the engraving kept, on its own layer
