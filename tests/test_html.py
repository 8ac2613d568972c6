"""The HTML reports: well formed, self-contained, every link resolving, and rendered by a real browser."""

import json
import os
import re
import shutil
import subprocess
import tomllib
from html import unescape
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest
from PIL import Image

import gearcad
from gearcad.export.html import pivot_marking
from gearcad.export.html_index import index_entry, write_index
from gearcad.export.write import write_design

from .conftest import PROFILES, ROOT

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
SVG_NS = "http://www.w3.org/2000/svg"
VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source", "track", "wbr"}


def profile(name: str, **output):
    raw = tomllib.loads((ROOT / "profiles" / f"{name}.toml").read_text(encoding="utf-8"))
    if name == "roller_body_m3":
        del raw["teeth"]  # smooth body and rollers: designs in a fraction of a second
    raw.setdefault("output", {}).update(output)
    return gearcad.parse_profile(raw)


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """Two profiles written as a build writes them, and the page over both: the rolling wheels
    and the body on three rollers (a bore, a part placed three times).  No charts: the pages
    of every profile with every output (charts, animation) are read from the session's build
    (``built``)."""
    out = tmp_path_factory.mktemp("html") / "out"
    designs = {
        "rolling_wheel": gearcad.design(
            profile("rolling_wheel", tolerance=0.01, charts=False, animation=False, formats=["dxf", "svg", "3mf"])
        ),
        "roller_body_m3": gearcad.design(
            profile("roller_body_m3", tolerance=0.02, charts=False, animation=False, formats=["svg", "stl", "3mf"])
        ),
    }
    entries = []
    for name, d in designs.items():
        (out / name).mkdir(parents=True)
        write_design(d, out / name)
        report = json.loads((out / name / "report.json").read_text(encoding="utf-8"))
        entries.append(index_entry(report, f"{name}/index.html", d.summary))
    write_index(out / "index.html", entries)
    return out, designs


