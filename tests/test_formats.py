"""The table of output formats: the profiles' choices and the written files derive from it."""

from gearcad import formats
from gearcad.export import files
from gearcad.profiles import DXF_FLAVOURS, FORMATS, OutputParams


def test_profiles_take_their_formats_and_flavours_from_the_table():
    assert FORMATS == tuple(f.name for f in formats.TABLE)
    assert OutputParams().formats == tuple(f.name for f in formats.TABLE if f.default) == ("dxf", "svg", "stl", "3mf")
    assert DXF_FLAVOURS == formats.by_name("dxf").flavours
    assert OutputParams().dxf == DXF_FLAVOURS[0]


def test_every_entry_names_a_writer_and_what_it_takes():
    for f in formats.TABLE:
        module, function = f.writer.split(":")
        if f.takes == "design":  # makes its own solids (STEP: OpenCASCADE, loaded only for it)
            assert (module, function) == ("step", "write_step_files") and f.wholes == ("assembly",), f
            continue
        assert module == "files" and callable(getattr(files, function)), f
        assert f.takes in {"drawing", "solid"} and set(f.wholes) <= {"assembly", "sheet", "plate"}


def test_a_build_writes_each_formats_files_as_the_table_says(built):
    import json

    report = json.loads((built / "spur_pair" / "report.json").read_text(encoding="utf-8"))
    parts = [p["name"] for p in report["parts"]]
    for f in (f for f in formats.TABLE if f.default):  # what the example profiles ask for
        expected = {f"{stem}.{f.extension}" for stem in [*parts, *f.wholes]}
        written = {name for name, entry in report["files"].items() if entry["kind"] == f.name}
        assert written == expected and all((built / "spur_pair" / n).stat().st_size > 0 for n in written)
