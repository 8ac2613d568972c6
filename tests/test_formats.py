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


def test_the_page_names_a_file_by_its_formats_entry_not_its_name():
    from gearcad.export.html_files import section_files

    def _what(name, entry):  # the "what" cell of the page's row for the file
        return section_files({name: entry}, "index.html").split("</td><td>")[2]

    three_mf = formats.by_name("3mf")
    assert [three_mf.whole_of(s) for s in ("plate", "plate-2", "assembly", "plates", "gear1")] == [
        "plate",
        "plate",
        "assembly",
        None,
        None,
    ]
    # a part named like a whole of another format is still a part; a whole says what it is
    assert _what("sheet.stl", {"kind": "stl", "part": "sheet"}).startswith("part sheet")
    assert _what("sheet.svg", {"kind": "svg", "part": "sheet"}).startswith(formats.WHOLES["sheet"])
    assert _what("plate-2.3mf", {"kind": "3mf", "part": "plate-2"}).startswith("print plate")
    # only the loop's own report is "the report", not any .json
    assert "the report" in _what("report.json", {"kind": "json"})
    assert "the report" not in _what("other.json", {"kind": "json"})