class Checker(HTMLParser):
    """Collects links, ids and text, and checks that every element is closed where it should be."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.stack, self.errors, self.links, self.ids, self.refs, self.text = [], [], [], set(), [], []

    def handle_starttag(self, tag, attrs):
        self._attrs(attrs)
        if tag not in VOID:
            self.stack.append(tag)

    def handle_startendtag(self, tag, attrs):
        self._attrs(attrs)

    def _attrs(self, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        for key in ("href", "src"):
            if key in a:
                (self.refs if a[key].startswith("#") else self.links).append(a[key])

    def handle_endtag(self, tag):
        if not self.stack or self.stack[-1] != tag:
            self.errors.append(f"</{tag}> closes {self.stack[-1:] or 'nothing'}")
        else:
            self.stack.pop()

    def handle_data(self, data):
        self.text.append(data)


def check_page(path: Path) -> Checker:
    """The page parses with every element closed, refers to nothing on the network (the SVG
    namespace is a name, not a download), and every link resolves to a file beside it."""
    text = path.read_text(encoding="utf-8")
    assert text.startswith("<!DOCTYPE html>")
    checker = Checker()
    checker.feed(text)
    checker.close()
    assert checker.errors == [] and checker.stack == []
    assert set(re.findall(r"(?i)https?://[^\s\"'<>)]+", text)) <= {SVG_NS}
    assert not re.search(r"(?i)(<script|<link|@import|url\()", text)  # nothing fetched, no script at all
    for link in checker.links:
        parts = urlsplit(link)
        assert not parts.scheme and not parts.netloc, link
        assert (path.parent / unquote(parts.path)).is_file(), link
    assert {r[1:] for r in checker.refs} <= checker.ids  # in-page links and <use> references resolve
    return checker


def test_profile_pages_link_every_file_and_name_every_finding(built, site):
    """Every profile's page as the build writes it beside every output (charts, animation,
    STEP), and the two pages of :func:`site`: each links every file beside it and names every
    finding and part its report gives."""
    folders = [p.parent for p in sorted(built.glob("*/index.html"))] + [site[0] / name for name in site[1]]
    assert len(folders) == len(PROFILES) + 2
    for folder in folders:
        checker = check_page(folder / "index.html")
        written = {p.name for p in folder.iterdir()} - {"index.html"}
        assert {unquote(link) for link in checker.links if "/" not in link} >= written, folder
        text = unescape(" ".join(checker.text))
        report = json.loads((folder / "report.json").read_text(encoding="utf-8"))
        for f in report["warnings"]:
            assert f["code"] in text and f["message"] in text, (folder, f)
        for part in report["parts"]:
            assert part["name"] in text, folder
    # the page shows some findings, not only "none"
    assert json.loads((built / "rolling_wheel" / "report.json").read_text(encoding="utf-8"))["warnings"]
    for name, d in site[1].items():  # the report's findings are the design's
        report = json.loads((site[0] / name / "report.json").read_text(encoding="utf-8"))
        assert [(f["code"], f["message"]) for f in report["warnings"]] == [(f.code, f.message) for f in d.findings]


def test_profile_page_says_what_marks_each_pivot(site):
    out, designs = site
    d = designs["roller_body_m3"]
    body, roller = d.part("body"), d.part("roller")
    # the profile's [bore] diameter = 8.0; the rollers get the default 1 mm pilot hole; both parts
    # carry an engraved cross at the pivot, and the report says the same
    assert pivot_marking(d, body).startswith("Ø8 mm bore and engraved cross ±")
    assert pivot_marking(d, roller).startswith("Ø1 mm pilot hole")
    report = {p["name"]: p["pivot"] for p in d.report()["parts"]}
    assert report["body"]["marked_by"] == "bore" and report["roller"] == {
        "marked_by": "pilot",
        "diameter": 1.0,
        "cross": pytest.approx(roller.pivot_mark),
    }
    text = unescape((out / "roller_body_m3" / "index.html").read_text(encoding="utf-8"))
    assert "Pivot: Ø8 mm bore and engraved cross" in re.sub(r"<[^>]+>", "", text)
    assert "roller × 3" in text  # placed three times


def test_index_links_every_profile(site):
    out, designs = site
    checker = check_page(out / "index.html")
    assert {link for link in checker.links if link.endswith(".html")} == {f"{name}/index.html" for name in designs}
    assert "rolling_wheel/assembly.svg" in checker.links  # a picture of its parts (not a chart)
    text = " ".join(checker.text)
    assert "paper-formula" in text and all(d.params.title in unescape(text) for d in designs.values())


def chromium(url: str, png: Path, tmp: Path, size=(1200, 1600)) -> str:
    """Render ``url`` headless into ``png``; return chromium's log."""
    profile_dir = tmp / f"chromium-{png.stem}"
    run = subprocess.run(
        [
            CHROMIUM,
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--enable-logging=stderr",
            "--v=0",
            f"--user-data-dir={profile_dir}",
            f"--screenshot={png}",
            f"--window-size={size[0]},{size[1]}",
            url,
        ],
        capture_output=True,
        text=True,
        timeout=60,
        env={**os.environ, "HOME": str(tmp)},
    )
    assert run.returncode == 0, run.stderr[-2000:]
    return run.stderr


@pytest.mark.skipif(
    not Path(CHROMIUM).is_file(), reason="no chromium: install it with `apt-get install -y chromium` (Debian)"
)
@pytest.mark.parametrize("page", ["rolling_wheel/index.html", "index.html"])
def test_pages_render_in_a_headless_browser(built, tmp_path, page):
    """The pages as the build writes them, with every chart and picture."""
    png = tmp_path / "page.png"
    log = chromium((built / page).as_uri(), png, tmp_path)
    # the page has no script, so any console message (chromium logs them as CONSOLE) is a fault
    assert not [line for line in log.splitlines() if "CONSOLE" in line or "Uncaught" in line]
    image = Image.open(png).convert("RGB")
    assert image.size == (1200, 1600)
    colours = image.getcolors(maxcolors=1 << 16)
    assert colours is None or len(colours) > 16  # text, drawings and rules, not a blank page
