"""The stylesheet of gearcad's HTML reports: system fonts only, nothing fetched."""

from html import escape

__all__ = ["CSS", "FILLS", "page"]

FILLS = 6
"""Part colours the stylesheet defines for drawings: classes ``f0`` … ``f5``."""

CSS = """
:root { --ink: #1d2330; --muted: #5b6475; --line: #d8dde6; --soft: #f4f6f9; --cut: #d1242f;
  --mark: #1f5fbf; --pivot: #0a7d32; --warn: #b35900; --ok: #1a7f37; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--ink); background: #fff; line-height: 1.45;
  font: 15px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, sans-serif; }
main { max-width: 1140px; margin: 0 auto; padding: 24px 28px 48px; }
header { border-bottom: 1px solid var(--line); padding-bottom: 14px; margin-bottom: 8px; }
h1 { font-size: 26px; margin: 0 0 4px; line-height: 1.25; }
h2 { font-size: 19px; margin: 30px 0 10px; padding-bottom: 4px; border-bottom: 1px solid var(--line); }
h3 { font-size: 15px; margin: 14px 0 6px; }
a { color: #0b57d0; text-decoration: none; } a:hover { text-decoration: underline; }
.sub { color: var(--muted); margin: 0 0 10px; }
.summary { font-family: ui-monospace, "SFMono-Regular", Menlo, Consolas, monospace; font-size: 13.5px;
  background: var(--soft); border-left: 3px solid var(--mark); padding: 8px 12px; margin: 8px 0; }
.badges span { display: inline-block; border-radius: 999px; padding: 2px 10px; margin: 2px 6px 2px 0;
  font-size: 13px; background: var(--soft); border: 1px solid var(--line); }
.count { display: inline-block; min-width: 26px; text-align: center; border-radius: 999px; padding: 0 8px;
  border: 1px solid var(--line); }
.badges .bad, .count.bad { background: #fff4e5; border-color: #f0c48a; color: var(--warn); }
.badges .good, .count.good { background: #eaf6ec; border-color: #a8d5b0; color: var(--ok); }
nav { font-size: 14px; margin: 10px 0 0; } nav a { margin-right: 14px; }
.legend { font-size: 13px; color: var(--muted); margin: 4px 0 10px; }
.legend i { display: inline-block; width: 18px; height: 0; border-top: 2px solid; vertical-align: middle;
  margin: 0 4px 0 10px; }
.cards { display: grid; grid-template-columns: repeat(auto-fill, minmax(250px, 1fr)); gap: 14px; }
.card { border: 1px solid var(--line); border-radius: 8px; padding: 10px 12px; background: #fff; }
.card svg { display: block; width: 100%; height: 230px; background: var(--soft); border-radius: 4px; }
.card h3 { margin: 8px 0 2px; } .card p { margin: 2px 0; font-size: 13.5px; }
.pivot-note { color: var(--pivot); } .pivot-note.none { color: var(--warn); }
.pair { display: grid; grid-template-columns: 3fr 2fr; gap: 14px; align-items: start; }
.wide svg { display: block; width: 100%; height: auto; max-height: 520px; background: var(--soft);
  border-radius: 4px; }
.pair img { width: 100%; border: 1px solid var(--line); border-radius: 4px; }
figure { margin: 0; } figcaption { font-size: 13px; color: var(--muted); margin-top: 4px; }
.charts { display: grid; grid-template-columns: 1fr; gap: 18px; }
.charts img { display: block; width: auto; max-width: 100%; border: 1px solid var(--line); border-radius: 4px; }
table { border-collapse: collapse; font-size: 13.5px; margin: 4px 0 10px; }
th, td { text-align: left; padding: 4px 10px 4px 0; border-bottom: 1px solid var(--line); vertical-align: top; }
th { color: var(--muted); font-weight: 600; }
td.num { font-variant-numeric: tabular-nums; text-align: right; }
table.kv th { font-weight: normal; }
.code { font-family: ui-monospace, Menlo, Consolas, monospace; font-size: 12.5px; background: #fff4e5;
  color: var(--warn); border: 1px solid #f0c48a; border-radius: 4px; padding: 0 5px; white-space: nowrap; }
ul.lines { font-family: ui-monospace, Menlo, Consolas, monospace; font-size: 13px; padding-left: 18px; }
details { border: 1px solid var(--line); border-radius: 6px; padding: 6px 12px; margin: 8px 0; }
details > summary { cursor: pointer; font-weight: 600; }
.note { font-size: 13.5px; color: var(--muted); }
.nowrap { white-space: nowrap; }
td.thumb { width: 170px; } img.thumb { display: block; width: 160px; max-height: 110px; object-fit: contain;
  border: 1px solid var(--line); border-radius: 4px; background: #fff; }
.ok { color: var(--ok); } .bad { color: var(--warn); }
footer { margin-top: 36px; font-size: 12.5px; color: var(--muted); border-top: 1px solid var(--line);
  padding-top: 10px; }
svg .part { stroke: var(--cut); stroke-width: 1.3px; }
svg .mark { fill: none; stroke: var(--mark); stroke-width: 0.9px; }
svg .pv { fill: none; stroke: var(--pivot); stroke-width: 2px; }
svg .frame { fill: #fff; stroke: #9aa3b2; stroke-width: 1px; }
svg .f0 { fill: #dbe8f6; } svg .f1 { fill: #fde2c8; } svg .f2 { fill: #d9f0d3; }
svg .f3 { fill: #eadcf5; } svg .f4 { fill: #fbe3e8; } svg .f5 { fill: #fff3bf; }
@media (max-width: 760px) { .pair { grid-template-columns: 1fr; } }
"""


def page(title: str, body: str) -> str:
    """A whole, self-contained HTML page: the stylesheet inline, nothing fetched."""
    return (
        '<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n'
        '<meta name="viewport" content="width=device-width, initial-scale=1">\n'
        f"<title>{escape(title)}</title>\n<style>{CSS}</style>\n</head>\n<body>\n<main>\n{body}\n</main>\n"
        "</body>\n</html>\n"
    )
